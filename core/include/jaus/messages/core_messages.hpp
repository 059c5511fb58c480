// Core subgroup: 0x0001-0x0011, 0x2001-0x2011, 0x4001-0x4011 (+ component control query/report).
#pragma once

#include "jaus/messages/common.hpp"
#include "jaus/messages/primary_status.hpp"

namespace jaus::msg {

struct AuthorityBody {
  std::uint8_t authority = 0;  // 0-255, 255 highest
  bool operator==(const AuthorityBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("authority", &AuthorityBody::authority, Byte{}));
  }
};

// Emergency code: bit 0 the Stop condition, bits 1-15 reserved.
inline constexpr auto kEmergencyCode = wire::bits_of<std::uint16_t>({"stop"});

struct EmergencyBody {
  std::uint16_t emergency_code = 1;  // bit 0: stop
  bool operator==(const EmergencyBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("emergency_code", &EmergencyBody::emergency_code, kEmergencyCode));
  }
};

struct CreateServiceConnectionBody {
  std::uint16_t command_code = 0;
  double periodic_rate_hz = 0;
  std::uint32_t presence_vector = 0;  // of the message to be sent on the SC
  bool operator==(const CreateServiceConnectionBody&) const = default;
  static constexpr auto describe() {
    using B = CreateServiceConnectionBody;
    return std::make_tuple(wire::field("command_code", &B::command_code, UShort{}),
                           wire::field("periodic_rate_hz", &B::periodic_rate_hz, kServiceRate),
                           wire::field("presence_vector", &B::presence_vector, UInt{}));
  }
};

// Response codes of Confirm Service Connection.
namespace sc_response {
inline constexpr std::uint8_t kCreated = 0;
inline constexpr std::uint8_t kNodeNotCapable = 1;
inline constexpr std::uint8_t kComponentNotCapable = 2;
inline constexpr std::uint8_t kInsufficientAuthority = 3;
inline constexpr std::uint8_t kRefused = 4;
inline constexpr std::uint8_t kInvalidParameters = 5;
inline constexpr std::uint8_t kCommandNotSupported = 6;
}  // namespace sc_response
inline constexpr auto kServiceConnectionResponse =
    wire::enum_of<std::uint8_t>({{sc_response::kCreated, "created"},
                                 {sc_response::kNodeNotCapable, "node_not_capable"},
                                 {sc_response::kComponentNotCapable, "component_not_capable"},
                                 {sc_response::kInsufficientAuthority, "insufficient_authority"},
                                 {sc_response::kRefused, "refused"},
                                 {sc_response::kInvalidParameters, "invalid_parameters"},
                                 {sc_response::kCommandNotSupported, "command_not_supported"}});

struct ConfirmServiceConnectionBody {
  std::uint16_t command_code = 0;
  std::uint8_t instance_id = 0;
  double confirmed_rate_hz = 0;
  std::uint8_t response_code = 0;
  bool operator==(const ConfirmServiceConnectionBody&) const = default;
  static constexpr auto describe() {
    using B = ConfirmServiceConnectionBody;
    return std::make_tuple(wire::field("command_code", &B::command_code, UShort{}),
                           wire::field("instance_id", &B::instance_id, Byte{}),
                           wire::field("confirmed_rate_hz", &B::confirmed_rate_hz, kServiceRate),
                           wire::field("response_code", &B::response_code, kServiceConnectionResponse));
  }
};

struct ServiceConnectionRefBody {
  std::uint16_t command_code = 0;
  std::uint8_t instance_id = 0;
  bool operator==(const ServiceConnectionRefBody&) const = default;
  static constexpr auto describe() {
    using B = ServiceConnectionRefBody;
    return std::make_tuple(wire::field("command_code", &B::command_code, UShort{}),
                           wire::field("instance_id", &B::instance_id, Byte{}));
  }
};

// Response codes of Confirm Component Control.
namespace control_response {
inline constexpr std::uint8_t kAccepted = 0;
inline constexpr std::uint8_t kNotSupported = 1;
inline constexpr std::uint8_t kNotAccepted = 2;
}  // namespace control_response
inline constexpr auto kControlResponse =
    wire::enum_of<std::uint8_t>({{control_response::kAccepted, "accepted"},
                                 {control_response::kNotSupported, "not_supported"},
                                 {control_response::kNotAccepted, "not_accepted"}});

// A body that is one response code, named by `Codes`: Confirm Component
// Control's here, and JSS's Confirm Control and Reject Control, each with its
// own names for the codes (jaus/jss/messages/core.hpp).
template <const auto& Codes>
struct ResponseCodeOf {
  std::uint8_t response_code = 0;
  bool operator==(const ResponseCodeOf&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("response_code", &ResponseCodeOf::response_code, Codes));
  }
};
using ResponseCodeBody = ResponseCodeOf<kControlResponse>;

struct TimeBody {
  std::optional<TimeStamp> time;
  std::optional<DateStamp> date;
  bool operator==(const TimeBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::optional(0, "time", &TimeBody::time, wire::Time{}),
                           wire::optional(1, "date", &TimeBody::date, wire::Date{}));
  }
};

// A query's presence vector: which optional fields the reply should carry
// (ANDed with what the responder has). A mask, not a layout: bits the report
// does not define are ignored (docs/wire-format.md, "Presence vectors").
template <std::unsigned_integral T>
struct PresenceQueryBody {
  T presence_vector = 0;
  bool operator==(const PresenceQueryBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("presence_vector", &PresenceQueryBody::presence_vector, wire::Int<T>{}));
  }
};


struct ComponentStatusBody {
  std::uint8_t primary_status = 0;    // bits 0-3 PrimaryStatus, bits 4-7 available
  std::uint32_t secondary_status = 0; // ours: bit 0 emergency held, 16-19 the component's, 20-31 stop counter (docs/components.md)
  bool operator==(const ComponentStatusBody&) const = default;
  static constexpr auto describe() {
    using B = ComponentStatusBody;
    return std::make_tuple(
        wire::field("primary_status", &B::primary_status, wire::enum_of<std::uint8_t>(kComponentStates)),
        wire::field("secondary_status", &B::secondary_status, UInt{}));
  }
};

struct ComponentControlBody {
  Address controller;  // subsystem, node, component, instance (all 0 when uncontrolled)
  std::uint8_t authority = 0;
  bool operator==(const ComponentControlBody&) const = default;
  static constexpr auto describe() {
    using B = ComponentControlBody;
    return std::make_tuple(wire::field("controller", &B::controller, wire::AddressCodec{}),
                           wire::field("authority", &B::authority, Byte{}));
  }
};

using SetComponentAuthority = Message<0x0001, "Set Component Authority", AuthorityBody>;
using Shutdown = Message<0x0002, "Shutdown", Empty>;
using Standby = Message<0x0003, "Standby", Empty>;
using Resume = Message<0x0004, "Resume", Empty>;
using Reset = Message<0x0005, "Reset", Empty>;
using SetEmergency = Message<0x0006, "Set Emergency", EmergencyBody>;
using ClearEmergency = Message<0x0007, "Clear Emergency", EmergencyBody>;
using CreateServiceConnection = Message<0x0008, "Create Service Connection", CreateServiceConnectionBody>;
using ConfirmServiceConnection = Message<0x0009, "Confirm Service Connection", ConfirmServiceConnectionBody>;
using ActivateServiceConnection = Message<0x000A, "Activate Service Connection", ServiceConnectionRefBody>;
using SuspendServiceConnection = Message<0x000B, "Suspend Service Connection", ServiceConnectionRefBody>;
using TerminateServiceConnection = Message<0x000C, "Terminate Service Connection", ServiceConnectionRefBody>;
using RequestComponentControl = Message<0x000D, "Request Component Control", AuthorityBody>;
using ReleaseComponentControl = Message<0x000E, "Release Component Control", Empty>;
using ConfirmComponentControl = Message<0x000F, "Confirm Component Control", ResponseCodeBody>;
using RejectComponentControl = Message<0x0010, "Reject Component Control", Empty>;
using SetTime = Message<0x0011, "Set Time", TimeBody>;

using QueryComponentAuthority = Message<0x2001, "Query Component Authority", Empty>;
using QueryComponentStatus = Message<0x2002, "Query Component Status", Empty>;
using QueryComponentControl = Message<0x200D, "Query Component Control", Empty>;
using QueryTime = Message<0x2011, "Query Time", PresenceQueryBody<std::uint8_t>>;

using ReportComponentAuthority = Message<0x4001, "Report Component Authority", AuthorityBody>;
using ReportComponentStatus = Message<0x4002, "Report Component Status", ComponentStatusBody>;
using ReportComponentControl = Message<0x400D, "Report Component Control", ComponentControlBody>;
using ReportTime = Message<0x4011, "Report Time", TimeBody>;

using CoreMessages =
    TypeList<SetComponentAuthority, Shutdown, Standby, Resume, Reset, SetEmergency, ClearEmergency,
             CreateServiceConnection, ConfirmServiceConnection, ActivateServiceConnection, SuspendServiceConnection,
             TerminateServiceConnection, RequestComponentControl, ReleaseComponentControl, ConfirmComponentControl,
             RejectComponentControl, SetTime, QueryComponentAuthority, QueryComponentStatus, QueryComponentControl,
             QueryTime, ReportComponentAuthority, ReportComponentStatus, ReportComponentControl, ReportTime>;

}  // namespace jaus::msg
