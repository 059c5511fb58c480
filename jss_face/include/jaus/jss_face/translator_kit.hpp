// The translator kit: what service translators share (translator.hpp;
// docs/jss.md, "The translator kit"): decoding and encoding on both sides,
// reading an RA component in process (never commanding through it), and a
// rate-limited log for what remote input repeats. The face's core services
// use it, and so does every component kind's JSS library
// (components/<name>/jss/).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/contents.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::jss_face {

// Whether a JSS message ID is one of Ms' (a translator's handles(): the
// messages it takes, listed once as types).
template <class... Ms>
constexpr bool is_one_of(std::uint16_t message_id) {
  return ((message_id == Ms::code) || ...);
}

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

namespace jaus::jss_face::kit {

// An RA message's payload (no header).
template <class M>
Expected<std::vector<std::uint8_t>> encode_ra(const M& message) {
  std::array<std::uint8_t, kMaxPayloadSize> buffer{};
  auto size = wire::encode_payload(message, buffer);
  if (!size) return unexpected(size.error());
  return std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*size));
}

template <class M>
Expected<M> decode_ra(std::span<const std::uint8_t> payload) {
  return wire::decode_payload<M>(payload);
}

// A JSS message's body (the contents after the message ID).
template <class M>
Expected<M> decode_jss_body(std::span<const std::uint8_t> body) {
  return jss::decode_body<M>(body);
}

// What a translator says about the JSS client that asked.
inline std::string who(const JssInbound& m) {
  return m.origin.client.to_string() + " -> " + m.our_component.to_string();
}

// The same in a refusal line: the client by its JSS ID, host and alias.
inline std::string who(const JssInbound& m, const FacePort& port) {
  return port.describe_client(m.origin.client) + " -> " + m.our_component.to_string();
}

// The rate-limited log of one translator: made on first use on the face's
// clock and scheduler (the port is the face's, for the face's life).
class TranslatorLog {
 public:
  template <class MakeText>
  void repeated(FacePort& port, rt::Repeated kind, rt::LogLevel level, MakeText make_text) {
    if (!lines_) {
      FacePort* p = &port;
      lines_ = std::make_unique<rt::RepeatedLines>(
          port.clock(), port.scheduler(), [p](rt::LogLevel l, const std::string& text) { p->log(l, text); });
    }
    lines_->write(kind, level, make_text);
  }

 private:
  std::unique_ptr<rt::RepeatedLines> lines_;
};

// Sends an RA message to our component as the client's alias.
template <class M>
void send_ra(FacePort& port, const JssInbound& from, const M& message, TranslatorLog& log) {
  auto payload = encode_ra(message);
  if (!payload) {
    log.repeated(port, "RA messages not encoded", rt::LogLevel::error, [&] {
      return std::string(M::name) + " for " + who(from) + " not encoded: " + payload.error().message();
    });
    return;
  }
  port.send_ra(from.origin, from.ra_component, M::code, *payload, from.standing);
}

// reply_jss (a JSS message from our component), as above.
using jaus::jss_face::reply_jss;

// A JSS body that did not decode: the face counts and logs it; never acted on.
inline void log_malformed(FacePort& port, const JssInbound& m, std::string_view what, const Error& error) {
  port.malformed(std::string(what) + " from " + who(m), error.message());
}

// The RA component behind a JSS one, read in process.
inline const rt::Component* ra_component(FacePort& port, const Address& address) {
  return port.node().find(address);
}

// Whether the client that sent `m` controls the RA component (its alias is
// the controller): what a translator asks before it changes state the RA
// has no message for.
inline bool client_controls(FacePort& port, const Address& ra, const jss::JssId& client) {
  const rt::Component* component = ra_component(port, ra);
  if (component == nullptr) return false;
  const auto& controller = component->control().controller();
  if (!controller || controller->address.subsystem != port.config().client_alias_subsystem) return false;
  return port.jss_id_for(controller->address) == client;
}
inline bool client_controls(FacePort& port, const JssInbound& m) {
  return client_controls(port, m.ra_component, m.origin.client);
}

}  // namespace jaus::jss_face::kit
