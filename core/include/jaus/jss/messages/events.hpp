// JSS Events v1.1 (docs/jss.md, "Events"). Unlike RA 3.3 events, the query inside
// Create/Update Event and the report inside Event are complete JSS messages,
// ID included, after a u32 byte count (codec::Embedded): decode them with
// jss::decode_contents<M>.
#pragma once

#include "jaus/jss/messages/common.hpp"
#include "jaus/messages/event_messages.hpp"

namespace jaus::jss::msg {

namespace event_type {
inline constexpr std::uint8_t kPeriodic = 0;
inline constexpr std::uint8_t kEveryChange = 1;
}  // namespace event_type
inline constexpr auto kEventType =
    wire::enum_of<std::uint8_t>({{event_type::kPeriodic, "periodic"}, {event_type::kEveryChange, "every_change"}});

// Reject Event Request response codes.
namespace reject_event {
inline constexpr std::uint8_t kPeriodicNotSupported = 1;
inline constexpr std::uint8_t kChangeBasedNotSupported = 2;
inline constexpr std::uint8_t kConnectionRefused = 3;
inline constexpr std::uint8_t kInvalidEventSetup = 4;
inline constexpr std::uint8_t kMessageNotSupported = 5;
inline constexpr std::uint8_t kInvalidEventIdForUpdate = 6;
}  // namespace reject_event
inline constexpr auto kRejectEventCode =
    wire::enum_of<std::uint8_t>({{reject_event::kPeriodicNotSupported, "periodic_events_not_supported"},
                                 {reject_event::kChangeBasedNotSupported, "change_based_events_not_supported"},
                                 {reject_event::kConnectionRefused, "connection_refused"},
                                 {reject_event::kInvalidEventSetup, "invalid_event_setup"},
                                 {reject_event::kMessageNotSupported, "message_not_supported"},
                                 {reject_event::kInvalidEventIdForUpdate, "invalid_event_id_for_update"}});

namespace command_result {
inline constexpr std::uint8_t kSuccessful = 0;
inline constexpr std::uint8_t kUnsuccessful = 1;
}  // namespace command_result
inline constexpr auto kCommandResult = wire::enum_of<std::uint8_t>(
    {{command_result::kSuccessful, "successful"}, {command_result::kUnsuccessful, "unsuccessful"}});

inline constexpr codec::Embedded<std::uint32_t> kMsg32{};

struct CreateEventBody {
  std::uint8_t request_id = 0;
  std::uint8_t event_type = event_type::kPeriodic;
  double requested_rate_hz = 0;              // 0..1092; 0 for every-change events
  std::vector<std::uint8_t> query_message;   // the query's contents, ID first
  bool operator==(const CreateEventBody&) const = default;
  static constexpr auto describe() {
    using B = CreateEventBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("event_type", &B::event_type, kEventType),
                           wire::field("requested_rate_hz", &B::requested_rate_hz, kEventRate),
                           wire::field("query_message", &B::query_message, kMsg32));
  }
};

struct UpdateEventBody {
  std::uint8_t request_id = 0;
  std::uint8_t event_type = event_type::kPeriodic;
  double requested_rate_hz = 0;
  std::uint8_t event_id = 0;
  std::vector<std::uint8_t> query_message;
  bool operator==(const UpdateEventBody&) const = default;
  static constexpr auto describe() {
    using B = UpdateEventBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("event_type", &B::event_type, kEventType),
                           wire::field("requested_rate_hz", &B::requested_rate_hz, kEventRate),
                           wire::field("event_id", &B::event_id, Byte{}),
                           wire::field("query_message", &B::query_message, kMsg32));
  }
};

// RA's, read in wire::Dialect::jss: no presence vector, no message code or
// response code; the event ID and the confirmed rate always sent.
using jaus::msg::CancelEventBody;
using jaus::msg::ConfirmEventRequestBody;
static_assert(wire::shared_with_jss<CancelEventBody>() && wire::shared_with_jss<ConfirmEventRequestBody>(),
              "a body JSS shares says so (kSharedWithJss)");

// JSS's Cancel Event: an event by its ID.
inline CancelEventBody cancel_event_by_id(std::uint8_t request_id, std::uint8_t event_id) {
  CancelEventBody cancel;
  cancel.request_id = request_id;
  cancel.event_id = event_id;
  return cancel;
}

struct RejectEventRequestBody {
  std::uint8_t request_id = 0;
  std::optional<std::uint8_t> response_code;
  std::optional<std::string> error_message;  // up to 80 characters, sent NUL padded
  bool operator==(const RejectEventRequestBody&) const = default;
  static constexpr auto describe() {
    using B = RejectEventRequestBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("request_id", &B::request_id, Byte{}),
                           wire::optional(0, "response_code", &B::response_code, kRejectEventCode),
                           wire::optional(1, "error_message", &B::error_message, wire::Text<80>{}));
  }
};

// Query Events: which events to report (a u8-tagged variant).
namespace events_filter {
inline constexpr std::uint8_t kMessageId = 0;  // events whose query has this message ID
inline constexpr std::uint8_t kEventType = 1;  // events of this type
inline constexpr std::uint8_t kEventId = 2;    // the event with this ID
inline constexpr std::uint8_t kAll = 3;        // every event (value 0)
}  // namespace events_filter
inline constexpr auto kEventsFilter = codec::tagged_of({{events_filter::kMessageId, "message_id", 2},
                                                        {events_filter::kEventType, "event_type", 1},
                                                        {events_filter::kEventId, "event_id", 1},
                                                        {events_filter::kAll, "all_events", 1}});

struct QueryEventsBody {
  codec::TaggedValue filter{events_filter::kAll, 0};
  bool operator==(const QueryEventsBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("filter", &QueryEventsBody::filter, kEventsFilter));
  }
};

struct EventEntry {
  std::uint8_t event_type = event_type::kPeriodic;
  std::uint8_t event_id = 0;
  std::vector<std::uint8_t> query_message;
  bool operator==(const EventEntry&) const = default;
  static constexpr auto describe() {
    using B = EventEntry;
    return std::make_tuple(wire::field("event_type", &B::event_type, kEventType),
                           wire::field("event_id", &B::event_id, Byte{}),
                           wire::field("query_message", &B::query_message, kMsg32));
  }
};

struct ReportEventsBody {
  std::vector<EventEntry> events;
  bool operator==(const ReportEventsBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("events", &ReportEventsBody::events, wire::Records<wire::Prefix<std::uint8_t>, EventEntry>{}));
  }
};

// RA's, read in wire::Dialect::jss: no report code; `report_message` is the
// report's whole contents, ID first (jss::decode_contents<M>).
using jaus::msg::EventBody;
static_assert(wire::shared_with_jss<EventBody>(), "a body JSS shares says so (kSharedWithJss)");

struct EventTimeoutBody {
  std::uint8_t timeout_min = 0;  // 0: events never time out
  bool operator==(const EventTimeoutBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("timeout_min", &EventTimeoutBody::timeout_min, Byte{}));
  }
};

struct CreateCommandEventBody {
  std::uint8_t request_id = 0;
  std::uint32_t maximum_allowed_duration_s = 0;
  std::vector<std::uint8_t> command_message;
  bool operator==(const CreateCommandEventBody&) const = default;
  static constexpr auto describe() {
    using B = CreateCommandEventBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("maximum_allowed_duration_s", &B::maximum_allowed_duration_s, UInt{}),
                           wire::field("command_message", &B::command_message, kMsg32));
  }
};

struct CommandEventBody {
  std::uint8_t event_id = 0;
  std::uint8_t command_result = command_result::kSuccessful;
  bool operator==(const CommandEventBody&) const = default;
  static constexpr auto describe() {
    using B = CommandEventBody;
    return std::make_tuple(wire::field("event_id", &B::event_id, Byte{}),
                           wire::field("command_result", &B::command_result, kCommandResult));
  }
};

using CreateEvent = Message<0x01F0, "Create Event", CreateEventBody>;
using UpdateEvent = Message<0x01F1, "Update Event", UpdateEventBody>;
using jaus::msg::CancelEvent;
using jaus::msg::ConfirmEventRequest;
using RejectEventRequest = Message<0x01F4, "Reject Event Request", RejectEventRequestBody>;
using CreateCommandEvent = Message<0x01F6, "Create Command Event", CreateCommandEventBody>;
using QueryEvents = Message<0x21F0, "Query Events", QueryEventsBody>;
using QueryEventTimeout = Message<0x21F2, "Query Event Timeout", Empty>;
using ReportEvents = Message<0x41F0, "Report Events", ReportEventsBody>;
using jaus::msg::Event;
using ReportEventTimeout = Message<0x41F2, "Report Event Timeout", EventTimeoutBody>;
using CommandEvent = Message<0x41F6, "Command Event", CommandEventBody>;

using EventsMessages = TypeList<CreateEvent, UpdateEvent, CancelEvent, ConfirmEventRequest, RejectEventRequest,
                                CreateCommandEvent, QueryEvents, QueryEventTimeout, ReportEvents, Event,
                                ReportEventTimeout, CommandEvent>;

}  // namespace jaus::jss::msg
