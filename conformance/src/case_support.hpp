// What the cases share: verdicts, and sending and asking through the session
// with every message recorded in the case's exchange (the runner records
// what comes back). Private to the conformance library.
#pragma once

#include <string>
#include <vector>

#include "jaus/conform/conformance_case.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::conform::detail {

inline CaseOutcome pass(std::string detail) { return {Verdict::pass, std::move(detail)}; }
inline CaseOutcome fail(std::string detail) { return {Verdict::fail, std::move(detail)}; }
// The case cannot judge this component as it found it (not Ready, control
// not granted): neither pass nor fail.
inline CaseOutcome skip(std::string why) { return {Verdict::skip, std::move(why)}; }

// Sends `message` to `to` from `from` (the runner's session or its second
// OCU) and records it.
template <class M>
void send_from(CaseContext& c, ocu::OcuSession& from, const Address& to, const M& message,
               std::uint8_t priority = priority::kDefault) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(message, payload);
  payload.resize(size ? *size : 0);
  Header h;
  h.command_code = M::code;
  h.priority = priority;
  h.source = from.self();
  h.destination = to;
  h.data_size = static_cast<std::uint16_t>(payload.size());
  c.exchange.push_back(
      Exchanged{true, h, std::move(payload), c.session.clock().now() - c.started, &from != &c.session});
  from.send(to, message, priority);
}
// Sends `message` to `to` from the OCU and records it.
template <class M>
void send(CaseContext& c, const Address& to, const M& message, std::uint8_t priority = priority::kDefault) {
  send_from(c, c.session, to, message, priority);
}
template <class M>
void send(CaseContext& c, const M& message, std::uint8_t priority = priority::kDefault) {
  send(c, c.target(), message, priority);
}

// Decodes a received payload as R, in the session's dialect.
template <class R>
Expected<R> decode(CaseContext& c, const ocu::Received& received) {
  R report{};
  if (auto decoded = wire::decode_payload_into(received.payload, report, c.session.options().dialect, kHeaderSize);
      !decoded) {
    std::string why(R::name);
    why += " does not decode: ";
    why += decoded.error().message();
    return unexpected(make_error(ErrorCode::malformed, std::move(why)));
  }
  return report;
}

// The next message from the target with one of `codes`.
inline Expected<ocu::Received> await(CaseContext& c, std::vector<std::uint16_t> codes) {
  return c.session.await_reply(c.target(), std::move(codes), c.reply_timeout);
}

// The next message from the target to `at` (the runner or its second OCU)
// with one of `codes`.
inline Expected<ocu::Received> await_at(CaseContext& c, ocu::OcuSession& at, std::vector<std::uint16_t> codes) {
  return at.await_reply(c.target(), std::move(codes), c.reply_timeout);
}

// Sends `query` to the target from `from`, waits for its reply R and decodes it.
template <class R, class Q>
Expected<R> ask_from(CaseContext& c, ocu::OcuSession& from, const Q& query) {
  send_from(c, from, c.target(), query);
  auto reply = await_at(c, from, {R::code});
  if (!reply) return unexpected(reply.error());
  return decode<R>(c, *reply);
}

// Sends `query` to the target, waits for a reply R and decodes it.
template <class R, class Q>
Expected<R> ask(CaseContext& c, const Q& query) {
  send(c, query);
  auto reply = await(c, {R::code});
  if (!reply) return unexpected(reply.error());
  return decode<R>(c, *reply);
}

// "not listed in its Report Services" reasons for not_applicable.
inline std::string unless_accepts(const ComponentUnderTest& component, std::uint16_t code, std::string_view what) {
  if (!component.services_known) return "its services are unknown (no Report Services)";
  return component.accepts(code) ? std::string() : "it does not accept " + std::string(what);
}
inline std::string unless_provides(const ComponentUnderTest& component, std::uint16_t code, std::string_view what) {
  if (!component.services_known) return "its services are unknown (no Report Services)";
  return component.provides(code) ? std::string() : "it provides no " + std::string(what);
}

}  // namespace jaus::conform::detail
