// RA 3.2/3.3 events: 0x01F0-0x01F3 and 0x41F1 (docs/wire-format.md; the optional
// fields of Create/Update Event follow the RA 3.3 peers' presence bits).
#pragma once

#include "jaus/jss/codecs.hpp"
#include "jaus/messages/common.hpp"

namespace jaus::msg {

// Event types: 0 periodic, 1 every change, 2 first change, 3 first change in
// and out of boundary, 4 periodic without repeats, 5 one time on demand.
// Boundaries: 0 equal, 1 not equal, 2 inside inclusive, 3 inside exclusive,
// 4 outside inclusive, 5 outside exclusive.
inline constexpr auto kEventType = wire::enum_of<std::uint8_t>({{0, "periodic"},
                                                                {1, "every_change"},
                                                                {2, "first_change"},
                                                                {3, "first_change_in_and_out_of_boundary"},
                                                                {4, "periodic_without_repeats"},
                                                                {5, "one_time"}});
inline constexpr auto kEventBoundary = wire::enum_of<std::uint8_t>({{0, "equal"},
                                                                    {1, "not_equal"},
                                                                    {2, "inside_inclusive"},
                                                                    {3, "inside_exclusive"},
                                                                    {4, "outside_inclusive"},
                                                                    {5, "outside_exclusive"}});

struct EventRequestBody {
  std::uint8_t request_id = 0;
  std::uint16_t report_code = 0;
  std::uint8_t event_type = 0;
  std::optional<std::uint8_t> event_boundary;
  std::optional<std::uint8_t> limit_data_field;
  std::optional<wire::EventLimit> lower_limit;
  std::optional<wire::EventLimit> upper_limit;
  std::optional<wire::EventLimit> state_limit;
  std::optional<double> minimum_rate_hz;
  std::optional<double> requested_rate_hz;
  std::optional<std::vector<std::uint8_t>> query_message;  // payload of the query (no header)
  bool operator==(const EventRequestBody&) const = default;
  static constexpr auto describe() {
    using B = EventRequestBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("report_code", &B::report_code, UShort{}),
                           wire::field("event_type", &B::event_type, kEventType),
                           wire::optional(0, "event_boundary", &B::event_boundary, kEventBoundary),
                           wire::optional(1, "limit_data_field", &B::limit_data_field, Byte{}),
                           wire::optional(2, "lower_limit", &B::lower_limit, wire::EventLimitCodec{}),
                           wire::optional(3, "upper_limit", &B::upper_limit, wire::EventLimitCodec{}),
                           wire::optional(4, "state_limit", &B::state_limit, wire::EventLimitCodec{}),
                           wire::optional(5, "minimum_rate_hz", &B::minimum_rate_hz, kServiceRate),
                           wire::optional(6, "requested_rate_hz", &B::requested_rate_hz, kServiceRate),
                           wire::optional(7, "query_message", &B::query_message, wire::Bytes<std::uint32_t>{}));
  }
};

// Update Event: as Create Event, with the event ID before the query message.
struct EventUpdateBody {
  std::uint8_t request_id = 0;
  std::uint16_t report_code = 0;
  std::uint8_t event_type = 0;
  std::optional<std::uint8_t> event_boundary;
  std::optional<std::uint8_t> limit_data_field;
  std::optional<wire::EventLimit> lower_limit;
  std::optional<wire::EventLimit> upper_limit;
  std::optional<wire::EventLimit> state_limit;
  std::optional<double> minimum_rate_hz;
  std::optional<double> requested_rate_hz;
  std::uint8_t event_id = 0;
  std::optional<std::vector<std::uint8_t>> query_message;
  bool operator==(const EventUpdateBody&) const = default;
  static constexpr auto describe() {
    using B = EventUpdateBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("report_code", &B::report_code, UShort{}),
                           wire::field("event_type", &B::event_type, kEventType),
                           wire::optional(0, "event_boundary", &B::event_boundary, kEventBoundary),
                           wire::optional(1, "limit_data_field", &B::limit_data_field, Byte{}),
                           wire::optional(2, "lower_limit", &B::lower_limit, wire::EventLimitCodec{}),
                           wire::optional(3, "upper_limit", &B::upper_limit, wire::EventLimitCodec{}),
                           wire::optional(4, "state_limit", &B::state_limit, wire::EventLimitCodec{}),
                           wire::optional(5, "minimum_rate_hz", &B::minimum_rate_hz, kServiceRate),
                           wire::optional(6, "requested_rate_hz", &B::requested_rate_hz, kServiceRate),
                           wire::field("event_id", &B::event_id, Byte{}),
                           wire::optional(7, "query_message", &B::query_message, wire::Bytes<std::uint32_t>{}));
  }
};

// RA cancels by message code or event ID; JSS by event ID alone, with no
// presence vector.
struct CancelEventBody {
  std::uint8_t request_id = 0;
  std::optional<std::uint16_t> message_code;  // RA only
  std::optional<std::uint8_t> event_id;       // JSS: always sent
  bool operator==(const CancelEventBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = CancelEventBody;
    using wire::Dialect;
    return std::make_tuple(wire::presence_vector<std::uint8_t>().not_in(Dialect::jss),
                           wire::field("request_id", &B::request_id, Byte{}),
                           wire::optional(0, "message_code", &B::message_code, UShort{}).not_in(Dialect::jss),
                           wire::optional(1, "event_id", &B::event_id, Byte{}).always_in(Dialect::jss));
  }
};

// Confirm Event Request response codes, as the RA 3.3 peers (and our node
// manager) send them; Part 3 defines only 0.
namespace event_response {
inline constexpr std::uint8_t kSuccessful = 0;
inline constexpr std::uint8_t kPeriodicNotSupported = 1;
inline constexpr std::uint8_t kChangeNotSupported = 2;
inline constexpr std::uint8_t kRefused = 3;
inline constexpr std::uint8_t kInvalidSetup = 4;
inline constexpr std::uint8_t kMessageNotSupported = 5;
inline constexpr std::uint8_t kInvalidEventIdForUpdate = 6;
}  // namespace event_response

inline constexpr auto kEventResponse =
    wire::enum_of<std::uint8_t>({{event_response::kSuccessful, "successful"},
                                 {event_response::kPeriodicNotSupported, "periodic_not_supported"},
                                 {event_response::kChangeNotSupported, "change_based_not_supported"},
                                 {event_response::kRefused, "connection_refused"},
                                 {event_response::kInvalidSetup, "invalid_event_setup"},
                                 {event_response::kMessageNotSupported, "message_not_supported"},
                                 {event_response::kInvalidEventIdForUpdate, "invalid_event_id_for_update"}});

// JSS confirms with the request and event IDs and the rate, always, and no
// presence vector; a refusal is its own message (Reject Event Request).
struct ConfirmEventRequestBody {
  std::uint8_t request_id = 0;
  std::uint16_t message_code = 0;  // RA only
  std::uint8_t event_id = 0;
  std::optional<double> confirmed_rate_hz;  // JSS: always sent
  std::uint8_t response_code = 0;           // kEventResponse; RA only
  bool operator==(const ConfirmEventRequestBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = ConfirmEventRequestBody;
    using wire::Dialect;
    return std::make_tuple(
        wire::presence_vector<std::uint8_t>().not_in(Dialect::jss), wire::field("request_id", &B::request_id, Byte{}),
        wire::field("message_code", &B::message_code, UShort{}).not_in(Dialect::jss),
        wire::field("event_id", &B::event_id, Byte{}),
        wire::optional(0, "confirmed_rate_hz", &B::confirmed_rate_hz, kServiceRate).always_in(Dialect::jss),
        wire::field("response_code", &B::response_code, kEventResponse).not_in(Dialect::jss));
  }
};

// RA's Event carries the report's command code and its payload; JSS's the
// whole report, ID first, after a byte count that counts the ID too
// (docs/jss.md, "Events"). One member holds the report as its dialect embeds it.
struct EventBody {
  std::uint8_t event_id = 0;
  std::uint16_t report_code = 0;  // RA only
  std::uint8_t sequence_number = 0;
  std::vector<std::uint8_t> report_message;  // RA: the report's payload (no header); JSS: its contents, ID first
  bool operator==(const EventBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = EventBody;
    using wire::Dialect;
    using Report = wire::PerDialect<wire::Bytes<std::uint32_t>, jss::codec::Embedded<std::uint32_t>>;
    return std::make_tuple(wire::field("event_id", &B::event_id, Byte{}),
                           wire::field("report_code", &B::report_code, UShort{}).not_in(Dialect::jss),
                           wire::field("sequence_number", &B::sequence_number, Byte{}),
                           wire::field("report_message", &B::report_message, Report{}));
  }
};

using CreateEvent = Message<0x01F0, "Create Event", EventRequestBody>;
using UpdateEvent = Message<0x01F1, "Update Event", EventUpdateBody>;
using CancelEvent = Message<0x01F2, "Cancel Event", CancelEventBody>;
using ConfirmEventRequest = Message<0x01F3, "Confirm Event Request", ConfirmEventRequestBody>;
using Event = Message<0x41F1, "Event", EventBody>;

using EventMessages = TypeList<CreateEvent, UpdateEvent, CancelEvent, ConfirmEventRequest, Event>;

}  // namespace jaus::msg
