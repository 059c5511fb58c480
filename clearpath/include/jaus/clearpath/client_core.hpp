// The Clearpath client's logic, sans-I/O: what to send, when to retry, what
// an ACK means, when the link is dead. The Asio link (link.hpp) feeds it
// bytes and time and writes what it hands out; tests drive it in virtual time.
#pragma once

#include <chrono>
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
  int max_attempts = 4;  // first send + retries
  // Current setpoints are resent this often to feed the platform's watchdog...
  std::chrono::milliseconds setpoint_period{50};
  // ...but only while they are younger than this (since set_setpoint): the
  // link never keeps a platform moving on a command its application stopped
  // renewing. 0 keeps a setpoint until it is replaced or cleared.
  std::chrono::milliseconds setpoint_max_age{500};
  // No frame from the platform for this long: the link is down.
  std::chrono::milliseconds data_silence{1000};
  std::chrono::milliseconds backoff_initial{100};
  std::chrono::milliseconds backoff_max{2000};
  std::uint8_t version = kDefaultVersion;
};

enum class ConnectionState { down, connecting, connected, retrying };
std::string_view to_string(ConnectionState state);

enum class CommandError {
  none,
  refused,      // the platform answered with non-zero result bits (see result)
  no_ack,       // every attempt timed out or came back "bad checksum"
  link_down,    // the link went down before an answer
  not_encodable,
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
};

class ClientCore {
 public:
  using CommandCallback = std::function<void(const CommandOutcome&)>;
  using DataCallback = std::function<void(const Envelope&)>;
  using StateCallback = std::function<void(ConnectionState)>;

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
  void send(AnyMessage message, CommandCallback done = {});
  // Keep a subscription (request with subscription N Hz) alive across reconnects.
  void subscribe(AnyMessage request, CommandCallback done = {});
  void unsubscribe(std::uint16_t request_type, std::uint8_t selector = 0);
  // Latest-wins stream, one slot per message type (velocity, outputs...),
  // resent every setpoint_period while younger than setpoint_max_age (from
  // `now`, when it was set). The application renews it as long as it wants
  // motion; when it stops renewing, the stream ends and the platform's own
  // watchdog stops the platform.
  void set_setpoint(AnyMessage command, rt::TimePoint now);
  void clear_setpoint(std::uint16_t type);
  // Safety: replaces the stream of this type with `stop` (a zero setpoint),
  // written once, first, at the next frame, and then the stream ends: nothing
  // of that type is re-sent until set_setpoint() is called again.
  void stop_setpoint(AnyMessage stop, rt::TimePoint now);
  void on_data(DataCallback callback) { on_data_ = std::move(callback); }
  // Every change of state() (down, connecting, connected, retrying).
  void on_state(StateCallback callback) { on_state_ = std::move(callback); }

  ConnectionState state() const { return state_; }
  const ClientCounters& counters() const { return counters_; }
  const ParserCounters& parser_counters() const { return parser_.counters(); }
  std::uint32_t last_timestamp() const { return last_timestamp_; }

 private:
  struct Pending {
    AnyMessage message;
    std::uint16_t type;
    CommandCallback done;
    int attempts = 0;
    std::optional<rt::TimePoint> deadline;  // unset: waiting in the queue
  };
  struct Key {
    std::uint16_t type;
    std::uint32_t timestamp;
    auto operator<=>(const Key&) const = default;
  };
  struct Setpoint {
    AnyMessage message;
    rt::TimePoint set_at{};
    bool fresh = true;       // not yet written since it was set
    bool stop_once = false;  // a stop: written once, then the stream ends
    rt::TimePoint last_sent{};
  };

  std::uint32_t next_timestamp(rt::TimePoint now);
  void transmit(Pending pending, rt::TimePoint now);
  void finish(Pending& pending, CommandOutcome outcome);
  void fail_all(CommandError error);
  void resubscribe();
  void handle_frame(const Frame& frame, rt::TimePoint now);
  void mark_down(rt::TimePoint now);
  void set_state(ConnectionState state);

  ClientConfig config_;
  rt::TimePoint epoch_;
  bool epoch_set_ = false;
  std::uint32_t last_timestamp_ = 0;
  ConnectionState state_ = ConnectionState::down;
  FrameParser parser_;
  std::deque<Pending> queue_;                 // waiting to be written
  std::deque<std::vector<std::uint8_t>> raw_; // fire-and-forget frames (cancels)
  std::map<Key, Pending> in_flight_;
  std::map<std::pair<std::uint16_t, std::uint8_t>, AnyMessage> subscriptions_;
  std::map<std::uint16_t, Setpoint> setpoints_;
  rt::TimePoint last_rx_{};
  bool wants_reconnect_ = true;
  rt::TimePoint reconnect_at_{};
  std::chrono::milliseconds backoff_;
  DataCallback on_data_;
  StateCallback on_state_;
  ClientCounters counters_;
};

}  // namespace jaus::clearpath
