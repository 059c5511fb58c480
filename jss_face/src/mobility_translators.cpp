// The mobility translators the face registers (builtin_translators.hpp).
#include "mobility_translators.hpp"

#include "builtin_translators.hpp"
#include "waypoint_driver_state.hpp"
#include "waypoint_translator.hpp"

namespace jaus::jss_face {

Translators mobility_translators(const FaceConfig&) {
  Translators translators;
  translators.push_back(make_primitive_driver_translator());
  translators.push_back(make_velocity_state_translator());
  translators.push_back(make_local_pose_translator());
  translators.push_back(make_global_pose_translator());
  // One JSS component, three services: the waypoint state is theirs together.
  auto waypoint_drivers = std::make_shared<WaypointDrivers>();
  translators.push_back(make_local_waypoint_driver_translator(waypoint_drivers));
  translators.push_back(make_list_driver_translator(waypoint_drivers));
  return translators;
}

}  // namespace jaus::jss_face
