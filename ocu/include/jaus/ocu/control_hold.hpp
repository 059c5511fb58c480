// Control of one component by the OCU: request it, hold it, release it.
//
// Holding needs no traffic of its own: the controlled component checks its
// controller with Query Component Status (every controller timeout / 3), and
// the OCU component, being an rt::Component, answers those by itself; the
// OCU's node manager heartbeats keep its node alive on the other side.
// Like other OCUs (jaus-wire-notes.md), the hold watches the component's
// Report Component Status on a 5 Hz service connection (at the send rate
// when faster, see send_while_held): it shows state changes, and silence
// means the component (or its node) is gone. Control also ends with Reject
// Component Control (taken over, or dropped).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/service_connection_client.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::ocu {

class ControlHold {
 public:
  enum class Outcome { granted, refused, rejected, no_reply, interrupted };
  struct RequestResult {
    Outcome outcome = Outcome::no_reply;
    std::uint8_t response_code = 0;  // of Confirm Component Control (refused)
    std::optional<jaus::Error> error;  // no_reply (timeout), interrupted, or a confirmation that does not decode
  };
  // not_ready: a command was being repeated (send_while_held, WhenNotReady::end_hold)
  // and the component reported a state other than Ready. unwatched: it refused
  // the status service connection, so nothing may be repeated to it.
  enum class End { time_up, interrupted, rejected, silent, not_ready, unwatched };
  // What repeating a command does while the component is not Ready.
  enum class WhenNotReady {
    end_hold,  // the hold ends (End::not_ready): whoever clears the state does not restart the motion
    pause,     // the hold goes on; sending starts again when the component is Ready (unsafe for motion)
  };

  // Silence of the status reports that ends a hold (when the component provides them).
  static constexpr jaus::rt::Duration kStatusSilence = std::chrono::seconds(5);

  ControlHold(OcuSession& session, const jaus::Address& target, std::uint8_t authority,
              jaus::rt::Duration status_silence = kStatusSilence);
  // Ends the status service connection.
  ~ControlHold();
  ControlHold(const ControlHold&) = delete;
  ControlHold& operator=(const ControlHold&) = delete;

  // Request Component Control; waits for Confirm or Reject Component Control.
  RequestResult request(jaus::rt::Duration timeout);
  // Runs the session while control is held: until `limit` (none: until
  // interrupted) or control is lost. `on_state` hears the component's
  // primary status when first reported and on every change ("Ready",
  // "Ready -> Emergency").
  End hold(std::optional<jaus::rt::Duration> limit, std::function<void(const std::string&)> on_state = {});
  // While held, sends `message` (header code and payload; the destination is
  // the target) every `period` while the component reports Ready: a driving
  // OCU repeats its Set Wrench Effort so that the driver's command timeout
  // never stops it while the operator holds the stick. Safety: nothing is
  // sent before the component has reported Ready, nor once it has reported
  // any other state (Emergency, Standby, Failure, ...): the hold ends then, or
  // with WhenNotReady::pause waits for Ready again. (Only Initialize before
  // the first Ready, a component still starting, is waited for either way.)
  // A component that refuses
  // the status service connection gets nothing (End::unwatched). The status
  // comes at least as often as the commands go, so a state is acted on within
  // a period. Nothing is sent after the hold ends.
  // `on_sending` hears when sending starts (true) and pauses (false).
  void send_while_held(PreparedMessage message, jaus::rt::Duration period,
                       WhenNotReady when_not_ready = WhenNotReady::end_hold,
                       std::function<void(bool sending)> on_sending = {});
  std::uint64_t sent_while_held() const { return sent_while_held_; }
  // The primary status last reported (bits 0-3), none before the first report.
  std::optional<std::uint8_t> state() const { return state_; }

  // Release Component Control (fire and forget: the RA has no reply to it)
  // and end the status service connection.
  void release();

  // Who has control now (Query Component Control), asked after a Reject:
  // none without a reply; a controller that is not a valid address means nobody.
  std::optional<jaus::msg::ReportComponentControl> who_has_control(jaus::rt::Duration timeout);

  // Liveness checks (Query Component Status) the component sent us while held.
  std::uint64_t liveness_checks() const { return liveness_checks_; }

 private:
  void watch_status();
  void stop_watching_status();
  bool status_refused() const;
  bool left_ready() const;
  double status_rate_hz() const;
  // Sends the repeated command when it is due and the component is Ready;
  // returns when to look again.
  jaus::rt::TimePoint repeat(jaus::rt::TimePoint now);

  OcuSession& session_;
  jaus::Address target_;
  std::uint8_t authority_;
  jaus::rt::Duration status_silence_;
  OcuSession::ListenerId listener_ = 0;
  bool rejected_ = false;
  std::uint64_t liveness_checks_ = 0;
  std::optional<jaus::rt::SubscriptionId> status_sc_;
  std::optional<std::uint8_t> state_;  // last primary status reported
  jaus::rt::TimePoint status_heard_{};
  std::function<void(const std::string&)> on_state_;
  std::optional<PreparedMessage> repeated_;
  jaus::rt::Duration repeat_period_{};
  WhenNotReady when_not_ready_ = WhenNotReady::end_hold;
  std::function<void(bool)> on_sending_;
  bool sending_ = false;
  bool been_ready_ = false;  // since send_while_held()
  jaus::rt::TimePoint next_send_{};
  std::uint64_t sent_while_held_ = 0;
};

}  // namespace jaus::ocu
