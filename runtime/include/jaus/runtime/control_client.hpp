// Control of another component, requester side: what a component does to
// command the level below it over JAUS (a waypoint driver commanding the
// primitive driver), as an operator unit would. Sans-I/O like the rest of the
// runtime: the owner sends what this asks for (Io) and hands over what it
// receives (on_message); time is the environment's.
//
//   acquire(): Request Component Control with the owner's authority, repeated
//     every reply_timeout up to `tries` times; Confirm 0 grants it, Confirm
//     1/2 or Reject refuses it, silence gives up.
//   held: granted, and the target's last Report Component Status said Ready.
//     Query Component Status goes every status_period while control is
//     requested or held, so the owner learns at once when the target leaves
//     Ready (an operator's Set Emergency, Standby) and when it falls silent.
//   lost: Reject Component Control (an operator of higher authority took
//     over, or the target dropped us), a status other than Ready, a Ready
//     whose stop counter moved since the hold began (a stop that came and
//     went between two reports: stop_counter.hpp), or no status for
//     status_silence. The target also sends its status at once on every
//     change of state, so a stop is mostly seen before the next query. The owner hears `lost(why)` once, and
//     control is released (Release Component Control), except after a Reject,
//     when it is not ours any more.
//
// Safety (why "held" needs Ready): a target that left Ready refuses commands,
// but it returns to Ready on Clear Emergency or Resume; an owner that kept
// commanding would start the vehicle again. So leaving Ready is a loss: the
// owner stops what it was doing and needs its own new reason to acquire again.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "jaus/core/header.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/environment.hpp"

namespace jaus::rt {

class ControlClient {
 public:
  struct Options {
    Duration reply_timeout = std::chrono::seconds(1);  // for Confirm Component Control
    int tries = 3;                                      // Request Component Control sent at most this often
    Duration status_period = std::chrono::milliseconds(100);
    Duration status_silence = std::chrono::seconds(1);  // no Report Component Status this long: lost
  };
  // How the owner sends (a component's send<M>()).
  struct Io {
    std::function<void(const Address&, const msg::RequestComponentControl&)> request;
    std::function<void(const Address&, const msg::ReleaseComponentControl&)> release;
    std::function<void(const Address&, const msg::QueryComponentStatus&)> query_status;
  };
  using Granted = std::function<void()>;
  using Lost = std::function<void(const std::string& why)>;

  enum class State : std::uint8_t { released, requesting, granted_waiting_ready, held };

  struct Counters {
    std::uint64_t requests_sent = 0;
    std::uint64_t granted = 0;
    std::uint64_t refused = 0;
    std::uint64_t lost = 0;  // after being held: taken over, not Ready, silent
    std::uint64_t released = 0;
  };

  ControlClient(Environment& env, Options options, Io io);
  ~ControlClient();
  ControlClient(const ControlClient&) = delete;
  ControlClient& operator=(const ControlClient&) = delete;

  // Asks for control of `target` with `authority`. `granted` is called once
  // control is held (confirmed and the target Ready); `lost` once, if it is
  // refused, never answered or later lost. Acquiring while requesting or
  // holding the same target does nothing; another target releases the first.
  void acquire(const Address& target, std::uint8_t authority, Granted granted, Lost lost);
  // Gives control back (Release Component Control when requested or held);
  // `lost` is not called. Idempotent.
  void release();

  // A message from the target this client is about (Confirm or Reject
  // Component Control, Report Component Status): true when taken.
  bool on_message(const Header& header, std::span<const std::uint8_t> payload);

  State state() const { return state_; }
  bool held() const { return state_ == State::held; }
  const Address& target() const { return target_; }
  const Counters& counters() const { return counters_; }

 private:
  void send_request();
  void on_confirm(std::uint8_t response_code);
  void on_status(std::uint8_t primary_status, std::uint32_t secondary_status);
  void tick();
  void arm_tick();
  void cancel_tick();
  // Ends the request or hold; `lost_` hears why (once). Sends Release unless rejected.
  void lose(const std::string& why, bool send_release);

  Environment& env_;
  Options options_;
  Io io_;
  State state_ = State::released;
  Address target_;
  std::uint8_t authority_ = 0;
  Granted granted_;
  Lost lost_;
  int requests_left_ = 0;
  TimePoint request_sent_{};
  TimePoint last_status_{};
  std::uint16_t held_stops_ = 0;  // the target's stop counter when it was first Ready to us
  TimerId timer_ = kNoTimer;
  Counters counters_;
};

std::string_view to_string(ControlClient::State state);

}  // namespace jaus::rt
