#include "jss_case_support.hpp"

namespace jaus::conform::jss_detail {

Expected<std::uint8_t> status_of(JssCaseContext& c) {
  auto report = ask<jss::msg::ReportStatus>(c, jss::msg::QueryStatus{});
  if (!report) return unexpected(report.error());
  return static_cast<std::uint8_t>(report->status & 0x0F);
}

std::string status_name(std::uint8_t status) {
  static constexpr const char* names[] = {"Init", "Ready", "Standby", "Shutdown", "Failure", "Emergency"};
  return status < std::size(names) ? names[status] : "status " + std::to_string(status);
}

Expected<ControlSeen> control_of(JssCaseContext& c) {
  auto report = ask<jss::msg::ReportControl>(c, jss::msg::QueryControl{});
  if (!report) return unexpected(report.error());
  return ControlSeen{report->controller, report->authority};
}

FreeTarget free_target(JssCaseContext& c) {
  auto control = control_of(c);
  if (!control) return {0, fail("Query Control: " + control.error().message())};
  if (control->controller.is_valid())
    return {0, skip("controlled by " + control->controller.to_string() + ": the case would take it away")};
  auto authority = ask<jss::msg::ReportAuthority>(c, jss::msg::QueryAuthority{});
  if (!authority) return {0, fail("Query Authority: " + authority.error().message())};
  return {authority->authority, std::nullopt};
}

JssControlHeld::JssControlHeld(JssCaseContext& c, ocu::JssSession& who, std::uint8_t authority)
    : c_(c), who_(who), authority_(authority) {
  send_from(c_, who_, c_.target(), jss::msg::RequestControl{{authority_}});
  auto reply = await_from(c_, who_, {jss::msg::ConfirmControl::code});
  if (!reply) {
    what_ = "no Confirm Control: " + reply.error().message();
    return;
  }
  auto confirm = decode<jss::msg::ConfirmControl>(*reply);
  if (!confirm) {
    what_ = confirm.error().message();
    return;
  }
  response_ = confirm->response_code;
  what_ = "Confirm Control " + std::to_string(*response_);
  held_ = granted();
}

void JssControlHeld::renew() { send_from(c_, who_, c_.target(), jss::msg::RequestControl{{authority_}}); }

void JssControlHeld::release() {
  if (!held_) return;
  held_ = false;
  send_from(c_, who_, c_.target(), jss::msg::ReleaseControl{});
  // Its Reject Control (0) is awaited briefly, so it does not reach the next case.
  (void)await_from(c_, who_, {jss::msg::RejectControl::code}, std::chrono::milliseconds(500));
}

JssControlHeld::~JssControlHeld() { release(); }

Expected<void> bring_to(JssCaseContext& c, std::uint8_t status) {
  auto now = status_of(c);
  if (!now) return unexpected(now.error());
  if (*now == status) return {};
  if (status == kReady) send(c, jss::msg::Resume{});
  else if (status == kStandby) send(c, jss::msg::Standby{});
  // The status follows the RA component's, which acts on the next tick.
  const auto until = c.session.clock().now() + c.reply_timeout;
  for (;;) {
    now = status_of(c);
    if (!now) return unexpected(now.error());
    if (*now == status) return {};
    if (c.session.clock().now() >= until)
      return unexpected(make_error(ErrorCode::invalid_argument, "still " + status_name(*now) + " after " +
                                                                    (status == kReady ? "Resume" : "Standby")));
    pause(c, std::chrono::milliseconds(100));
  }
}

}  // namespace jaus::conform::jss_detail
