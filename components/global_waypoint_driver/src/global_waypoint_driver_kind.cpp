#include "jaus/components/global_waypoint_driver_kind.hpp"

#include "jaus/components/global_waypoint_driver.hpp"
#include "jaus/components/mobility_driver_kind.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& global_waypoint_driver_kind() {
  static const rt::ComponentKind kind = mobility_driver_kind<GlobalWaypointDriver>(
      "global_waypoint_driver", component_id::kGlobalWaypointDriver, waypoint_driver_option_keys(),
      waypoint_driver_options, DriverFrame::any);
  return kind;
}

}  // namespace jaus::components
