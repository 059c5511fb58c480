// JSS mobility v1.0 (docs/jss.md, "Mobility services"): Local Waypoint Driver, List
// Manager and Local Waypoint List Driver. RA has a numbered waypoint list and
// no list manager: the face keeps the elements (jss_face/).
#pragma once

#include "jaus/jss/messages/common.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::jss::msg {

// RA's, read in wire::Dialect::jss: no waypoint number (the list manager
// keeps the elements), tolerances in bits 4 and 5, z over -100000..100000.
using jaus::msg::LocalWaypointBody;
static_assert(wire::shared_with_jss<LocalWaypointBody>(), "a body JSS shares says so (kSharedWithJss)");

// RA's, read in wire::Dialect::jss: 0..327.67 m/s (RA: 0..10000).
using jaus::msg::TravelSpeedBody;
static_assert(wire::shared_with_jss<TravelSpeedBody>(), "a body JSS shares says so (kSharedWithJss)");

// ---- List Manager ----------------------------------------------------------

namespace element_uid {
inline constexpr std::uint16_t kNone = 0;     // previous: the head; next: the tail
inline constexpr std::uint16_t kAll = 65535;  // Delete Element: every element
}  // namespace element_uid

namespace element_format {
inline constexpr std::uint8_t kJausMessage = 0;
inline constexpr std::uint8_t kUserDefined = 1;
}  // namespace element_format
inline constexpr auto kElementFormat = wire::enum_of<std::uint8_t>(
    {{element_format::kJausMessage, "jaus_message"}, {element_format::kUserDefined, "user_defined"}});

// Reject Element Request response codes.
namespace reject_element {
inline constexpr std::uint8_t kInvalidElementId = 1;
inline constexpr std::uint8_t kInvalidPreviousElement = 2;
inline constexpr std::uint8_t kInvalidNextElement = 3;
inline constexpr std::uint8_t kUnsupportedElementType = 4;
inline constexpr std::uint8_t kElementIdNotFound = 5;
inline constexpr std::uint8_t kOutOfMemory = 6;
inline constexpr std::uint8_t kUnspecifiedError = 7;
}  // namespace reject_element
inline constexpr auto kRejectElementCode =
    wire::enum_of<std::uint8_t>({{reject_element::kInvalidElementId, "invalid_element_id"},
                                 {reject_element::kInvalidPreviousElement, "invalid_previous_element"},
                                 {reject_element::kInvalidNextElement, "invalid_next_element"},
                                 {reject_element::kUnsupportedElementType, "unsupported_element_type"},
                                 {reject_element::kElementIdNotFound, "element_id_not_found"},
                                 {reject_element::kOutOfMemory, "out_of_memory"},
                                 {reject_element::kUnspecifiedError, "unspecified_error"}});

// One list element: its UID, its neighbours' UIDs and its data (for the
// Local Waypoint List Driver: format 0 and a whole Set Local Waypoint, ID
// first). Also the body of Report Element.
struct ElementRecord {
  std::uint16_t element_uid = 0;   // 0 and 65535 reserved
  std::uint16_t previous_uid = 0;  // 0: the head
  std::uint16_t next_uid = 0;      // 0: the tail
  std::uint8_t format = element_format::kJausMessage;
  std::vector<std::uint8_t> element_data;
  bool operator==(const ElementRecord&) const = default;
  static constexpr auto describe() {
    using B = ElementRecord;
    return std::make_tuple(wire::field("element_uid", &B::element_uid, UShort{}),
                           wire::field("previous_uid", &B::previous_uid, UShort{}),
                           wire::field("next_uid", &B::next_uid, UShort{}),
                           wire::field("format", &B::format, kElementFormat),
                           wire::field("element_data", &B::element_data, codec::Embedded<std::uint16_t>{0}));
  }
};

struct SetElementBody {
  std::uint8_t request_id = 0;
  std::vector<ElementRecord> elements;
  bool operator==(const SetElementBody&) const = default;
  static constexpr auto describe() {
    using B = SetElementBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("elements", &B::elements, wire::Records<wire::Prefix<std::uint8_t>, ElementRecord>{}));
  }
};

struct DeleteElementBody {
  std::uint8_t request_id = 0;
  std::vector<std::uint16_t> element_uids;  // 65535: all
  bool operator==(const DeleteElementBody&) const = default;
  static constexpr auto describe() {
    using B = DeleteElementBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("element_uids", &B::element_uids, wire::Array<wire::Prefix<std::uint8_t>, UShort>{}));
  }
};

struct ElementRequestBody {
  std::uint8_t request_id = 0;
  bool operator==(const ElementRequestBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("request_id", &ElementRequestBody::request_id, Byte{}));
  }
};

struct RejectElementRequestBody {
  std::uint8_t request_id = 0;
  std::uint8_t response_code = reject_element::kUnspecifiedError;
  bool operator==(const RejectElementRequestBody&) const = default;
  static constexpr auto describe() {
    using B = RejectElementRequestBody;
    return std::make_tuple(wire::field("request_id", &B::request_id, Byte{}),
                           wire::field("response_code", &B::response_code, kRejectElementCode));
  }
};

// Query Element, Report Active Element (0: nothing executing).
struct ElementUidBody {
  std::uint16_t element_uid = 0;
  bool operator==(const ElementUidBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("element_uid", &ElementUidBody::element_uid, UShort{}));
  }
};

struct ElementListBody {
  std::vector<std::uint16_t> element_uids;
  bool operator==(const ElementListBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("element_uids", &ElementListBody::element_uids,
                                       wire::Array<wire::Prefix<std::uint16_t>, UShort>{}));
  }
};

struct ElementCountBody {
  std::uint16_t element_count = 0;
  bool operator==(const ElementCountBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("element_count", &ElementCountBody::element_count, UShort{}));
  }
};

// Execute List: the speed, and the element to start at (absent: only the speed changes).
struct ExecuteListBody {
  double speed_mps = 0;  // 0..327.67
  std::optional<std::uint16_t> element_uid;
  bool operator==(const ExecuteListBody&) const = default;
  static constexpr auto describe() {
    using B = ExecuteListBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("speed_mps", &B::speed_mps, kTravelSpeed),
                           wire::optional(0, "element_uid", &B::element_uid, UShort{}));
  }
};

// Local Waypoint Driver.
using jaus::msg::SetTravelSpeed;
using jaus::msg::SetLocalWaypoint;
using jaus::msg::QueryTravelSpeed;
using QueryLocalWaypoint = Message<0x240D, "Query Local Waypoint", QueryPresence8Body>;
using jaus::msg::ReportTravelSpeed;
using jaus::msg::ReportLocalWaypoint;
// List Manager.
using SetElement = Message<0x041A, "Set Element", SetElementBody>;
using DeleteElement = Message<0x041B, "Delete Element", DeleteElementBody>;
using ConfirmElementRequest = Message<0x041C, "Confirm Element Request", ElementRequestBody>;
using RejectElementRequest = Message<0x041D, "Reject Element Request", RejectElementRequestBody>;
using QueryElement = Message<0x241A, "Query Element", ElementUidBody>;
using QueryElementList = Message<0x241B, "Query Element List", Empty>;
using QueryElementCount = Message<0x241C, "Query Element Count", Empty>;
using ReportElement = Message<0x441A, "Report Element", ElementRecord>;
using ReportElementList = Message<0x441B, "Report Element List", ElementListBody>;
using ReportElementCount = Message<0x441C, "Report Element Count", ElementCountBody>;
// Local Waypoint List Driver.
using ExecuteList = Message<0x041E, "Execute List", ExecuteListBody>;
using QueryActiveElement = Message<0x241E, "Query Active Element", Empty>;
using ReportActiveElement = Message<0x441E, "Report Active Element", ElementUidBody>;

using WaypointMessages =
    TypeList<SetTravelSpeed, SetLocalWaypoint, QueryTravelSpeed, QueryLocalWaypoint, ReportTravelSpeed,
             ReportLocalWaypoint, SetElement, DeleteElement, ConfirmElementRequest, RejectElementRequest, QueryElement,
             QueryElementList, QueryElementCount, ReportElement, ReportElementList, ReportElementCount, ExecuteList,
             QueryActiveElement, ReportActiveElement>;

}  // namespace jaus::jss::msg
