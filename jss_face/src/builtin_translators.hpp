// The service translators the face registers on every node (face.cpp):
// the core services (core_translators.cpp) and the mobility services
// (mobility_translators.cpp). Each returns them in the order they are asked:
// the first translator whose from_jss()/from_ra() returns true wins.
#pragma once

#include <memory>
#include <vector>

#include "jaus/jss_face/face.hpp"
#include "jaus/jss_face/translator.hpp"

namespace jaus::jss_face {

using Translators = std::vector<std::unique_ptr<ServiceTranslator>>;

// Transport and Events (listed on every component; the face itself does the
// transport and runs the events), Access Control, Management, Liveness,
// Discovery.
Translators core_translators(const FaceConfig& config);
// Primitive Driver, the pose and velocity sensors, the waypoint drivers, the
// list manager.
Translators mobility_translators(const FaceConfig& config);

}  // namespace jaus::jss_face
