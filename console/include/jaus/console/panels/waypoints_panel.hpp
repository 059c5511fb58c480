// The Waypoints panel: a route clicked on the map loaded into a local
// waypoint driver (Standby, Set Travel Speed, the list); Resume (the Control
// panel's `state`) drives it.
#pragma once

#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class WaypointsPanel final : public Panel {
 public:
  using Panel::Panel;

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kWaypoints}; }
  void on_frame(PageId page, const WaypointsFrame& frame);
};

}  // namespace jaus::console
