// The core services' translators (AS5710 core v1.1), one file each;
// core_translators() (core_translators.cpp) registers them in this order.
#pragma once

#include <memory>

#include "jaus/jss_face/face.hpp"
#include "jaus/jss_face/translator.hpp"

namespace jaus::jss_face {

inline constexpr std::uint8_t kNodeManagerId = 1;  // the RA node manager: Discovery, no control

std::unique_ptr<ServiceTranslator> make_transport_events_translator();
std::unique_ptr<ServiceTranslator> make_discovery_translator(const FaceConfig& config);
std::unique_ptr<ServiceTranslator> make_liveness_translator();
std::unique_ptr<ServiceTranslator> make_access_control_translator();
std::unique_ptr<ServiceTranslator> make_management_translator();

inline ServiceUri core_service(const char* name) { return ServiceUri{std::string("urn:jaus:jss:core:") + name, 1, 1}; }

}  // namespace jaus::jss_face
