// The local pose sensor's JSS service: Local Pose Sensor 1.0 on the RA local
// pose sensor (docs/jss.md, "Sensors"). Listed for the node host by
// jaus_jss_translators() (this folder's CMakeLists.txt).
#pragma once

#include "jaus/jss_face/translator.hpp"

namespace jaus::components_jss {

// Its translators, for the JSS face (jss_face::TranslatorFactory).
jss_face::Translators local_pose_sensor_translators(const jss_face::FaceConfig& config);

}  // namespace jaus::components_jss
