#include "jaus/ocu/jss_control.hpp"

#include <algorithm>

#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;
namespace jss_msg = jss::msg;

Error decode_failure(const jss::JssId& from, std::string_view what, const Error& error) {
  return make_error(ErrorCode::malformed,
                    std::string(what) + " from " + from.to_string() + " does not decode: " + error.message());
}

}  // namespace

std::string_view to_string(JssControlResponse response) {
  switch (response) {
    case JssControlResponse::accepted: return "CONTROL_ACCEPTED";
    case JssControlResponse::not_available: return "NOT_AVAILABLE";
    case JssControlResponse::insufficient_authority: return "INSUFFICIENT_AUTHORITY";
  }
  return "unknown";
}

std::string_view jss_reject_control_text(std::uint8_t code) {
  switch (code) {
    case 0: return "CONTROL_RELEASED";
    case 1: return "NOT_AVAILABLE";
    default: return "unknown";
  }
}

Expected<JssControlResponse> request_jss_control(JssSession& session, const jss::JssId& component,
                                                 std::uint8_t authority, rt::Duration timeout) {
  jss_msg::RequestControl request;
  request.authority = authority;
  const auto contents = jss::encode_contents(request);
  auto reply =
      session.request_contents(component, contents, {jss_msg::ConfirmControl::code, jss_msg::RejectControl::code}, timeout);
  if (!reply) return unexpected(reply.error());
  if (reply->message_id() == jss_msg::RejectControl::code) return JssControlResponse::not_available;
  auto confirm = jss::decode_contents<jss_msg::ConfirmControl>(reply->contents);
  if (!confirm) return unexpected(decode_failure(component, "Confirm Control", confirm.error()));
  if (confirm->response_code > 2)
    return unexpected(make_error(ErrorCode::malformed, "Confirm Control from " + component.to_string() +
                                                           " has response code " +
                                                           std::to_string(confirm->response_code) + " (0..2)"));
  return static_cast<JssControlResponse>(confirm->response_code);
}

Expected<void> release_jss_control(JssSession& session, const jss::JssId& component, rt::Duration timeout) {
  const auto contents = jss::encode_contents(jss_msg::ReleaseControl{});
  auto reply = session.request_contents(component, contents, {jss_msg::RejectControl::code}, timeout);
  if (!reply) return unexpected(reply.error());
  return {};
}

Expected<JssControlStatus> query_jss_control(JssSession& session, const jss::JssId& component, rt::Duration timeout) {
  auto report = session.query<jss_msg::ReportControl>(component, jss_msg::QueryControl{}, timeout);
  if (!report) return unexpected(report.error());
  JssControlStatus status;
  status.controller = report->controller;
  status.authority = report->authority;
  return status;
}

Expected<std::uint8_t> query_jss_timeout(JssSession& session, const jss::JssId& component, rt::Duration timeout) {
  auto report = session.query<jss_msg::ReportTimeout>(component, jss_msg::QueryTimeout{}, timeout);
  if (!report) return unexpected(report.error());
  return report->timeout_s;
}

Expected<std::uint8_t> query_jss_authority(JssSession& session, const jss::JssId& component, rt::Duration timeout) {
  auto report = session.query<jss_msg::ReportAuthority>(component, jss_msg::QueryAuthority{}, timeout);
  if (!report) return unexpected(report.error());
  return report->authority;
}

JssControlHold::JssControlHold(JssSession& session, const jss::JssId& component, Options options)
    : session_(session), component_(component), options_(options) {}

Expected<std::unique_ptr<JssControlHold>> JssControlHold::take(JssSession& session, const jss::JssId& component,
                                                               Options options) {
  auto response = request_jss_control(session, component, options.authority, options.request_timeout);
  if (!response) return unexpected(response.error());
  if (*response != JssControlResponse::accepted)
    return unexpected(make_error(ErrorCode::refused,
                                 component.to_string() + " refused control: " + std::string(to_string(*response))));
  std::unique_ptr<JssControlHold> hold(new JssControlHold(session, component, options));
  JssControlHold* raw = hold.get();
  hold->listener_ = session.listen([raw](const JssReceived& m) {
    if (m.source() != raw->component_ || !raw->held()) return;
    if (m.message_id() == jss_msg::RejectControl::code) {
      auto reject = jss::decode_contents<jss_msg::RejectControl>(m.contents);
      raw->lose("Reject Control: " +
                std::string(reject ? jss_reject_control_text(reject->response_code) : "(does not decode)"));
    } else if (m.message_id() == jss_msg::ConfirmControl::code) {
      auto confirm = jss::decode_contents<jss_msg::ConfirmControl>(m.contents);
      if (confirm && confirm->response_code == jss_msg::confirm_control::kControlAccepted) raw->confirmed_ = true;
      if (confirm && confirm->response_code != 0 && confirm->response_code <= 2)
        raw->lose("re-request answered " +
                  std::string(to_string(static_cast<JssControlResponse>(confirm->response_code))));
    }
  });
  // The component's timeout decides how often control is requested again.
  rt::Duration period = options.refresh_when_unknown;
  if (auto timeout = query_jss_timeout(session, component, options.request_timeout)) {
    hold->timeout_s_ = *timeout;
    period = *timeout == 0 ? options.refresh_when_no_timeout : std::chrono::milliseconds(500) * *timeout;
  }
  hold->refresh_period_ = std::max(period, options.min_refresh);
  hold->next_refresh_ = session.clock().now() + hold->refresh_period_;
  if (hold->held())
    hold->refresh_timer_ = session.scheduler().call_at(hold->next_refresh_, [raw] {
      raw->refresh_timer_ = rt::kNoTimer;
      raw->refresh();
    });
  return hold;
}

JssControlHold::~JssControlHold() {
  if (held()) (void)release();
  if (refresh_timer_ != rt::kNoTimer) session_.scheduler().cancel(refresh_timer_);
  session_.unlisten(listener_);
}

void JssControlHold::refresh() {
  if (!held()) return;
  const auto now = session_.clock().now();
  const bool due = now >= next_refresh_;
  if (due || !confirmed_) {
    jss_msg::RequestControl request;
    request.authority = options_.authority;
    session_.send(component_, request);  // the Confirm Control comes to the listener
    if (due) {
      ++refreshes_;
      next_refresh_ = now + refresh_period_;
    }
    confirmed_ = false;
  }
  // Unconfirmed: again after a resend period (never past the next refresh).
  const auto next = confirmed_ ? next_refresh_ : std::min(next_refresh_, now + kQueryResendPeriod);
  refresh_timer_ = session_.scheduler().call_at(next, [this] {
    refresh_timer_ = rt::kNoTimer;
    refresh();
  });
}

void JssControlHold::lose(std::string reason) {
  if (!held()) return;
  state_ = State::lost;
  lost_reason_ = std::move(reason);
  if (refresh_timer_ != rt::kNoTimer) session_.scheduler().cancel(refresh_timer_);
  refresh_timer_ = rt::kNoTimer;
  if (on_lost_) on_lost_(lost_reason_);
}

bool JssControlHold::hold_for(std::optional<rt::Duration> limit) {
  const rt::Duration forever = std::chrono::hours(24 * 365);
  session_.run_until([this] { return !held(); }, limit.value_or(forever));
  return held();
}

Expected<void> JssControlHold::release(rt::Duration timeout) {
  if (!held()) return {};
  state_ = State::released;
  if (refresh_timer_ != rt::kNoTimer) session_.scheduler().cancel(refresh_timer_);
  refresh_timer_ = rt::kNoTimer;
  // Also after Ctrl-C: resend until the Reject Control (released) comes, at most kLongestCleanup.
  const auto contents = jss::encode_contents(jss_msg::ReleaseControl{});
  bool released = false;
  const auto id = session_.listen([&](const JssReceived& m) {
    if (m.source() == component_ && m.message_id() == jss_msg::RejectControl::code) released = true;
  });
  session_.resend_until([&] { session_.send_contents(component_, contents); }, [&] { return released; },
                        std::min(timeout, JssSession::kLongestCleanup), kQueryResendPeriod, /*through_stop=*/true);
  session_.unlisten(id);
  if (!released) return unexpected(no_reply_error(component_, timeout));
  return {};
}

}  // namespace jaus::ocu
