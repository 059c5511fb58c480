// Control of one component by the OCU: request it, hold it, release it.
//
// The controlled component drops its controller after a silence of its
// controller timeout (3 s by default): any message from the OCU component
// counts, and it asks for one with Query Component Status every timeout / 3,
// which the OCU component, being an rt::Component, answers by itself. Over a
// lossy link those answers alone are not enough (at 30 % loss each way three
// query-answer pairs in a row are lost every few seconds), so while holding,
// the hold also sends a keepalive (Query Component Status, cheap and without
// effect) whenever nothing else went to the component for kKeepalive: a
// timeout passes only when a dozen datagrams in a row are lost. The first
// goes as soon as the hold begins, and until the status service connection's
// first report its answers count as status reports: the state is known at
// once even when the connection's creation was lost (its client creates it
// again after 1 s). The OCU's
// node manager heartbeats keep its node alive on the other side.
// Over loss, the request is sent again until answered, and the release goes
// with an ACK request, retransmitted until ACKed (must_arrive.hpp).
// A Reject Component Control can be lost too (sent once, when the component
// dropped us during a partition): every kControlCheck the hold asks Query
// Component Control, and an answer naming another controller (or none) ends
// the hold like a Reject, so a hold never goes on streaming refused commands.
// Like other OCUs (docs/wire-format.md, "Service connections"), the hold watches the component's
// Report Component Status on a 5 Hz service connection (at the send rate
// when faster, see send_while_held): it shows state changes, and silence
// means the component (or its node) is gone. A stop shorter than a report
// period still shows: the component sends its controller its status at once
// on every change, and every report carries a stop counter
// (jaus/runtime/stop_counter.hpp) that moves on every stop. Control also ends with Reject
// Component Control (taken over, or dropped).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/service_connection_client.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/repeated_query.hpp"
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
  // Longest time without a message to the component while holding: the
  // default controller timeout / 12.
  static constexpr jaus::rt::Duration kKeepalive = std::chrono::milliseconds(250);
  // Release Component Control: paced by the measured round trip until
  // ACKed, a second at most (clean-up after Ctrl-C).
  static constexpr MustArrivePolicy kReleasePolicy = MustArrivePolicy::cleanup();
  // How often the hold asks who has control.
  static constexpr jaus::rt::Duration kControlCheck = std::chrono::seconds(1);

  ControlHold(OcuSession& session, const jaus::Address& target, std::uint8_t authority,
              jaus::rt::Duration status_silence = kStatusSilence);
  // Ends the status service connection.
  ~ControlHold();
  ControlHold(const ControlHold&) = delete;
  ControlHold& operator=(const ControlHold&) = delete;

  // Request Component Control; waits for Confirm or Reject Component Control,
  // sending the request again every kQueryResendPeriod (a second request from
  // the controller changes nothing), so one lost datagram costs 250 ms.
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
  // A stop that came and went between two reports ends it too (stop_seen()).
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
  // The first stop the component reported once commands went (send_while_held):
  // a state other than Ready, or a Ready whose stop counter moved (a stop
  // that came and went between two reports, jaus/runtime/stop_counter.hpp).
  struct StopSeen {
    std::uint8_t state;           // the primary status it was reported with
    bool between_reports;         // only the stop counter showed it
    std::uint16_t stops_before;   // the stop counter before ...
    std::uint16_t stops_after;    // ... and in the report that showed the stop
  };
  const std::optional<StopSeen>& stop_seen() const { return stop_seen_; }

  // Release Component Control and end the status service connection. The RA
  // has no reply to it, so it goes with an ACK request, retransmitted until
  // ACKed (kReleasePolicy), also after a stop was requested: Ctrl-C releases.
  // Unacknowledged, the component's controller timeout ends the control
  // (and stops it) instead.
  ArrivalResult release();

  // Who has control now (Query Component Control), asked after a Reject:
  // none without a reply; a controller that is not a valid address means nobody.
  std::optional<jaus::msg::ReportComponentControl> who_has_control(jaus::rt::Duration timeout);

  // The component's answer to a control check that named another controller
  // (or none): the hold ended with End::rejected without a Reject received.
  const std::optional<jaus::msg::ReportComponentControl>& control_elsewhere() const { return control_elsewhere_; }

  // Liveness checks (Query Component Status) the component sent us while held.
  std::uint64_t liveness_checks() const { return liveness_checks_; }
  // Keepalives sent while held (none while the repeated command goes often enough).
  std::uint64_t keepalives_sent() const { return keepalives_sent_; }

 private:
  void watch_status();
  // A Report Component Status from the component: on its service connection,
  // or answering a keepalive.
  // `may_resume`: the report may say Ready again (on the service connection,
  // or before its first report); otherwise it may only tell of a stop.
  void heard_status(std::uint8_t primary_status, std::uint32_t secondary_status, bool may_resume);
  void stop_watching_status();
  bool status_refused() const;
  bool left_ready() const;
  double status_rate_hz() const;
  // Sends the repeated command when it is due and the component is Ready;
  // returns when to look again.
  jaus::rt::TimePoint repeat(jaus::rt::TimePoint now);
  // Sends a keepalive when nothing went to the component for kKeepalive;
  // returns when the next one is due.
  jaus::rt::TimePoint keep_alive(jaus::rt::TimePoint now);
  // Asks Query Component Control when due; returns when it is next due.
  jaus::rt::TimePoint check_control(jaus::rt::TimePoint now);
  bool control_gone() const { return rejected_ || control_elsewhere_.has_value(); }

  OcuSession& session_;
  jaus::Address target_;
  std::uint8_t authority_;
  jaus::rt::Duration status_silence_;
  OcuSession::ListenerId listener_ = 0;
  bool rejected_ = false;
  std::uint64_t liveness_checks_ = 0;
  std::optional<jaus::rt::SubscriptionId> status_sc_;
  std::optional<std::uint8_t> state_;  // last primary status reported
  std::optional<std::uint16_t> last_stops_;  // the stop counter of the last report
  std::optional<StopSeen> stop_seen_;
  bool status_reported_ = false;       // by the service connection (not only by keepalive answers)
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
  jaus::rt::TimePoint last_sent_{};  // to the component, by the hold
  std::uint64_t keepalives_sent_ = 0;
  jaus::rt::TimePoint next_control_check_{};
  std::optional<jaus::msg::ReportComponentControl> control_elsewhere_;
};

}  // namespace jaus::ocu
