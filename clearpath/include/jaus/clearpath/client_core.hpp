// The Clearpath client's logic, sans-I/O: what to send, when to retry, what
// an ACK means, when the link is dead. The Asio link (link.hpp) feeds it
// bytes and time and writes what it hands out; tests drive it in virtual time.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"

namespace jaus::clearpath {

struct ClientConfig {
  std::chrono::milliseconds ack_timeout{250};
  // First send + retries. A command that exhausts them takes the link down
  // only when no ACK to anything came back since its first send (the command
  // path is dead); otherwise it finishes CommandError::no_ack on a live link.
  int max_attempts = 4;
  // A subscription request that finished no_ack on a live link is asked
  // again after this (subscriptions are wanted state, not one-off commands).
  std::chrono::milliseconds resubscribe_delay{1000};
  // Current setpoints are resent this often to feed the platform's watchdog...
  std::chrono::milliseconds setpoint_period{50};
  // ...but only while they are younger than this (since set_setpoint): the
  // link never keeps a platform moving on a command its application stopped
  // renewing. 0 keeps a setpoint until it is replaced or cleared.
  std::chrono::milliseconds setpoint_max_age{500};
  // No frame from the platform for this long: the link is down.
  std::chrono::milliseconds data_silence{1000};
  // Does the platform still hear us? Setpoints go without ACK, so while only
  // they flow nothing would tell. When no ACK (to anything) came back for
  // probe_period, a probe goes: a single Request Echo with ACK (16 bytes; its
  // ACK and empty Echo reply are 30 bytes back), written after everything
  // else waiting, outside the command queue. At most 10 a second, and none
  // while commands are being acknowledged: on a 115200-baud line about 1.4 %
  // of the bandwidth to the platform and 2.6 % back. 0 disables probing.
  std::chrono::milliseconds probe_period{100};
  // No ACK to anything for this long since a probe went unanswered (about
  // probe_timeout / probe_period probes lost in a row): the platform no
  // longer hears us, even if its data still flows, and the link goes down.
  std::chrono::milliseconds probe_timeout{1000};
  std::chrono::milliseconds backoff_initial{100};
  std::chrono::milliseconds backoff_max{2000};
  std::uint8_t version = kDefaultVersion;
  // Commands and requests sent with ACK that are not finished yet (waiting to
  // be written, or written and waiting for their ACK). A send() or subscribe()
  // beyond it finishes at once with CommandError::queue_full, so an
  // application that commands faster than the link cannot grow memory without
  // end. Set Safety System, cancels (unsubscribe) and the re-requests of a
  // reconnect are never refused: each replaces its own waiting one, so they
  // cannot pile up.
  std::size_t max_waiting_commands = 64;
};

enum class ConnectionState { down, connecting, connected, retrying };
std::string_view to_string(ConnectionState state);

enum class CommandError {
  none,
  refused,      // the platform answered with non-zero result bits (see result)
  no_ack,       // every attempt timed out or came back "bad checksum"
  link_down,    // the link went down before an answer
  not_encodable,
  superseded,   // a newer command of its kind (or a setpoint of its type) replaced it
  queue_full,   // refused at once: max_waiting_commands are waiting already
};

struct CommandOutcome {
  CommandError error = CommandError::none;
  std::uint16_t result = 0;  // ACK result bits when refused
  int attempts = 0;
  bool ok() const { return error == CommandError::none; }
};

struct ClientCounters {
  std::uint64_t frames_sent = 0, frames_received = 0;
  std::uint64_t acks_ok = 0, acks_refused = 0, acks_unmatched = 0;
  std::uint64_t retries = 0, timeouts = 0, bad_checksum_acks = 0;
  std::uint64_t decode_errors = 0, data_received = 0;
  std::uint64_t reconnects = 0, setpoints_sent = 0, setpoints_replaced = 0;
  std::uint64_t setpoints_expired = 0;  // older than setpoint_max_age: no longer sent
  std::uint64_t setpoints_dropped = 0;  // the link went down: a reconnect never re-arms them
  std::uint64_t commands_superseded = 0;    // finished superseded (never written, or not retried)
  std::uint64_t commands_refused_full = 0;  // finished queue_full
  std::uint64_t commands_unanswered = 0;    // finished no_ack
  std::uint64_t subscriptions_rerequested = 0;  // asked again after a no_ack on a live link
  std::uint64_t probes_sent = 0;      // Request Echo with ACK, written because no ACK came back for probe_period
  std::uint64_t probes_answered = 0;  // ACKs matching a probe
  std::uint64_t unheard_downs = 0;    // link taken down because the platform no longer hears us
  std::uint64_t data_withheld = 0;    // data not delivered: the platform has not yet shown it hears us again
};

class ClientCore {
 public:
  using CommandCallback = std::function<void(const CommandOutcome&)>;
  using DataCallback = std::function<void(const Envelope&)>;
  using StateCallback = std::function<void(ConnectionState)>;
  using ProblemCallback = std::function<void(const Error&)>;

  explicit ClientCore(ClientConfig config = {});

  // ---- from the transport ---------------------------------------------------
  void on_connected(rt::TimePoint now);
  void on_disconnected(rt::TimePoint now);
  void on_bytes(std::span<const std::uint8_t> bytes, rt::TimePoint now);
  // Timeouts, retries, setpoint resends, silence watchdog. Call every few ms.
  void tick(rt::TimePoint now);
  // Next frame to write (empty: nothing to send), one frame per call so each
  // can be its own datagram. Setpoints go first and are encoded at the last
  // moment, so an unsent older setpoint is never written.
  std::vector<std::uint8_t> take_frame(rt::TimePoint now);
  // The link must be reopened (silence or failure); the shell waits until then.
  bool wants_reconnect() const { return wants_reconnect_; }
  rt::TimePoint reconnect_at() const { return reconnect_at_; }
  void reconnect_started(rt::TimePoint now);
  void open_failed(rt::TimePoint now);

  // ---- from the application ---------------------------------------------------
  // A command or request sent with ACK, retried with a new timestamp on
  // timeout or "bad checksum"; done(outcome) runs once.
  //
  // Ordering, per kind: a kind is the message type plus, where the type
  // addresses one of several things, its mount (0x0400) or joint (0x1012,
  // 0x1013, and the requests that carry one), as subscriptions are keyed.
  // - One in flight per kind: a newer command of a kind waits until the
  //   older one is answered, so a retry can never land after a newer command
  //   of its kind (a stale safety word or GPIO value would win otherwise).
  // - Latest wins: a newer command replaces a waiting one of its kind that it
  //   covers (the older one finishes `superseded`), and an in-flight one that
  //   times out is not retried when a newer one of its kind waits. Partial
  //   commands replace only what they cover: Set GPIO Output/Direction a
  //   subset of their mask, Set Analog Outputs / Set Absolute Joints a subset
  //   of their channels or joints; Set Relative Joints never (deltas add up);
  //   a single-reply request only a single-reply request, a subscription
  //   setting (rate or cancel) only a subscription setting (a single reply
  //   leaves the subscription alone).
  // - Set Safety System goes before every other waiting command (only
  //   setpoints and stops go earlier), retries included.
  // - Otherwise commands go out in the order they were sent; one waiting for
  //   its own kind does not hold back those of other kinds.
  // - At most max_waiting_commands unfinished, else queue_full at once.
  void send(AnyMessage message, CommandCallback done = {});
  // Keep a subscription (request with subscription N Hz) alive across
  // reconnects. Refused (queue_full, not kept) like send() when full.
  void subscribe(AnyMessage request, CommandCallback done = {});
  void unsubscribe(std::uint16_t request_type, std::uint8_t selector = 0);
  // Latest-wins stream, one slot per message type (velocity, outputs...),
  // resent every setpoint_period while younger than setpoint_max_age (from
  // `now`, when it was set). The application renews it as long as it wants
  // motion; when it stops renewing, the stream ends and the platform's own
  // watchdog stops the platform. A setpoint supersedes the send() commands of
  // its kind that it covers: waiting ones finish `superseded` at once, one in
  // flight is never retried (so no older command of its type sent with ACK
  // reaches the platform after it).
  void set_setpoint(AnyMessage command, rt::TimePoint now);
  void clear_setpoint(std::uint16_t type);
  // Safety: replaces the stream of this type with `stop` (a zero setpoint),
  // written once, first, at the next frame, and then the stream ends: nothing
  // of that type is re-sent until set_setpoint() is called again. Supersedes
  // send() commands of its kind as set_setpoint() does.
  void stop_setpoint(AnyMessage stop, rt::TimePoint now);
  // Every data message; withheld (counted, not delivered) after a down because
  // the platform did not hear us, until an ACK shows it does again.
  void on_data(DataCallback callback) { on_data_ = std::move(callback); }
  // Every change of state() (down, connecting, connected, retrying).
  void on_state(StateCallback callback) { on_state_ = std::move(callback); }
  // Every piece of input passed over, saying where and why: bytes the parser
  // rejected (bad CRC, bad length, garbage, ...; parser_counters()) and frames
  // that do not decode (ClientCounters::decode_errors). Never acted on; for
  // the owner's log.
  void on_problem(ProblemCallback callback) { on_problem_ = std::move(callback); }

  ConnectionState state() const { return state_; }
  const ClientCounters& counters() const { return counters_; }
  const ParserCounters& parser_counters() const { return parser_.counters(); }
  std::uint32_t last_timestamp() const { return last_timestamp_; }
  // Why the link last went down, in words (empty before it ever did), e.g.
  // "the platform no longer hears us: ...; link down". For the owner's log.
  const std::string& down_reason() const { return down_reason_; }
  // Commands sent with ACK and not finished (what max_waiting_commands bounds).
  std::size_t waiting_commands() const { return queue_.size() + in_flight_.size(); }

 private:
  // What a command addresses: its type, and the mount or joint if it has one.
  struct Kind {
    std::uint16_t type;
    std::uint8_t selector;
    auto operator<=>(const Kind&) const = default;
  };
  struct Pending {
    Pending(AnyMessage m, Kind k, CommandCallback d = {}) : message(std::move(m)), kind(k), done(std::move(d)) {}
    AnyMessage message;
    Kind kind;
    CommandCallback done;
    int attempts = 0;
    std::optional<rt::TimePoint> deadline;  // unset: waiting in the queue
    std::optional<rt::TimePoint> first_sent;
    bool stale = false;  // a setpoint of its kind was written after it: never retried
  };
  // An ACK names the (type, timestamp) it answers.
  struct AckKey {
    std::uint16_t type;
    std::uint32_t timestamp;
    auto operator<=>(const AckKey&) const = default;
  };
  struct Setpoint {
    AnyMessage message;
    rt::TimePoint set_at{};
    bool fresh = true;       // not yet written since it was set
    bool stop_once = false;  // a stop: written once, then the stream ends
    rt::TimePoint last_sent{};
  };

  std::uint32_t next_timestamp(rt::TimePoint now);
  static Kind kind_of_message(std::uint16_t type, const AnyMessage& message);
  bool enqueue(Pending pending, bool bounded);
  void supersede_for_setpoint(const AnyMessage& setpoint, std::uint16_t type);
  bool in_flight(const Kind& kind) const;
  std::deque<Pending>::iterator next_waiting();
  bool retry_or_finish(Pending pending, std::uint16_t result, rt::TimePoint now);
  bool answered_since_first_send(const Pending& pending) const;
  void rerequest_due_subscriptions(rt::TimePoint now);
  void supersede(Pending& pending);
  void finish(Pending& pending, CommandOutcome outcome);
  void fail_all(CommandError error);
  void resubscribe();
  void handle_frame(const Frame& frame, rt::TimePoint now);
  void mark_down(rt::TimePoint now, std::string reason);
  void mark_unheard(rt::TimePoint now, std::string why);
  bool probe_due(rt::TimePoint now) const;
  std::vector<std::uint8_t> take_probe(rt::TimePoint now);
  void set_state(ConnectionState state);

  ClientConfig config_;
  rt::TimePoint epoch_;
  bool epoch_set_ = false;
  std::uint32_t last_timestamp_ = 0;
  ConnectionState state_ = ConnectionState::down;
  FrameParser parser_;
  std::deque<Pending> queue_;                 // waiting to be written, in the order sent
  std::deque<std::vector<std::uint8_t>> raw_; // fire-and-forget frames (cancels)
  std::map<AckKey, Pending> in_flight_;
  std::map<std::pair<std::uint16_t, std::uint8_t>, AnyMessage> subscriptions_;
  std::map<std::uint16_t, Setpoint> setpoints_;
  // Subscriptions whose request finished no_ack on a live link: asked again then.
  std::map<Kind, rt::TimePoint> resubscribe_at_;
  rt::TimePoint last_rx_{};
  std::optional<rt::TimePoint> last_ack_;  // any ACK, matched or not: the platform hears us
  rt::TimePoint connected_at_{};
  std::optional<rt::TimePoint> last_probe_;
  std::optional<AckKey> probe_key_;                 // the last probe written, to count its ACK
  std::optional<rt::TimePoint> unanswered_probe_;   // the first probe written since the last ACK
  std::uint64_t probes_sent_at_unanswered_ = 0;
  // Set when the link went down because the platform did not hear us: until
  // an ACK shows it does again, its data is withheld, so the owner does not
  // take a platform that still talks but does not listen for a live one.
  bool hearing_unconfirmed_ = false;
  std::string down_reason_;
  bool wants_reconnect_ = true;
  rt::TimePoint reconnect_at_{};
  std::chrono::milliseconds backoff_;
  DataCallback on_data_;
  StateCallback on_state_;
  ProblemCallback on_problem_;
  ClientCounters counters_;
};

}  // namespace jaus::clearpath
