#include "jaus/ocu/control_hold.hpp"

#include <algorithm>

#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "jaus/runtime/stop_counter.hpp"

namespace jaus::ocu {

namespace {
using namespace std::chrono_literals;
// What controlling OCUs use (docs/wire-format.md, "Service connections").
constexpr double kStatusRateHz = 5;
// The fastest rate a service connection can ask for (RA 3.3: 1092 Hz).
constexpr double kFastestStatusRateHz = 1092;
constexpr std::uint8_t kReady = static_cast<std::uint8_t>(jaus::msg::PrimaryStatus::ready);
constexpr std::uint8_t kInitialize = static_cast<std::uint8_t>(jaus::msg::PrimaryStatus::initialize);
// The hold wakes this often to look at the status reports' silence.
constexpr jaus::rt::Duration kHoldSlice = 250ms;
}  // namespace

ControlHold::ControlHold(OcuSession& session, const jaus::Address& target, std::uint8_t authority,
                         jaus::rt::Duration status_silence)
    : session_(session), target_(target), authority_(authority), status_silence_(status_silence) {}

ControlHold::~ControlHold() {
  if (listener_) session_.unlisten(listener_);
  stop_watching_status();
}

ControlHold::RequestResult ControlHold::request(jaus::rt::Duration timeout) {
  RequestResult r;
  auto reply = request_resending(session_, target_, jaus::msg::RequestComponentControl{{authority_}},
                                 {jaus::msg::ConfirmComponentControl::code, jaus::msg::RejectComponentControl::code},
                                 timeout);
  if (!reply) {
    r.outcome = session_.interrupted() ? Outcome::interrupted : Outcome::no_reply;
    r.error = reply.error();
    return r;
  }
  if (reply->header.command_code == jaus::msg::RejectComponentControl::code) {
    r.outcome = Outcome::rejected;
    return r;
  }
  jaus::msg::ConfirmComponentControl confirm{};
  if (!jaus::wire::decode_payload_into(reply->payload, confirm, session_.options().dialect, jaus::kHeaderSize)) {
    r.outcome = Outcome::refused;
    r.response_code = 0xFF;
    r.error = jaus::make_error(jaus::ErrorCode::malformed, "Confirm Component Control from " + target_.to_string() +
                                                               " does not decode");
    return r;
  }
  r.response_code = confirm.response_code;
  if (confirm.response_code != jaus::msg::control_response::kAccepted) {
    r.outcome = Outcome::refused;
    return r;
  }
  r.outcome = Outcome::granted;

  // From now on a Reject means control is gone; the liveness checks show the component watches us.
  listener_ = session_.listen([this](const Received& m) {
    if (m.header.source != target_) return;
    if (m.header.command_code == jaus::msg::RejectComponentControl::code) rejected_ = true;
    if (m.header.command_code == jaus::msg::QueryComponentStatus::code) ++liveness_checks_;
    // The answer to a keepalive (the first state sooner when the service
    // connection's creation was lost), or the component's own report of a
    // change of state (sent to its controller at once). Once the service
    // connection's reports come, such a report may only tell of a stop: a
    // Ready in it may be an answer overtaken by a newer report.
    if (m.header.command_code == jaus::msg::ReportComponentStatus::code && !m.header.service_connection) {
      jaus::msg::ReportComponentStatus report{};
      if (jaus::wire::decode_payload_into(m.payload, report, session_.options().dialect, jaus::kHeaderSize))
        heard_status(report.primary_status, report.secondary_status, /*may_resume=*/!status_reported_);
    }
    // The answer to a control check (or to who_has_control).
    if (m.header.command_code == jaus::msg::ReportComponentControl::code && !control_elsewhere_) {
      jaus::msg::ReportComponentControl report{};
      if (jaus::wire::decode_payload_into(m.payload, report, session_.options().dialect, jaus::kHeaderSize) &&
          report.controller != session_.self())
        control_elsewhere_ = report;
    }
  });
  next_control_check_ = session_.clock().now() + kControlCheck;
  watch_status();
  return r;
}

// Safety: a repeated command is stopped on the first report of another state
// than Ready, so the reports come at least as often as the commands go.
double ControlHold::status_rate_hz() const {
  if (!repeated_) return kStatusRateHz;
  const double send_rate_hz = 1.0 / std::chrono::duration<double>(repeat_period_).count();
  return std::clamp(send_rate_hz, kStatusRateHz, kFastestStatusRateHz);
}

void ControlHold::watch_status() {
  status_heard_ = session_.clock().now();
  status_sc_ = session_.component().subscribe<jaus::msg::ReportComponentStatus>(
      target_, status_rate_hz(), 0,
      [this](const jaus::Header&, const jaus::msg::ReportComponentStatus& report) {
        status_reported_ = true;
        heard_status(report.primary_status, report.secondary_status, /*may_resume=*/true);
      });
}

void ControlHold::heard_status(std::uint8_t primary_status, std::uint32_t secondary_status, bool may_resume) {
  status_heard_ = session_.clock().now();
  const std::uint8_t state = primary_status & 0x0F;
  const std::uint16_t stops = jaus::rt::stop_counter::of(secondary_status);
  // Safety: once commands went, any stop the component reports ends the
  // hold for good (WhenNotReady::end_hold), also one that came and went
  // between two reports: its stop counter moved (stop_counter.hpp). Kept
  // even when a later report says Ready again.
  if (been_ready_ && !stop_seen_) {
    if (state != kReady)
      stop_seen_ = StopSeen{state, false, last_stops_.value_or(stops), stops};
    else if (last_stops_ && stops != *last_stops_)
      stop_seen_ = StopSeen{state, true, *last_stops_, stops};
  }
  last_stops_ = stops;
  if (state == kReady && !may_resume) return;
  if (state_ == state) return;
  const std::string text =
      state_ ? primary_status_text(*state_) + " -> " + primary_status_text(state) : primary_status_text(state);
  state_ = state;
  if (on_state_) on_state_(text);
}

void ControlHold::stop_watching_status() {
  if (status_sc_) session_.component().unsubscribe(*status_sc_);
  status_sc_.reset();
}

bool ControlHold::status_refused() const {
  if (!status_sc_) return false;
  const auto* status = session_.component().subscription(*status_sc_);
  return status && status->refused;
}

ControlHold::End ControlHold::hold(std::optional<jaus::rt::Duration> limit,
                                   std::function<void(const std::string&)> on_state) {
  on_state_ = std::move(on_state);
  if (state_ && on_state_) on_state_(primary_status_text(*state_));  // reported before the hold began
  auto& clock = session_.clock();
  const auto until = limit ? clock.now() + *limit : jaus::rt::TimePoint::max();
  for (;;) {
    if (control_gone()) return End::rejected;
    if (session_.interrupted()) return End::interrupted;
    if (repeated_ && status_refused()) return End::unwatched;
    if (repeated_ && when_not_ready_ == WhenNotReady::end_hold && left_ready()) return End::not_ready;
    const auto now = clock.now();
    if (now >= until) return End::time_up;
    auto slice = std::min<jaus::rt::Duration>(until - now, kHoldSlice);
    if (repeated_) slice = std::min<jaus::rt::Duration>(slice, repeat(now) - now);
    slice = std::min<jaus::rt::Duration>(slice, check_control(now) - now);
    slice = std::min<jaus::rt::Duration>(slice, keep_alive(now) - now);
    // Only reports that came can stop: a component that does not provide its
    // status (refused, or a peer without service connections) is held without
    // this check. (The connection's own `confirmed` is reset while the client
    // re-creates it after a silence, so it cannot tell.)
    if (state_ && now - status_heard_ > status_silence_) return End::silent;
    // A new state wakes the loop at once: it decides before the next command goes.
    session_.run_until(
        [this, seen = state_, stopped = stop_seen_.has_value()] {
          return control_gone() || state_ != seen || stop_seen_.has_value() != stopped;
        },
        slice);
  }
}

// A component still starting (Initialize before it was ever Ready: a node
// just started, its hardware not heard yet) is waited for; every other state
// is a stop someone or something asked for.
bool ControlHold::left_ready() const {
  if (stop_seen_) return true;
  if (!state_ || *state_ == kReady) return false;
  return been_ready_ || *state_ != kInitialize;
}

jaus::rt::TimePoint ControlHold::repeat(jaus::rt::TimePoint now) {
  const bool ready = state_ == kReady;
  if (ready != sending_) {
    sending_ = ready;
    been_ready_ = been_ready_ || ready;
    next_send_ = now;  // at once when Ready (again)
    if (on_sending_) on_sending_(ready);
  }
  if (!ready) return now + kHoldSlice;  // a state report wakes the hold sooner
  if (now >= next_send_) {
    jaus::Header header = repeated_->header;
    header.destination = target_;
    session_.send_raw(header, repeated_->payload);
    ++sent_while_held_;
    last_sent_ = now;
    // From the ideal times, so a late wake-up does not slow the rate down.
    next_send_ += repeat_period_;
    if (next_send_ < now) next_send_ = now + repeat_period_;
  }
  return next_send_;
}

jaus::rt::TimePoint ControlHold::check_control(jaus::rt::TimePoint now) {
  if (now >= next_control_check_) {
    session_.send(target_, jaus::msg::QueryComponentControl{});
    last_sent_ = now;
    next_control_check_ = now + kControlCheck;
  }
  return next_control_check_;
}

jaus::rt::TimePoint ControlHold::keep_alive(jaus::rt::TimePoint now) {
  if (now - last_sent_ >= kKeepalive) {
    session_.send(target_, jaus::msg::QueryComponentStatus{});
    ++keepalives_sent_;
    last_sent_ = now;
  }
  return last_sent_ + kKeepalive;
}

void ControlHold::send_while_held(PreparedMessage message, jaus::rt::Duration period, WhenNotReady when_not_ready,
                                  std::function<void(bool sending)> on_sending) {
  repeated_ = std::move(message);
  repeat_period_ = std::max<jaus::rt::Duration>(period, 1ms);
  when_not_ready_ = when_not_ready;
  on_sending_ = std::move(on_sending);
  // Already watching (control granted): again, at the rate the commands need.
  if (status_sc_) {
    stop_watching_status();
    watch_status();
  }
}

ArrivalResult ControlHold::release() {
  stop_watching_status();
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(jaus::msg::ReleaseComponentControl{}, payload);
  if (!size) return ArrivalResult{};
  jaus::Header header;
  header.command_code = jaus::msg::ReleaseComponentControl::code;
  return send_must_arrive_through_stop(session_, target_, header, std::span(payload).first(*size), kReleasePolicy);
}

std::optional<jaus::msg::ReportComponentControl> ControlHold::who_has_control(jaus::rt::Duration timeout) {
  auto reply = request_resending(session_, target_, jaus::msg::QueryComponentControl{},
                                 {jaus::msg::ReportComponentControl::code}, timeout);
  if (!reply) return std::nullopt;
  jaus::msg::ReportComponentControl report{};
  if (!jaus::wire::decode_payload_into(reply->payload, report, session_.options().dialect, jaus::kHeaderSize))
    return std::nullopt;
  return report;
}

}  // namespace jaus::ocu
