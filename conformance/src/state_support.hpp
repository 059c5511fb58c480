// States and control for the cases that move a component: its primary
// status, its controller, and control taken for a case and always released.
// Private to the conformance library.
#pragma once

#include <string>

#include "case_support.hpp"
#include "jaus/messages/core_messages.hpp"

namespace jaus::conform::detail {

inline std::string state_text(msg::PrimaryStatus state) {
  switch (state) {
    case msg::PrimaryStatus::initialize:
      return "Initialize";
    case msg::PrimaryStatus::ready:
      return "Ready";
    case msg::PrimaryStatus::standby:
      return "Standby";
    case msg::PrimaryStatus::shutdown:
      return "Shutdown";
    case msg::PrimaryStatus::failure:
      return "Failure";
    case msg::PrimaryStatus::emergency:
      return "Emergency";
  }
  return "state " + std::to_string(static_cast<int>(state));
}

inline Expected<msg::PrimaryStatus> primary_status(CaseContext& c) {
  auto report = ask<msg::ReportComponentStatus>(c, msg::QueryComponentStatus{});
  if (!report) return unexpected(report.error());
  return static_cast<msg::PrimaryStatus>(report->primary_status & 0x0F);
}

// Who controls the component (0.0.0.0 when nobody does).
inline Expected<Address> current_controller(CaseContext& c) {
  auto report = ask<msg::ReportComponentControl>(c, msg::QueryComponentControl{});
  if (!report) return unexpected(report.error());
  return report->controller;
}

// Control of the component for one case, at the highest authority unless
// told, by the runner or its second OCU (`by`), released when the case ends
// however it ends.
class ControlHeld {
 public:
  explicit ControlHeld(CaseContext& c, std::uint8_t authority = 255) : ControlHeld(c, authority, c.session) {}
  ControlHeld(CaseContext& c, std::uint8_t authority, ocu::OcuSession& by) : c_(c), by_(by), authority_(authority) {
    request();
  }
  ~ControlHeld() { release(); }
  // Releases control now (a case that checks what a release does). Also
  // after an ask_again() that went unanswered: control may still be held.
  void release() {
    if (may_hold_) send_from(c_, by_, c_.target(), msg::ReleaseComponentControl{});
    granted_ = may_hold_ = false;
  }
  ControlHeld(const ControlHeld&) = delete;
  ControlHeld& operator=(const ControlHeld&) = delete;

  // Asks again at the same authority, with no release first (a controller
  // asking again keeps control): after something that may have ended it.
  bool ask_again() {
    request();
    return granted_;
  }

  bool granted() const { return granted_; }
  const std::string& why() const { return why_; }

 private:
  void request() {
    granted_ = false;
    why_.clear();
    send_from(c_, by_, c_.target(), msg::RequestComponentControl{{authority_}});
    auto reply = await_at(c_, by_, {msg::ConfirmComponentControl::code, msg::RejectComponentControl::code});
    if (!reply) {
      why_ = reply.error().message();
      return;
    }
    if (reply->header.command_code == msg::RejectComponentControl::code) {
      why_ = "Reject Component Control";
      return;
    }
    auto confirm = decode<msg::ConfirmComponentControl>(c_, *reply);
    if (!confirm) {
      why_ = confirm.error().message();
      return;
    }
    granted_ = confirm->response_code == msg::control_response::kAccepted;
    may_hold_ = may_hold_ || granted_;
    if (!granted_) why_ = "Confirm Component Control response " + std::to_string(confirm->response_code);
  }

  CaseContext& c_;
  ocu::OcuSession& by_;
  std::uint8_t authority_;
  bool granted_ = false;
  bool may_hold_ = false;  // granted since the last release
  std::string why_;
};

}  // namespace jaus::conform::detail
