// local_waypoint_driver_translators(): the three services of the RA local
// waypoint driver's JSS component, in the order the face asks them.
#include "jaus/components_jss/local_waypoint_driver_jss.hpp"

#include <memory>

#include "waypoint_driver_state.hpp"
#include "waypoint_translator.hpp"

namespace jaus::components_jss {

jss_face::Translators local_waypoint_driver_translators(const jss_face::FaceConfig&) {
  jss_face::Translators translators;
  // One JSS component, three services: the waypoint state is theirs together.
  auto waypoint_drivers = std::make_shared<WaypointDrivers>();
  translators.push_back(make_local_waypoint_driver_translator(waypoint_drivers));
  translators.push_back(make_list_driver_translator(waypoint_drivers));
  return translators;
}

}  // namespace jaus::components_jss
