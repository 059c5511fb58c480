// Access control of one JSS component (docs/jss.md, "Access Control"): request with an
// authority, keep it by requesting again before the component's timeout
// (Report Timeout; as fkie IOP does, at half of it), release; Reject Control
// from the component means control was lost (taken by a higher authority,
// timed out, released, Shutdown/Reset).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "jaus/ocu/jss_session.hpp"

namespace jaus::ocu {

// Confirm Control response codes.
enum class JssControlResponse : std::uint8_t { accepted = 0, not_available = 1, insufficient_authority = 2 };
std::string_view to_string(JssControlResponse response);
// Reject Control response codes: 0 CONTROL_RELEASED, 1 NOT_AVAILABLE.
std::string_view jss_reject_control_text(std::uint8_t code);

struct JssControlStatus {
  jss::JssId controller;  // 0.0.0 when nobody controls it
  std::uint8_t authority = 0;
  bool controlled() const { return controller.is_valid(); }
};

// Request Control, resent every 250 ms until Confirm Control (or Reject
// Control) comes. Errors: timeout, interrupted, a reply that does not decode.
Expected<JssControlResponse> request_jss_control(JssSession& session, const jss::JssId& component,
                                                 std::uint8_t authority, rt::Duration timeout = kJssDefaultTimeout);
// Release Control, resent until Reject Control (0: released) comes.
// Errors: timeout, interrupted.
Expected<void> release_jss_control(JssSession& session, const jss::JssId& component,
                                   rt::Duration timeout = kJssDefaultTimeout);
Expected<JssControlStatus> query_jss_control(JssSession& session, const jss::JssId& component,
                                             rt::Duration timeout = kJssDefaultTimeout);
// Report Timeout: seconds, 0 = the component never times its controller out.
Expected<std::uint8_t> query_jss_timeout(JssSession& session, const jss::JssId& component,
                                         rt::Duration timeout = kJssDefaultTimeout);
Expected<std::uint8_t> query_jss_authority(JssSession& session, const jss::JssId& component,
                                           rt::Duration timeout = kJssDefaultTimeout);

// Holds control while the session runs: requests it, asks the component's
// timeout, and requests again every half of it (every refresh_when_no_timeout
// when the component has none, refresh_when_unknown when it does not say).
// Over a lossy link a re-request (or its Confirm) may be lost: it is sent
// again every 250 ms until confirmed, so a timeout passes only when every
// datagram of half of it is lost. Ends on Reject Control from the component,
// on a re-request answered with anything but CONTROL_ACCEPTED, or on
// release(). The destructor releases when still held (best effort, 1 s).
class JssControlHold {
 public:
  struct Options {
    std::uint8_t authority = 0;
    rt::Duration request_timeout = kJssDefaultTimeout;
    rt::Duration refresh_when_no_timeout = std::chrono::seconds(5);
    rt::Duration refresh_when_unknown = std::chrono::seconds(1);  // Query Timeout not answered
    // Never re-request more often than this (a 1 s timeout: every 500 ms).
    rt::Duration min_refresh = std::chrono::milliseconds(100);
  };
  enum class State { held, refused, lost, released };

  // Requests control; an error when it is not granted (the error's text has
  // the Confirm Control code: "1.1.33 refused control: INSUFFICIENT_AUTHORITY"),
  // or no reply.
  static Expected<std::unique_ptr<JssControlHold>> take(JssSession& session, const jss::JssId& component,
                                                        Options options);
  ~JssControlHold();
  JssControlHold(const JssControlHold&) = delete;
  JssControlHold& operator=(const JssControlHold&) = delete;

  const jss::JssId& component() const { return component_; }
  State state() const { return state_; }
  bool held() const { return state_ == State::held; }
  // The component's control timeout as it reported it (0: none, or not answered).
  std::uint8_t timeout_s() const { return timeout_s_; }
  rt::Duration refresh_period() const { return refresh_period_; }
  std::uint64_t refreshes() const { return refreshes_; }
  // Why control was lost: "Reject Control: CONTROL_RELEASED", "re-request answered INSUFFICIENT_AUTHORITY".
  const std::string& lost_reason() const { return lost_reason_; }
  // Called once when control is lost (not on release()).
  void on_lost(std::function<void(const std::string& reason)> callback) { on_lost_ = std::move(callback); }
  // Runs the session while held, until `limit` (none: until interrupted). True while still held.
  bool hold_for(std::optional<rt::Duration> limit);
  // Release Control and wait for Reject Control 0; goes on after a stop was requested (Ctrl-C releases).
  Expected<void> release(rt::Duration timeout = kJssDefaultTimeout);

 private:
  JssControlHold(JssSession& session, const jss::JssId& component, Options options);
  // Sends Request Control when due, or again while the last one is unconfirmed; sets the next timer.
  void refresh();
  void lose(std::string reason);

  JssSession& session_;
  jss::JssId component_;
  Options options_;
  State state_ = State::held;
  std::uint8_t timeout_s_ = 0;
  rt::Duration refresh_period_{};
  std::uint64_t refreshes_ = 0;
  std::string lost_reason_;
  std::function<void(const std::string&)> on_lost_;
  JssSession::ListenerId listener_ = 0;
  rt::TimerId refresh_timer_ = rt::kNoTimer;
  rt::TimePoint next_refresh_{};
  bool confirmed_ = true;  // the last Request Control was answered CONTROL_ACCEPTED
};

}  // namespace jaus::ocu
