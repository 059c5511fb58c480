#include "jaus/runtime/control_client.hpp"

#include "jaus/runtime/lifecycle.hpp"
#include "jaus/runtime/stop_counter.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::rt {

namespace {
std::string state_name(std::uint8_t primary_status) {
  return std::string(to_string(static_cast<PrimaryStatus>(primary_status & 0x0F)));
}
}  // namespace

std::string_view to_string(ControlClient::State state) {
  switch (state) {
    case ControlClient::State::released: return "released";
    case ControlClient::State::requesting: return "requesting";
    case ControlClient::State::granted_waiting_ready: return "granted, waiting for Ready";
    case ControlClient::State::held: return "held";
  }
  return "?";
}

ControlClient::ControlClient(Environment& env, Options options, Io io)
    : env_(env), options_(options), io_(std::move(io)) {}

ControlClient::~ControlClient() { cancel_tick(); }

void ControlClient::acquire(const Address& target, std::uint8_t authority, Granted granted, Lost lost) {
  if (state_ != State::released && target == target_) {
    // The same target: keep the request or the hold, with the new listeners.
    granted_ = std::move(granted);
    lost_ = std::move(lost);
    return;
  }
  release();
  target_ = target;
  authority_ = authority;
  granted_ = std::move(granted);
  lost_ = std::move(lost);
  state_ = State::requesting;
  requests_left_ = options_.tries;
  last_status_ = env_.clock.now();
  send_request();
  arm_tick();
}

void ControlClient::release() {
  if (state_ == State::released) return;
  cancel_tick();
  state_ = State::released;
  ++counters_.released;
  io_.release(target_, msg::ReleaseComponentControl{});
}

void ControlClient::send_request() {
  --requests_left_;
  ++counters_.requests_sent;
  request_sent_ = env_.clock.now();
  io_.request(target_, msg::RequestComponentControl{{authority_}});
}

bool ControlClient::on_message(const Header& header, std::span<const std::uint8_t> payload) {
  if (state_ == State::released || header.source != target_) return false;
  switch (header.command_code) {
    case msg::ConfirmComponentControl::code: {
      msg::ConfirmComponentControl confirm{};
      if (!wire::decode_payload_into(payload, confirm, wire::Dialect::ra, kHeaderSize)) return false;
      on_confirm(confirm.response_code);
      return true;
    }
    case msg::RejectComponentControl::code:
      // Taken over by a higher authority, or dropped by the target: not ours
      // any more, so nothing to release.
      lose("control of " + target_.to_string() + " taken away (Reject Component Control)", /*send_release=*/false);
      return true;
    case msg::ReportComponentStatus::code: {
      msg::ReportComponentStatus status{};
      if (!wire::decode_payload_into(payload, status, wire::Dialect::ra, kHeaderSize)) return false;
      on_status(status.primary_status, status.secondary_status);
      return true;
    }
    default: return false;
  }
}

void ControlClient::on_confirm(std::uint8_t response_code) {
  if (state_ != State::requesting) return;  // a late duplicate of the confirmation we acted on
  if (response_code != msg::control_response::kAccepted) {
    ++counters_.refused;
    lose("control of " + target_.to_string() + " refused (Confirm Component Control " +
             std::to_string(response_code) + ")",
         /*send_release=*/false);
    return;
  }
  // Granted; held once the target says it is Ready (asked at once).
  state_ = State::granted_waiting_ready;
  last_status_ = env_.clock.now();
  io_.query_status(target_, msg::QueryComponentStatus{});
}

void ControlClient::on_status(std::uint8_t primary_status, std::uint32_t secondary_status) {
  last_status_ = env_.clock.now();
  if (state_ == State::requesting) return;  // its state says nothing about our request yet
  if (static_cast<PrimaryStatus>(primary_status & 0x0F) != PrimaryStatus::ready) {
    lose(target_.to_string() + " is in " + state_name(primary_status), /*send_release=*/true);
    return;
  }
  const std::uint16_t stops = stop_counter::of(secondary_status);
  // Safety: Ready again, but a stop came and went since the last report (Set
  // then Clear Emergency between two samples): lost as if it had been seen,
  // so nothing the target stopped is started again by us.
  if (state_ == State::held && stops != held_stops_) {
    lose(target_.to_string() + " stopped and went back to Ready between two status reports (stop counter " +
             std::to_string(held_stops_) + " -> " + std::to_string(stops) + ")",
         /*send_release=*/true);
    return;
  }
  if (state_ == State::granted_waiting_ready) {
    held_stops_ = stops;  // stops before we held it are not ours to see
    state_ = State::held;
    ++counters_.granted;
    if (granted_) granted_();
  }
}

void ControlClient::arm_tick() {
  cancel_tick();
  timer_ = env_.scheduler.call_at(env_.clock.now() + options_.status_period, [this] {
    timer_ = kNoTimer;
    tick();
  });
}

void ControlClient::cancel_tick() {
  if (timer_ == kNoTimer) return;
  env_.scheduler.cancel(timer_);
  timer_ = kNoTimer;
}

void ControlClient::tick() {
  const TimePoint now = env_.clock.now();
  if (state_ == State::requesting) {
    if (now - request_sent_ >= options_.reply_timeout) {
      if (requests_left_ <= 0) {
        ++counters_.refused;
        // Release too: a confirmation lost on the way back may have granted it.
        lose(target_.to_string() + " did not answer Request Component Control", /*send_release=*/true);
        return;
      }
      send_request();
    }
  } else {
    if (now - last_status_ >= options_.status_silence) {
      lose(target_.to_string() + " silent (no Report Component Status)", /*send_release=*/true);
      return;
    }
    io_.query_status(target_, msg::QueryComponentStatus{});
  }
  arm_tick();
}

void ControlClient::lose(const std::string& why, bool send_release) {
  const bool was_held = state_ == State::held;
  cancel_tick();
  state_ = State::released;
  if (was_held) ++counters_.lost;
  if (send_release) {
    ++counters_.released;
    io_.release(target_, msg::ReleaseComponentControl{});
  }
  // Moved out first: the listener may acquire again (a new hold, new listeners).
  Lost lost = std::move(lost_);
  granted_ = {};
  lost_ = {};
  if (lost) lost(why);
}

}  // namespace jaus::rt
