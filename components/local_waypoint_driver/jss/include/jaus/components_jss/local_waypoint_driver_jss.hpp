// The local waypoint driver's JSS services, one JSS component: Local
// Waypoint Driver 1.0, List Manager 1.0 and Local Waypoint List Driver 1.0
// on the RA local waypoint driver (docs/jss.md, "Local Waypoint Driver (one
// waypoint)", "List Manager and Local Waypoint List Driver"). Listed for the
// node host by jaus_jss_translators() (this folder's CMakeLists.txt).
#pragma once

#include <cstdint>

#include "jaus/jss/all.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::components_jss {

// Its translators, for the JSS face (jss_face::TranslatorFactory): the
// waypoint driver's, then the list manager's and list driver's, sharing the
// state the face keeps per RA driver (waypoint_driver_state.hpp).
jss_face::Translators local_waypoint_driver_translators(const jss_face::FaceConfig& config);

// A JSS local waypoint as RA waypoint `number`: X, Y, angles with JSS's
// near-zero made 0, Z clamped to RA's -10 km..35 km; the tolerances stay in
// the face (RA has none).
msg::SetLocalWaypoint local_waypoint_to_ra(const jss::msg::SetLocalWaypoint& jss, std::uint16_t number);

}  // namespace jaus::components_jss
