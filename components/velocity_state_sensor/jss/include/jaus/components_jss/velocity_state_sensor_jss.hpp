// The velocity state sensor's JSS service: Velocity State Sensor 1.0 on the
// RA velocity state sensor (docs/jss.md, "Sensors"). Listed for the node
// host by jaus_jss_translators() (this folder's CMakeLists.txt).
#pragma once

#include "jaus/jss_face/translator.hpp"

namespace jaus::components_jss {

// Its translators, for the JSS face (jss_face::TranslatorFactory).
jss_face::Translators velocity_state_sensor_translators(const jss_face::FaceConfig& config);

}  // namespace jaus::components_jss
