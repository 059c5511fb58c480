#include "jaus/messages/catalogue.hpp"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "catalogue_entries.hpp"

namespace jaus::msg {

namespace {

using detail::code_text;

std::vector<MessageInfo> sorted_by_code(std::vector<MessageInfo> all) {
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.code < b.code; });
  return all;
}

std::vector<MessageInfo> ra_set() {
  std::vector<MessageInfo> all;
  for (auto part : {detail::core_entries(), detail::communications_entries(), detail::platform_state_entries(),
                    detail::platform_waypoint_entries(), detail::manipulator_entries(),
                    detail::environment_entries(), detail::discovery_and_event_entries()}) {
    all.insert(all.end(), part.begin(), part.end());
  }
  return sorted_by_code(std::move(all));
}

Error json_error(std::string_view field, std::string detail) {
  return Error{ErrorCode::json, 0, std::string(field), std::move(detail)};
}

constexpr std::string_view kAckNakNames[] = {"none", "ack_requested", "nak", "ack"};

std::string_view data_flag_name(DataFlag flag) {
  switch (flag) {
    case DataFlag::single: return "single";
    case DataFlag::first: return "first";
    case DataFlag::middle: return "middle";
    case DataFlag::retransmitted: return "retransmitted";
    case DataFlag::last: return "last";
  }
  return "single";
}

template <class T>
bool small_integer(const nlohmann::ordered_json& j, unsigned max, T& out) {
  if (!j.is_number_unsigned() || j.get<std::uint64_t>() > max) return false;
  out = static_cast<T>(j.get<std::uint64_t>());
  return true;
}

// Header keys that the JSON may set; command_code and data_size are derived.
Expected<Header, Error> header_from_json(const nlohmann::ordered_json& j) {
  Header h;
  if (j.is_null()) return h;
  if (!j.is_object()) return unexpected(json_error("header", "expected an object"));
  for (const auto& [key, value] : j.items()) {
    bool ok = true;
    if (key == "priority") {
      ok = small_integer(value, 15, h.priority);
    } else if (key == "ack_nak") {
      ok = false;
      for (unsigned i = 0; i < 4; ++i)
        if ((value.is_string() && value.get<std::string>() == kAckNakNames[i]) ||
            (value.is_number_unsigned() && value.get<std::uint64_t>() == i)) {
          h.ack_nak = static_cast<AckNak>(i);
          ok = true;
        }
    } else if (key == "service_connection") {
      ok = value.is_boolean();
      if (ok) h.service_connection = value.get<bool>();
    } else if (key == "experimental") {
      ok = value.is_boolean();
      if (ok) h.experimental = value.get<bool>();
    } else if (key == "version") {
      ok = small_integer(value, 63, h.version);
    } else if (key == "destination" || key == "source") {
      const auto address = value.is_string() ? Address::parse(value.get<std::string>()) : std::nullopt;
      ok = address.has_value();
      if (ok) (key == "destination" ? h.destination : h.source) = *address;
    } else if (key == "data_flag") {
      ok = false;
      for (auto flag : {DataFlag::single, DataFlag::first, DataFlag::middle, DataFlag::retransmitted, DataFlag::last})
        if ((value.is_string() && value.get<std::string>() == data_flag_name(flag)) ||
            (value.is_number_unsigned() && value.get<std::uint64_t>() == static_cast<unsigned>(flag))) {
          h.data_flag = flag;
          ok = true;
        }
    } else if (key == "sequence") {
      ok = small_integer(value, 0xFFFF, h.sequence);
    } else if (key == "data_size" || key == "command_code") {
      // Derived from the message; accepted so that decode output round-trips.
    } else {
      return unexpected(json_error("header", "unknown key '" + key + "'"));
    }
    if (!ok) return unexpected(json_error("header", "bad value for '" + key + "'"));
  }
  return h;
}

}  // namespace

namespace detail {
Expected<std::uint16_t, Error> message_code_from_json(const Json& message, std::string_view key, wire::Dialect set) {
  const bool jss = set == wire::Dialect::jss;
  const std::string field(key);
  if (const auto it = message.find(field); it != message.end()) {
    if (it->is_number_unsigned() && it->get<std::uint64_t>() <= 0xFFFF) return static_cast<std::uint16_t>(it->get<std::uint64_t>());
    if (it->is_string()) {
      const std::string text = it->get<std::string>();
      unsigned value = 0;
      int consumed = 0;
      if (std::sscanf(text.c_str(), "%x%n", &value, &consumed) == 1 && consumed == static_cast<int>(text.size()) &&
          value <= 0xFFFF)
        return static_cast<std::uint16_t>(value);
    }
    return unexpected(json_error(field, std::string("expected ") + (jss ? "a message ID" : "a command code") +
                                            " such as \"0x4402\""));
  }
  if (const auto it = message.find("name"); it != message.end() && it->is_string()) {
    if (const auto* info = find_message(set, it->get<std::string>())) return info->code;
    return unexpected(
        json_error("name", std::string("no ") + (jss ? "JSS " : "") + "message named '" + it->get<std::string>() + "'"));
  }
  return unexpected(json_error(field, "'" + field + "' or 'name' is required"));
}

std::string code_text(std::uint16_t code) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", code);
  return text;
}
}  // namespace detail

std::span<const MessageInfo> catalogue(wire::Dialect dialect) {
  static const std::vector<MessageInfo> ra = ra_set();
  static const std::vector<MessageInfo> jss = sorted_by_code(detail::jss_set());
  return message_set_of(dialect) == wire::Dialect::jss ? std::span<const MessageInfo>(jss)
                                                       : std::span<const MessageInfo>(ra);
}

const MessageInfo* find_message(wire::Dialect dialect, std::uint16_t code) {
  const auto all = catalogue(dialect);
  const auto it = std::lower_bound(all.begin(), all.end(), code, [](const auto& m, auto c) { return m.code < c; });
  return it != all.end() && it->code == code ? &*it : nullptr;
}

const MessageInfo* find_message(wire::Dialect dialect, std::string_view name) {
  for (const auto& m : catalogue(dialect))
    if (m.name == name || m.type_name == name) return &m;
  return nullptr;
}

MessageClass message_class_of(wire::Dialect set, std::uint16_t code) {
  switch (code >> 12) {
    case 0x0: return MessageClass::command;
    case 0x2: return MessageClass::query;
    case 0x4: return MessageClass::inform;
    default: break;
  }
  if (message_set_of(set) == wire::Dialect::jss) return MessageClass::command;
  switch (code >> 12) {
    case 0x6: return MessageClass::event_setup;
    case 0x8: return MessageClass::event_notification;
    case 0xD: return MessageClass::node_management;
    default: return MessageClass::experimental;
  }
}

std::string_view to_string(MessageClass message_class) {
  switch (message_class) {
    case MessageClass::command: return "command";
    case MessageClass::query: return "query";
    case MessageClass::inform: return "inform";
    case MessageClass::event_setup: return "event setup";
    case MessageClass::event_notification: return "event notification";
    case MessageClass::node_management: return "node management";
    case MessageClass::experimental: return "experimental";
  }
  return "command";
}

std::string_view message_subgroup(std::uint16_t code) {
  const unsigned low = code & 0x0FFF;
  if (low < 0x200) return "core";
  if (low < 0x400) return "communications";
  if (low < 0x600) return "platform";
  if (low < 0x800) return "manipulator";
  if (low < 0xA00) return "environment sensor";
  if (low < 0xC00) return "discovery";
  return "other";
}

nlohmann::ordered_json header_to_json(const Header& h) {
  return nlohmann::ordered_json{{"priority", h.priority},
                        {"ack_nak", kAckNakNames[static_cast<unsigned>(h.ack_nak) & 3]},
                        {"service_connection", h.service_connection},
                        {"experimental", h.experimental},
                        {"version", h.version},
                        {"destination", h.destination.to_string()},
                        {"source", h.source.to_string()},
                        {"data_size", h.data_size},
                        {"data_flag", data_flag_name(h.data_flag)},
                        {"sequence", h.sequence}};
}

Expected<nlohmann::ordered_json, Error> message_to_json(std::span<const std::uint8_t> bytes, wire::Dialect dialect) {
  auto packet = decode_packet(bytes);
  if (!packet) return unexpected(packet.error());
  const Header& h = packet->header;
  const MessageInfo* info = find_message(wire::Dialect::ra, h.command_code);
  if (!info)
    return unexpected(Error{ErrorCode::unknown_message, 2, "command_code", code_text(h.command_code)});
  if (h.data_flag != DataFlag::single)
    return unexpected(Error{ErrorCode::bad_data_flag, 13, "data_flag",
                            "one packet of a large data set: reassemble before decoding"});
  auto fields = info->body_to_json(packet->payload, dialect);
  if (!fields) return unexpected(fields.error());
  return nlohmann::ordered_json{
      {"code", code_text(h.command_code)}, {"name", info->name}, {"header", header_to_json(h)}, {"fields", *fields}};
}

Expected<Bytes, Error> message_from_json(const nlohmann::ordered_json& message, wire::Dialect dialect) {
  if (!message.is_object()) return unexpected(json_error({}, "expected a JSON object"));
  for (const auto& [key, value] : message.items())
    if (key != "code" && key != "name" && key != "header" && key != "fields")
      return unexpected(json_error({}, "unknown key '" + key + "'"));
  auto code = detail::message_code_from_json(message, "code", wire::Dialect::ra);
  if (!code) return unexpected(code.error());
  const MessageInfo* info = find_message(wire::Dialect::ra, *code);
  if (!info) return unexpected(Error{ErrorCode::unknown_message, 0, "code", code_text(*code)});
  auto header = header_from_json(message.value("header", nlohmann::ordered_json()));
  if (!header) return unexpected(header.error());
  auto payload = info->body_from_json(message.value("fields", nlohmann::ordered_json::object()), dialect);
  if (!payload) return unexpected(payload.error());
  if (payload->size() > kMaxPayloadSize)
    return unexpected(Error{ErrorCode::payload_too_large, 0, {}, std::to_string(payload->size()) + " bytes, at most 4080 in one packet"});
  header->command_code = *code;
  header->data_size = static_cast<std::uint16_t>(payload->size());
  auto head = encode_header(*header);
  if (!head) return unexpected(head.error());
  Bytes out(head->begin(), head->end());
  out.insert(out.end(), payload->begin(), payload->end());
  return out;
}

std::string messages_markdown() {
  std::string out = R"(# Supported messages

Generated from the message descriptions by `jausctl msg doc`; a test fails when
this file and the descriptions disagree. Regenerate with
`jausctl msg doc > docs/messages.md`.

## Conventions

- Every message is a 16-byte header (see `core/include/jaus/core/header.hpp`)
  and the payload listed here, fields in wire order, little-endian.
- Values are in engineering units, named in the key: `_deg` degrees, `_rad`
  radians, `_m` metres, `_mps` m/s, `_rps` rad/s, `_rps2` rad/s^2, `_hz`
  hertz, `_percent`, `_c` degrees Celsius, `_nm` newton metres, `_s` seconds.
  Keys without a unit are integers, bit fields or text.
- `scaled [lower, upper]` fields use the RA scaled-integer rule; values are
  clamped to the limits on encode and round-trip within one step.
- Optional fields carry their presence-vector bit. The presence vector of a
  message whose layout it governs is derived from the fields present; a
  received vector with bits the message does not define is rejected
  (`reserved_presence_bits`), since the layout after it cannot be known. A
  query's `presence_vector` is a request mask: bits beyond the report's are
  ignored (docs/wire-format.md, "Presence vectors").
- `enum: 0 initialize, 1 ready, ...` fields appear in JSON by name
  (`"primary_status": "ready"`) and are read back by name or number; a value
  without a name (reserved, vendor, a gear within a range) stays a number.
  `bits: bit 0 stop, ...` fields appear as an object of their named bits
  (`{"stop": true}`; a wider part is a number or its value's name) plus
  `"other_bits"` when bits no name covers are set, and are read back from such
  an object (absent bits are 0) or a plain number. On the wire both are the
  plain integer.
- Counts (`u8 count`) are derived from the array length on encode and checked
  against the bytes left on decode; "0 is reserved" counts are rejected.
- Decoding consumes every byte: trailing bytes are an error.

## Dialects and settled ambiguities

- `ra` (default) is Part 3 as written and what the node sends. `openjaus`
  reads and writes what the common open RA 3.3 implementation does: manipulator
  signed values as unsigned with bias = lower limit, 2^32 - 2 steps for 32-bit
  unsigned ranges, `(int)(x + 0.5)` rounding, date stamps with a 7-bit
  calendar year and a 0-based month, and the extra u16 `object_id` at the end
  of Report Relative Object Position. In that dialect our encoder reproduces
  its vectors byte for byte (`tests/core/vectors_test.cpp`).
- Query Local Path Segment (0x2410): Part 3's table puts the presence vector
  first, the reverse of its global twin 0x240F; the RA 3.3 peers send the
  number first for both, and so do we.
- Report Global Pose / Local Pose / Velocity State: the mapping table names a
  field 11 for bit 9 that the field table does not have; bit 9 is reserved.
- Joint values whose limits depend on the joint type (positions, velocities,
  accelerations, force/torques) are carried with the revolute limits, in the
  revolute unit. For a prismatic joint the same integer means
  value x (prismatic range / revolute range): positions x 10/(8 pi) m,
  velocities x 5/(10 pi) m/s, accelerations x 20/(10 pi) m/s^2, forces x 0.5 N.
- Report Manipulator Specifications: thousandths of a radian or millimetres
  are both read x 0.001, so values are in rad or m by joint type; the last
  joint comes first, as Part 3 orders it.
- Report Image carries opaque bytes (Part 3 defines no fields).
- Cancel Event: presence bit 0 is the message code and bit 1 the event ID, as
  the RA 3.3 peers send them.
- Create/Update Event: optional fields follow the RA 3.3 peers' presence bits
  (0 boundary, 1 limit field, 2-4 lower/upper/state limits, 5 minimum rate,
  6 requested rate, 7 query message); an event limit is a type byte then a
  value of that type (`bits` holds its little-endian bytes).

## Messages

| code | name | subgroup | class | payload |
|---|---|---|---|---|
)";
  for (const auto& m : catalogue(wire::Dialect::ra)) {
    out += "| " + code_text(m.code) + " | " + std::string(m.name) + " | " + std::string(message_subgroup(m.code)) +
           " | " + std::string(to_string(m.message_class)) + " | " + m.fields_doc() + " |\n";
  }
  return out;
}

}  // namespace jaus::msg
