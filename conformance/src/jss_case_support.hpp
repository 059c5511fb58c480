// What the JSS cases share: sending and asking through a JssSession with
// every message recorded in the case's exchange (the runner records what
// comes back), control held for a case and always released, and the
// component's management status. Private to the conformance library.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "case_support.hpp"
#include "jaus/conform/jss_case.hpp"
#include "jaus/jss/all.hpp"

namespace jaus::conform::jss_detail {

using detail::fail;
using detail::pass;
using detail::skip;

inline Exchanged sent_record(JssCaseContext& c, const jss::JssId& to, std::span<const std::uint8_t> contents,
                             bool by_second) {
  Exchanged e;
  e.sent = true;
  e.header.command_code = jss::message_id_of(contents);
  if (contents.size() > 2) e.payload.assign(contents.begin() + 2, contents.end());
  e.at = c.session.clock().now() - c.started;
  e.second = by_second;
  e.jss_peer = to;
  return e;
}

// Sends `message` from `from` (the runner's session or its second client) to `to`, recorded.
template <class M>
void send_from(JssCaseContext& c, ocu::JssSession& from, const jss::JssId& to, const M& message,
               jss::JudpPriority priority = jss::JudpPriority::normal) {
  const auto contents = jss::encode_contents(message);
  c.exchange.push_back(sent_record(c, to, contents, &from != &c.session));
  from.send_contents(to, contents, priority);
}
template <class M>
void send(JssCaseContext& c, const M& message, jss::JudpPriority priority = jss::JudpPriority::normal) {
  send_from(c, c.session, c.target(), message, priority);
}

// The first message from the target to `to` with one of `ids`, within the reply timeout.
inline Expected<ocu::JssReceived> await_from(JssCaseContext& c, ocu::JssSession& to, std::vector<std::uint16_t> ids,
                                             std::optional<rt::Duration> timeout = std::nullopt) {
  return to.await_reply(c.target(), std::move(ids), timeout.value_or(c.reply_timeout));
}

template <class R>
Expected<R> decode(const ocu::JssReceived& received) {
  auto decoded = jss::decode_contents<R>(received.contents);
  if (!decoded) {
    std::string why(R::name);  // appended, not concatenated: gcc 12's -Warray-bounds false positive
    why += " does not decode: ";
    why += decoded.error().message();
    return unexpected(make_error(ErrorCode::malformed, std::move(why)));
  }
  return decoded;
}

// Sends `query` from `from` to the target, waits for a reply R and decodes it.
template <class R, class Q>
Expected<R> ask_from(JssCaseContext& c, ocu::JssSession& from, const Q& query,
                     std::optional<rt::Duration> timeout = std::nullopt) {
  send_from(c, from, c.target(), query);
  auto reply = await_from(c, from, {R::code}, timeout);
  if (!reply) return unexpected(reply.error());
  return decode<R>(*reply);
}
template <class R, class Q>
Expected<R> ask(JssCaseContext& c, const Q& query, std::optional<rt::Duration> timeout = std::nullopt) {
  return ask_from<R>(c, c.session, query, timeout);
}

// Messages with `id` from the target to `session`, heard from construction
// on (a reply may come while another session waits: both run on one loop).
class Heard {
 public:
  Heard(JssCaseContext& c, ocu::JssSession& session, std::uint16_t id) : session_(session) {
    listener_ = session.listen([this, id, target = c.target()](const ocu::JssReceived& r) {
      if (r.source() == target && r.message_id() == id) messages_.push_back(r);
    });
  }
  ~Heard() { session_.unlisten(listener_); }
  Heard(const Heard&) = delete;
  Heard& operator=(const Heard&) = delete;
  // The first one, waiting up to `timeout` for it.
  std::optional<ocu::JssReceived> first(rt::Duration timeout) {
    session_.run_until([&] { return !messages_.empty(); }, timeout);
    if (messages_.empty()) return std::nullopt;
    return messages_.front();
  }

 private:
  ocu::JssSession& session_;
  ocu::JssSession::ListenerId listener_ = 0;
  std::vector<ocu::JssReceived> messages_;
};

// Lets `d` pass, hearing what comes meanwhile.
inline void pause(JssCaseContext& c, rt::Duration d) { c.session.run_for(d); }

// The component's management status (Report Status, low nibble), or why not.
Expected<std::uint8_t> status_of(JssCaseContext& c);
std::string status_name(std::uint8_t status);
// Who controls the target (0.0.0 when nobody) and at what authority.
struct ControlSeen {
  jss::JssId controller;
  std::uint8_t authority = 0;
};
Expected<ControlSeen> control_of(JssCaseContext& c);

inline constexpr std::uint8_t kReady = 1;
inline constexpr std::uint8_t kStandby = 2;
inline constexpr std::uint8_t kEmergency = 5;
inline constexpr std::uint8_t kControlAccepted = 0;
inline constexpr std::uint8_t kInsufficientAuthority = 2;
inline constexpr std::uint8_t kControlReleased = 0;

// Control of the target for a case, by `who` (the runner or its second
// client) at `authority`: requested at construction (granted() says whether
// Confirm Control 0 came), released when it goes (Release Control, its
// Reject Control awaited briefly).
class JssControlHeld {
 public:
  JssControlHeld(JssCaseContext& c, ocu::JssSession& who, std::uint8_t authority);
  ~JssControlHeld();
  JssControlHeld(const JssControlHeld&) = delete;
  JssControlHeld& operator=(const JssControlHeld&) = delete;

  bool granted() const { return response_ && *response_ == kControlAccepted; }
  // "Confirm Control 2", "no Confirm Control within 1 s".
  std::string what() const { return what_; }
  // Request Control again at the same authority (keeps it alive).
  void renew();
  // Released already (by the case): nothing to do at the end.
  void forget() { held_ = false; }
  void release();

 private:
  JssCaseContext& c_;
  ocu::JssSession& who_;
  std::uint8_t authority_;
  std::optional<std::uint8_t> response_;
  std::string what_;
  bool held_ = false;
};

// Puts the target in `status` (Ready or Standby) with Resume / Standby from
// its controller, and checks it got there.
Expected<void> bring_to(JssCaseContext& c, std::uint8_t status);

// "not listed in its services" reasons for not_applicable.
inline std::string unless_has(const JssComponentUnderTest& component, std::string_view service) {
  if (!component.services_known) return "its services are unknown (it is in no Report Services)";
  return component.has(service) ? std::string() : "it lists no " + std::string(service) + " service";
}

// What a case that takes control first checks: nobody controls the target (the
// case would otherwise take it from someone), and the authority to request
// control at: the target's own (Query Authority), never refused as too low.
// `outcome` set: the case ends with it (fail: a query unanswered; skip:
// someone controls it).
struct FreeTarget {
  std::uint8_t authority = 0;
  std::optional<CaseOutcome> outcome;
};
FreeTarget free_target(JssCaseContext& c);

}  // namespace jaus::conform::jss_detail
