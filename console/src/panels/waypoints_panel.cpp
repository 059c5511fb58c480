#include "jaus/console/panels/waypoints_panel.hpp"

#include "jaus/messages/all.hpp"

namespace jaus::console {

void WaypointsPanel::on_frame(PageId page, const WaypointsFrame& frame) {
  // A route drives when its driver goes from Standby to Ready (Resume):
  // Standby first, then the list, all while still its controller (control
  // is lost at the next status poll; `resume` takes it again).
  session().send(frame.target, jaus::msg::Standby{});
  session().send(frame.target, jaus::msg::SetTravelSpeed{{frame.speed_mps}});
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    jaus::msg::SetLocalWaypoint waypoint{};
    waypoint.waypoint_number = static_cast<std::uint16_t>(i);
    waypoint.x_m = frame.points[i].x;
    waypoint.y_m = frame.points[i].y;
    session().send(frame.target, waypoint);
  }
  pages().event(EventLevel::info, "loaded " + std::to_string(frame.points.size()) + " waypoint(s) into " +
                                      frame.target.to_string() + " at " + std::to_string(frame.speed_mps) +
                                      " m/s (page " + std::to_string(page) + ")");
}

}  // namespace jaus::console
