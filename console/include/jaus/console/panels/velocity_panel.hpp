// The velocities under the map: Report Velocity State of every velocity
// state sensor, to every page as `velocity`.
#pragma once

#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class VelocityPanel final : public Panel {
 public:
  using Panel::Panel;

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kVelocity}; }
  void follow(const jaus::Address& component, std::string_view view) override;
};

}  // namespace jaus::console
