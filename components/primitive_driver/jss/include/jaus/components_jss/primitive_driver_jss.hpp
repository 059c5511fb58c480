// The primitive driver's JSS service: Primitive Driver 1.0 on the RA
// primitive driver (docs/jss.md, "Primitive Driver"). Listed for the node
// host by jaus_jss_translators() (this folder's CMakeLists.txt).
#pragma once

#include "jaus/jss/all.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::components_jss {

// Its translators, for the JSS face (jss_face::TranslatorFactory).
jss_face::Translators primitive_driver_translators(const jss_face::FaceConfig& config);

// JSS Set Wrench Effort as RA takes it: the six propulsive efforts rescaled,
// within one JSS step of 0 exactly 0; resistive efforts and presence copied.
msg::SetWrenchEffort wrench_effort_to_ra(const jss::msg::SetWrenchEffort& jss);

}  // namespace jaus::components_jss
