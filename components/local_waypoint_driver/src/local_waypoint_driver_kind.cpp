#include "jaus/components/local_waypoint_driver_kind.hpp"

#include "jaus/components/local_waypoint_driver.hpp"
#include "jaus/components/mobility_driver_kind.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

// Its elements are in the vehicle's local frame: a pose source without one is refused.
const rt::ComponentKind& local_waypoint_driver_kind() {
  static const rt::ComponentKind kind = mobility_driver_kind<LocalWaypointDriver>(
      "local_waypoint_driver", component_id::kLocalWaypointDriver, waypoint_driver_option_keys(),
      waypoint_driver_options, DriverFrame::local, {rt::operator_view::kWaypoints});
  return kind;
}

}  // namespace jaus::components
