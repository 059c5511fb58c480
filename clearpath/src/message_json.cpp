#include "jaus/clearpath/message_json.hpp"

#include <charconv>
#include <cstdio>

#include "detail/json_visitors.hpp"

namespace jaus::clearpath {
namespace {

std::string hex16(std::uint16_t v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", v);
  return buf;
}

Unexpected<Error> json_error(std::string field, std::string detail) {
  return unexpected(Error{ErrorCode::json, 0, std::move(field), std::move(detail)});
}

// An unsigned header number that must fit in T: JSON integer or "0x.." string.
template <class T>
Expected<T> header_number(const nlohmann::json& json, const char* key, T fallback) {
  const auto it = json.find(key);
  if (it == json.end()) return fallback;
  std::uint64_t v = 0;
  if (it->is_number_unsigned()) {
    v = it->get<std::uint64_t>();
  } else if (it->is_string()) {
    const auto s = it->get<std::string>();
    const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
    const char* first = s.data() + (hex ? 2 : 0);
    const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v, hex ? 16 : 10);
    if (ec != std::errc{} || end != s.data() + s.size()) return json_error(key, "not a number: " + s);
  } else {
    return json_error(key, "expected a non-negative integer or a \"0x..\" string");
  }
  if (!std::in_range<T>(v)) return json_error(key, "too large");
  return static_cast<T>(v);
}

}  // namespace

nlohmann::json fields_to_json(const AnyMessage& message) {
  nlohmann::json out;
  detail::JsonWriter writer(out);
  visit([&](const auto& m) { std::remove_cvref_t<decltype(m)>::describe(m, writer); }, message);
  return out;
}

nlohmann::json to_json(const Envelope& envelope) {
  nlohmann::json j;
  const std::uint16_t type = envelope.header.type;
  j["type"] = hex16(type);
  j["name"] = std::string(name_of(envelope.message));
  if (envelope.message.holds<Ack>()) {
    j["kind"] = "ack";
    const auto target = find_message(type);
    j["acknowledges"] = target ? std::string(target->name) : hex16(type);
    j["result_text"] = describe_ack_result(envelope.message.get<Ack>().result);
  } else {
    j["kind"] = std::string(to_string(kind_of(type)));
  }
  j["timestamp"] = envelope.header.timestamp;
  j["flags"] = envelope.header.flags;
  j["version"] = envelope.header.version;
  j["fields"] = fields_to_json(envelope.message);
  return j;
}

Expected<AnyMessage> message_from_json(const AnyMessage& prototype, const nlohmann::json& fields) {
  if (!fields.is_object()) return json_error("fields", "expected an object");
  AnyMessage message = prototype;
  detail::FieldPath path;
  detail::JsonReader reader(fields, path);
  visit([&](auto& m) { std::remove_cvref_t<decltype(m)>::describe(m, reader); }, message);
  if (reader.error) return unexpected(*reader.error);
  return message;
}

Expected<Envelope> envelope_from_json(const nlohmann::json& json) {
  if (!json.is_object()) return json_error("", "expected a JSON object");
  Envelope envelope{{}, Ack{}};
  auto type = header_number<std::uint16_t>(json, "type", 0);
  if (!type) return unexpected(type.error());
  const auto name_it = json.find("name");
  if (name_it != json.end() && !name_it->is_string()) return json_error("name", "expected a string");
  const std::string name = name_it != json.end() ? name_it->get<std::string>() : "";
  const bool has_type = json.contains("type");

  std::optional<AnyMessage> prototype;
  if (name == "ack") {
    if (!has_type) return json_error("type", "an ACK needs the acknowledged type");
    const auto kind = kind_of(*type);
    if (kind != MessageKind::command && kind != MessageKind::request)
      return json_error("type", "an ACK acknowledges a command or request type");
    prototype = Ack{};
  } else {
    std::optional<MessageTypeInfo> info;
    if (!name.empty()) {
      info = find_message(name);
      if (!info) return json_error("name", "unknown message name '" + name + "'");
      if (has_type && info->type != *type) return json_error("type", "does not match name '" + name + "'");
    } else if (has_type) {
      info = find_message(*type);
      if (!info) return unexpected(Error{ErrorCode::unknown_message, 0, "type", hex16(*type)});
    } else {
      return json_error("", "give \"type\" or \"name\"");
    }
    *type = info->type;
    prototype = make_message(info->type);
  }
  envelope.header.type = *type;
  auto timestamp = header_number<std::uint32_t>(json, "timestamp", 0);
  if (!timestamp) return unexpected(timestamp.error());
  auto flags = header_number<std::uint8_t>(json, "flags", 0);
  if (!flags) return unexpected(flags.error());
  auto version = header_number<std::uint8_t>(json, "version", kDefaultVersion);
  if (!version) return unexpected(version.error());
  envelope.header.timestamp = *timestamp;
  envelope.header.flags = *flags;
  envelope.header.version = *version;

  const auto fields_it = json.find("fields");
  const nlohmann::json empty = nlohmann::json::object();
  auto message = message_from_json(*prototype, fields_it != json.end() ? *fields_it : empty);
  if (!message) return unexpected(message.error());
  envelope.message = std::move(*message);
  return envelope;
}

}  // namespace jaus::clearpath
