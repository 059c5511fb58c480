// JSS core services v1.1 (docs/jss.md, "Core services"): Access Control,
// Management, Liveness, Time (whose messages are RA's bytes).
#pragma once

#include "jaus/jss/messages/common.hpp"
#include "jaus/messages/communications_messages.hpp"

namespace jaus::jss::msg {

// Confirm Control response codes.
namespace confirm_control {
inline constexpr std::uint8_t kControlAccepted = 0;
inline constexpr std::uint8_t kNotAvailable = 1;
inline constexpr std::uint8_t kInsufficientAuthority = 2;
}  // namespace confirm_control
inline constexpr auto kConfirmControlCode =
    wire::enum_of<std::uint8_t>({{confirm_control::kControlAccepted, "control_accepted"},
                                 {confirm_control::kNotAvailable, "not_available"},
                                 {confirm_control::kInsufficientAuthority, "insufficient_authority"}});

// Reject Control response codes (RA's Reject Component Control has no body).
namespace reject_control {
inline constexpr std::uint8_t kControlReleased = 0;
inline constexpr std::uint8_t kNotAvailable = 1;
}  // namespace reject_control
inline constexpr auto kRejectControlCode = wire::enum_of<std::uint8_t>(
    {{reject_control::kControlReleased, "control_released"}, {reject_control::kNotAvailable, "not_available"}});

using ConfirmControlBody = jaus::msg::ResponseCodeOf<kConfirmControlCode>;
using RejectControlBody = jaus::msg::ResponseCodeOf<kRejectControlCode>;

// Report Control: the controlling client (0.0.0 when not controlled) and its authority.
struct ReportControlBody {
  JssId controller;
  std::uint8_t authority = 0;
  bool operator==(const ReportControlBody&) const = default;
  static constexpr auto describe() {
    using B = ReportControlBody;
    return std::make_tuple(wire::field("controller", &B::controller, codec::IdCodec{}),
                           wire::field("authority", &B::authority, Byte{}));
  }
};

// Report Timeout: the access control timeout, 0 = none.
struct TimeoutBody {
  std::uint8_t timeout_s = 0;
  bool operator==(const TimeoutBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("timeout_s", &TimeoutBody::timeout_s, Byte{}));
  }
};

// Report Status: status 0-5 as RA's primary status; the u32 is reserved (send 0).
struct StatusBody {
  std::uint8_t status = 0;
  std::uint32_t reserved = 0;
  bool operator==(const StatusBody&) const = default;
  static constexpr auto describe() {
    using B = StatusBody;
    return std::make_tuple(wire::field("status", &B::status, wire::enum_of<std::uint8_t>(kComponentStates)),
                           wire::field("reserved", &B::reserved, UInt{}));
  }
};

// Access Control.
using SetAuthority = Message<0x0001, "Set Authority", AuthorityBody>;
using RequestControl = Message<0x000D, "Request Control", AuthorityBody>;
using ReleaseControl = Message<0x000E, "Release Control", Empty>;
using ConfirmControl = Message<0x000F, "Confirm Control", ConfirmControlBody>;
using RejectControl = Message<0x0010, "Reject Control", RejectControlBody>;
using QueryAuthority = Message<0x2001, "Query Authority", Empty>;
using QueryTimeout = Message<0x2003, "Query Timeout", Empty>;
using QueryControl = Message<0x200D, "Query Control", Empty>;
using ReportAuthority = Message<0x4001, "Report Authority", AuthorityBody>;
using ReportTimeout = Message<0x4003, "Report Timeout", TimeoutBody>;
using ReportControl = Message<0x400D, "Report Control", ReportControlBody>;

// Management.
using jaus::msg::Shutdown;
using jaus::msg::Standby;
using jaus::msg::Resume;
using jaus::msg::Reset;
using jaus::msg::SetEmergency;
using jaus::msg::ClearEmergency;
using QueryStatus = Message<0x2002, "Query Status", Empty>;
using ReportStatus = Message<0x4002, "Report Status", StatusBody>;

// Time.
using jaus::msg::SetTime;
using QueryTime = Message<0x2011, "Query Time", QueryPresence8Body>;
using jaus::msg::ReportTime;

// Liveness.
using jaus::msg::QueryHeartbeatPulse;
using jaus::msg::ReportHeartbeatPulse;

using AccessControlMessages = TypeList<SetAuthority, RequestControl, ReleaseControl, ConfirmControl, RejectControl,
                                       QueryAuthority, QueryTimeout, QueryControl, ReportAuthority, ReportTimeout,
                                       ReportControl>;
using ManagementMessages =
    TypeList<Shutdown, Standby, Resume, Reset, SetEmergency, ClearEmergency, QueryStatus, ReportStatus>;
using TimeMessages = TypeList<SetTime, QueryTime, ReportTime>;
using LivenessMessages = TypeList<QueryHeartbeatPulse, ReportHeartbeatPulse>;

}  // namespace jaus::jss::msg
