// The global waypoint driver (component 45): Set Global Waypoint and Set
// Travel Speed; Waypoint Count, Global Waypoint and Travel Speed reports.
// The route is followed in a local frame (x north, y east) whose datum is
// the vehicle's geodetic position when the motion starts: the waypoints'
// latitude and longitude and the vehicle's position are projected into it
// (GeographicLib's LocalCartesian, local_frame.hpp). Elevation, roll, pitch
// and yaw are stored and echoed, not followed.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "jaus/components/local_frame.hpp"
#include "jaus/components/waypoint_driver.hpp"

namespace jaus::components {

struct GlobalWaypoints {
  using Body = msg::GlobalWaypointBody;
  using Set = msg::SetGlobalWaypoint;
  using Query = msg::QueryGlobalWaypoint;
  using Report = msg::ReportGlobalWaypoint;
  static constexpr std::string_view kWhat = "global waypoint";

  class Frame {
   public:
    // Datum: the vehicle's position in `start` (an error without one).
    static Expected<Frame> at(const PoseSample& start);
    std::optional<guidance::Point2> vehicle(const PoseSample& pose) const;
    guidance::Point2 point(const Body& waypoint) const;

   private:
    explicit Frame(LocalFrame frame) : frame_(std::move(frame)) {}
    LocalFrame frame_;
  };
};

using GlobalWaypointDriver = WaypointDriver<GlobalWaypoints>;

}  // namespace jaus::components
