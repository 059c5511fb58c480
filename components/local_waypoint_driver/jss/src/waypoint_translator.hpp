// The translators of the RA local waypoint driver's JSS component: Local
// Waypoint Driver (waypoint_translator.cpp) and List Manager + Local Waypoint
// List Driver (list_driver_translator.cpp), sharing one WaypointDrivers.
#pragma once

#include <memory>

#include "jaus/jss_face/translator.hpp"

namespace jaus::components_jss {

class WaypointDrivers;

std::unique_ptr<jss_face::ServiceTranslator> make_local_waypoint_driver_translator(
    std::shared_ptr<WaypointDrivers> drivers);
std::unique_ptr<jss_face::ServiceTranslator> make_list_driver_translator(std::shared_ptr<WaypointDrivers> drivers);

}  // namespace jaus::components_jss
