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
#include "jaus/wire/message.hpp"

namespace jaus::jss_face {

std::unique_ptr<ServiceTranslator> make_transport_events_translator();
std::unique_ptr<ServiceTranslator> make_discovery_translator(const FaceConfig& config);
std::unique_ptr<ServiceTranslator> make_liveness_translator();
std::unique_ptr<ServiceTranslator> make_access_control_translator();
std::unique_ptr<ServiceTranslator> make_management_translator();

inline ServiceUri core_service(const char* name) { return ServiceUri{std::string("urn:jaus:jss:core:") + name, 1, 1}; }

// The JSS message M a client sent; nullopt (counted and logged as
// malformed) when its body is not M's.
template <class M>
std::optional<M> decode_jss(const JssInbound& m, FacePort& port) {
  auto decoded = jss::decode_body<M>(m.body);
  if (!decoded) {
    port.malformed(std::string(M::name) + " from " + m.origin.client.to_string(), decoded.error().message());
    return std::nullopt;
  }
  return std::move(*decoded);
}

// Sends a JSS message from our component (a value out of its field's range
// is our bug: logged, never sent).
template <class M>
void reply_jss(FacePort& port, const ReplyTo& to, const jss::JssId& from, const M& message) {
  auto contents = jss::try_encode_contents(message);
  if (!contents) {
    port.log(rt::LogLevel::error, std::string(M::name) + " to " + to.client.to_string() +
                                      " not encoded: " + contents.error().message());
    return;
  }
  port.reply(to, from, *contents);
}

// The RA message M a component sent to a client's alias (nullopt: not M's layout).
template <class M>
std::optional<M> decode_ra(const RaOutbound& m) {
  auto decoded = wire::decode_payload<M>(m.payload);
  if (!decoded) return std::nullopt;
  return std::move(*decoded);
}

}  // namespace jaus::jss_face
