#include "jaus/jss/catalogue.hpp"

#include <algorithm>
#include <cstdio>
#include <type_traits>

#include "../catalogue_entries.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/jss/contents.hpp"
#include "message_notes.hpp"

namespace jaus::msg::detail {

std::vector<MessageInfo> jss_set() {
  std::vector<MessageInfo> all = jss_core_entries();
  for (auto& m : jss_mobility_entries()) all.push_back(m);
  for (auto& m : all) {
    for (const auto& note : jss::detail::kMessageNotes) {
      if (note.id != m.code) continue;
      m.service_uri = note.service_uri;
      m.summary = note.summary;
    }
  }
  return all;
}

}  // namespace jaus::msg::detail

namespace jaus::jss {

namespace {

using Json = nlohmann::ordered_json;
using msg::MessageInfo;
constexpr auto kJss = wire::Dialect::jss;

std::string id_text(std::uint16_t id) { return msg::detail::code_text(id); }

Unexpected<Error> json_error(std::string_view field, std::string detail) {
  return unexpected(Error{ErrorCode::json, 0, std::string(field), std::move(detail)});
}

constexpr std::string_view kPriorityNames[] = {"low", "normal", "high", "safety_critical"};
constexpr std::string_view kBroadcastNames[] = {"none", "local", "global"};
constexpr std::string_view kAckNakNames[] = {"none", "ack_requested", "nak", "ack"};
constexpr std::string_view kDataFlagNames[] = {"single", "first", "middle", "last"};

// A name of `names` or its index.
bool named_from_json(const Json& j, std::span<const std::string_view> names, unsigned& out) {
  for (unsigned i = 0; i < names.size(); ++i)
    if ((j.is_string() && j.get<std::string>() == names[i]) || (j.is_number_unsigned() && j.get<std::uint64_t>() == i)) {
      out = i;
      return true;
    }
  return false;
}

}  // namespace

std::string_view service_name(std::string_view service_uri) {
  const auto colon = service_uri.rfind(':');
  return colon == std::string_view::npos ? service_uri : service_uri.substr(colon + 1);
}

Expected<Json> contents_to_json(std::span<const std::uint8_t> contents) {
  if (contents.size() < kMessageIdSize)
    return unexpected(Error{ErrorCode::truncated, 0, "message_id",
                            "needs 2 bytes, " + std::to_string(contents.size()) + " left"});
  const std::uint16_t id = message_id_of(contents);
  const MessageInfo* info = msg::find_message(kJss, id);
  if (info == nullptr) return unexpected(Error{ErrorCode::unknown_message, 0, "message_id", id_text(id)});
  auto fields = info->body_to_json(contents.subspan(kMessageIdSize), kJss);
  if (!fields) return unexpected(fields.error());
  return Json{{"id", id_text(id)}, {"name", info->name}, {"fields", std::move(*fields)}};
}

Expected<Bytes> contents_from_json(const Json& message) {
  if (!message.is_object()) return json_error({}, "expected a JSON object");
  for (const auto& [key, value] : message.items())
    if (key != "id" && key != "name" && key != "fields") return json_error({}, "unknown key '" + key + "'");
  auto id = msg::detail::message_code_from_json(message, "id", kJss);
  if (!id) return unexpected(id.error());
  const MessageInfo* info = msg::find_message(kJss, *id);
  if (info == nullptr) return unexpected(Error{ErrorCode::unknown_message, 0, "id", id_text(*id)});
  auto body = info->body_from_json(message.value("fields", Json::object()), kJss);
  if (!body) return unexpected(body.error());
  Bytes out{static_cast<std::uint8_t>(*id & 0xFF), static_cast<std::uint8_t>(*id >> 8)};
  out.insert(out.end(), body->begin(), body->end());
  return out;
}

Json header_to_json(const JudpHeader& h) {
  return Json{{"message_type", h.message_type},
              {"priority", kPriorityNames[static_cast<unsigned>(h.priority) & 3]},
              {"broadcast", static_cast<unsigned>(h.broadcast) < 3 ? Json(kBroadcastNames[static_cast<unsigned>(h.broadcast)])
                                                                   : Json(static_cast<unsigned>(h.broadcast))},
              {"ack_nak", kAckNakNames[static_cast<unsigned>(h.ack_nak) & 3]},
              {"data_flag", kDataFlagNames[static_cast<unsigned>(h.data_flag) & 3]},
              {"destination", h.destination.to_string()},
              {"source", h.source.to_string()},
              {"sequence", h.sequence}};
}

Expected<JudpHeader> header_from_json(const Json& j) {
  JudpHeader h;
  if (j.is_null()) return h;
  if (!j.is_object()) return json_error("header", "expected an object");
  for (const auto& [key, value] : j.items()) {
    bool ok = true;
    unsigned index = 0;
    if (key == "priority") {
      ok = named_from_json(value, kPriorityNames, index);
      h.priority = static_cast<JudpPriority>(index);
    } else if (key == "broadcast") {
      ok = named_from_json(value, kBroadcastNames, index);
      h.broadcast = static_cast<JudpBroadcast>(index);
    } else if (key == "ack_nak") {
      ok = named_from_json(value, kAckNakNames, index);
      h.ack_nak = static_cast<JudpAckNak>(index);
    } else if (key == "data_flag") {
      ok = named_from_json(value, kDataFlagNames, index);
      h.data_flag = static_cast<JudpDataFlag>(index);
    } else if (key == "destination" || key == "source") {
      const auto id = value.is_string() ? JssId::parse(value.get<std::string>()) : std::nullopt;
      ok = id.has_value();
      if (ok) (key == "destination" ? h.destination : h.source) = *id;
    } else if (key == "sequence") {
      ok = value.is_number_unsigned() && value.get<std::uint64_t>() <= 0xFFFF;
      if (ok) h.sequence = static_cast<std::uint16_t>(value.get<std::uint64_t>());
    } else if (key == "message_type") {
      ok = value.is_number_unsigned() && value.get<std::uint64_t>() == 0;
    } else {
      return json_error("header", "unknown key '" + key + "'");
    }
    if (!ok) return json_error("header", "bad value for '" + key + "'");
  }
  return h;
}

Expected<Json> datagram_to_json(std::span<const std::uint8_t> datagram) {
  auto packets = decode_judp_datagram(datagram);
  if (!packets) return unexpected(packets.error());
  Json out{{"packets", Json::array()}};
  for (const auto& packet : *packets) {
    Json entry{{"header", header_to_json(packet.header)}};
    const bool whole = packet.header.data_flag == JudpDataFlag::single && !packet.contents.empty();
    if (whole) {
      auto message = contents_to_json(packet.contents);
      if (!message) {
        Error e = message.error();
        e.offset += static_cast<std::size_t>(packet.contents.data() - datagram.data());
        return unexpected(std::move(e));
      }
      entry["message"] = std::move(*message);
    } else {
      entry["contents"] = to_hex(packet.contents);
    }
    out["packets"].push_back(std::move(entry));
  }
  return out;
}

Expected<Bytes> datagram_from_json(const Json& packet) {
  if (!packet.is_object()) return json_error({}, "expected {\"header\": {...}, \"message\": {...}}");
  for (const auto& [key, value] : packet.items())
    if (key != "header" && key != "message" && key != "contents") return json_error({}, "unknown key '" + key + "'");
  auto header = header_from_json(packet.value("header", Json()));
  if (!header) return unexpected(header.error());
  Bytes contents;
  if (const auto it = packet.find("message"); it != packet.end()) {
    auto encoded = contents_from_json(*it);
    if (!encoded) return unexpected(encoded.error());
    contents = std::move(*encoded);
  } else if (const auto hex = packet.find("contents"); hex != packet.end()) {
    auto bytes = hex->is_string() ? parse_hex(hex->get<std::string>())
                                  : Expected<Bytes>(unexpected(make_error(ErrorCode::json, "expected hex")));
    if (!bytes) return json_error("contents", bytes.error().detail);
    contents = std::move(*bytes);
  }
  Bytes out(1 + kMinDataSize + contents.size());
  auto size = encode_judp_datagram(*header, contents, out);
  if (!size) return unexpected(size.error());
  out.resize(*size);
  return out;
}

// ---- embedded messages (codec::Embedded) ------------------------------------

namespace codec {

template <class J>
J embedded_message_to_json(std::span<const std::uint8_t> contents) {
  static_assert(std::is_same_v<J, Json>, "the catalogue speaks nlohmann::ordered_json");
  // Shown by fields only when they give back the same bytes (element data of
  // a user-defined format may look like a message and not be one).
  if (auto message = contents_to_json(contents); message) {
    if (auto again = contents_from_json(*message); again && std::ranges::equal(*again, contents)) return *message;
  }
  Json out = Json::object();
  if (contents.size() >= kMessageIdSize) out["id"] = id_text(message_id_of(contents));
  out["hex"] = to_hex(contents);
  return out;
}

template <class J>
Expected<void> embedded_message_from_json(const J& j, std::vector<std::uint8_t>& contents) {
  static_assert(std::is_same_v<J, Json>, "the catalogue speaks nlohmann::ordered_json");
  const Json* hex = j.is_string() ? &j : nullptr;
  if (j.is_object()) {
    if (const auto it = j.find("hex"); it != j.end()) hex = &*it;
  }
  if (hex != nullptr) {
    if (!hex->is_string()) return wire::detail::json_error("'hex': expected a hex string");
    auto bytes = parse_hex(hex->get<std::string>());
    if (!bytes) return wire::detail::json_error(bytes.error().detail);
    contents = std::move(*bytes);
    return {};
  }
  if (!j.is_object()) return wire::detail::json_error("expected {\"name\" or \"id\", \"fields\"} or {\"hex\": ...}");
  auto encoded = contents_from_json(j);
  if (!encoded) return wire::detail::json_error((encoded.error().field.empty() ? "" : encoded.error().field + ": ") +
                                                encoded.error().detail);
  contents = std::move(*encoded);
  return {};
}

template Json embedded_message_to_json<Json>(std::span<const std::uint8_t>);
template Expected<void> embedded_message_from_json<Json>(const Json&, std::vector<std::uint8_t>&);

}  // namespace codec

// ---- docs/jss-messages.md ----------------------------------------------------

std::string messages_markdown() {
  std::string out = R"(# Supported JSS messages

Generated from the JSS message descriptions (`core/include/jaus/jss/messages/`,
and the RA bodies JSS shares, read in the JSS dialect: docs/jss.md, "Scaled
values") by `jausctl msg doc --dialect jss` (or `jss_messages_doc`, built with
the tests); a test fails when this file and the descriptions disagree. Regenerate
with `jausctl msg doc --dialect jss > docs/jss-messages.md`.
The face that speaks them is described in docs/jss.md.

## Conventions

- SAE JAUS (JSS): AS5710 core services v1.1, AS6009 mobility services v1.0,
  carried by AS5669A ("JUDP", version byte 0x02) on UDP port 3794.
- The contents of a transport message are the u16 message ID, then the body
  listed here, fields in wire order; every multi-byte field is little-endian.
- Values are in engineering units, named in the key (`_m`, `_rad`, `_mps`,
  `_rps`, `_hz`, `_percent`, `_s`, `_min`); keys without a unit are integers,
  enumerations, IDs or text.
- `scaled [lower, upper]` fields are JSS scaled integers, all unsigned:
  step (upper - lower) / (2^n - 1), bias lower, rounded on encode and clamped
  to the limits; they round-trip within one step. Peers built with the JAUS
  Tool Set truncate instead of rounding; their values decode within one step.
- Optional fields carry their presence-vector bit; the presence vector is
  derived from the fields present, and a received one with bits the message
  does not define is rejected (`reserved_presence_bits`). A query's
  `presence_vector` is a request mask.
- `u8 length + text` is a JSIDL variable-length string; `text, 80 bytes` is
  NUL padded on send and read up to the first NUL.
- An embedded JSS message (Create Event's query, Event's report, a list
  element's data) is preceded by its byte count, which includes its own
  2-byte ID. In JSON it is `{"id", "name", "fields"}`, or `{"id", "hex"}`
  when the bytes are not a message we know.
- Decoding consumes every byte: trailing bytes are an error.

## Messages

| ID | name | service | class | body |
|---|---|---|---|---|
)";
  for (const auto& m : msg::catalogue(kJss)) {
    out += "| " + id_text(m.code) + " | " + std::string(m.name) + " | " + std::string(service_name(m.service_uri)) +
           " | " + std::string(to_string(m.message_class)) + " | " + m.fields_doc() + " |\n";
  }
  out += "\n## What each message does\n\n| ID | name | summary |\n|---|---|---|\n";
  for (const auto& m : msg::catalogue(kJss))
    out += "| " + id_text(m.code) + " | " + std::string(m.name) + " | " + std::string(m.summary) + " |\n";
  return out;
}

}  // namespace jaus::jss
