// The core services' translators (AS5710 core v1.1), one file each;
// core_translators() (core_translators.cpp) registers them in this order.
// What they read and write are the codec's JSS messages (jaus/jss/messages)
// and the RA messages (jaus/messages): described once, nowhere else.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "jaus/core/component_ids.hpp"
#include "jaus/jss/contents.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/jss_face/translator_kit.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::jss_face {

std::unique_ptr<ServiceTranslator> make_transport_events_translator();
std::unique_ptr<ServiceTranslator> make_discovery_translator(const FaceConfig& config);
std::unique_ptr<ServiceTranslator> make_liveness_translator();
std::unique_ptr<ServiceTranslator> make_access_control_translator();
std::unique_ptr<ServiceTranslator> make_management_translator();

inline ServiceUri core_service(const char* name) { return ServiceUri{std::string("urn:jaus:jss:core:") + name, 1, 1}; }

// Transport and Events (listed on every component; the face itself does the
// transport and runs the events), Access Control, Management, Liveness,
// Discovery, in the order they are asked: the first translator whose
// from_jss()/from_ra() returns true wins. A kind's own services come after
// them (JssFace's constructor).
Translators core_translators(const FaceConfig& config);

}  // namespace jaus::jss_face
