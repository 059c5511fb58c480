// The local waypoint driver (component 46): Set Local Waypoint and Set
// Travel Speed; Waypoint Count, Local Waypoint and Travel Speed reports. The
// waypoints are in the pose source's local frame (the local pose sensor's:
// origin at the vehicle's start, x north, y east); z, roll, pitch and yaw are
// stored and echoed, not followed.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "jaus/components/waypoint_driver.hpp"

namespace jaus::components {

struct LocalWaypoints {
  using Body = msg::LocalWaypointBody;
  using Set = msg::SetLocalWaypoint;
  using Query = msg::QueryLocalWaypoint;
  using Report = msg::ReportLocalWaypoint;
  static constexpr std::string_view kWhat = "local waypoint";

  // The pose source's own local frame, whatever the vehicle's start.
  struct Frame {
    static Expected<Frame> at(const PoseSample& start) {
      if (!start.local_position)
        return unexpected(make_error(ErrorCode::invalid_argument,
                                     "the pose source gives no local position (vehicle.local_frame: true)"));
      return Frame{};
    }
    std::optional<guidance::Point2> vehicle(const PoseSample& pose) const {
      if (!pose.local_position) return std::nullopt;
      return guidance::Point2{pose.local_position->x_m, pose.local_position->y_m};
    }
    guidance::Point2 point(const Body& waypoint) const { return {waypoint.x_m, waypoint.y_m}; }
  };
};

using LocalWaypointDriver = WaypointDriver<LocalWaypoints>;

}  // namespace jaus::components
