#include "jaus/ocu/message_json.hpp"

#include "jaus/base/hex.hpp"
#include "jaus/messages/catalogue.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

namespace {

using jaus::unexpected;

auto invalid(std::string why) { return unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, std::move(why))); }

constexpr std::uint16_t kQueryClass = 0x2000;
constexpr std::uint16_t kReportClass = 0x4000;
constexpr std::uint16_t kClassMask = 0xF000;
// Queries have a handful of fields; the loop that fills them ends well before.
constexpr int kMaxQueryFields = 16;

bool is_query(std::uint16_t code) { return (code & kClassMask) == kQueryClass; }

// The catalogue says "'key' is missing" for a required field left out.
std::optional<std::string> missing_field(const jaus::Error& error) {
  const std::string suffix = "' is missing";
  const std::string& d = error.detail;
  if (error.code != jaus::ErrorCode::json || d.size() <= suffix.size() + 1 || d.front() != '\'' ||
      d.compare(d.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  return d.substr(1, d.size() - suffix.size() - 1);
}

std::string message_label(std::uint16_t code) {
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, code);
  return info ? std::string(info->name) + " (" + code_text(code) + ")" : code_text(code);
}

}  // namespace

std::string describe_error(const jaus::Error& error) {
  if (error.code == jaus::ErrorCode::json) {
    std::string out = "bad JSON";
    if (!error.field.empty()) out += " in '" + std::string(error.field) + "'";
    if (!error.detail.empty()) out += ": " + error.detail;
    return out;
  }
  return error.message();
}

std::optional<std::uint16_t> report_code_for(std::uint16_t query_code) {
  if (!is_query(query_code)) return std::nullopt;
  const auto report = static_cast<std::uint16_t>(query_code + (kReportClass - kQueryClass));
  if (!jaus::msg::find_message(jaus::wire::Dialect::ra, report)) return std::nullopt;
  return report;
}

jaus::Expected<PreparedMessage> prepare_query(std::uint16_t code, std::optional<std::uint32_t> presence_vector,
                                      const Json& fields) {
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, code);
  if (!info) return invalid("unknown message code " + code_text(code));
  if (!is_query(code))
    return invalid(message_label(code) + " is not a query (queries are 0x2nnn; `jausctl send` sends any message)");
  if (!fields.is_object()) return invalid("--fields must be a JSON object");
  Json given = fields;
  if (presence_vector) {
    if (given.contains("presence_vector"))
      return invalid("the presence vector is given twice (--pv and --fields)");
    given["presence_vector"] = *presence_vector;
  }
  Json filled = given;
  for (int attempt = 0; attempt < kMaxQueryFields; ++attempt) {
    auto payload = info->body_from_json(filled, jaus::wire::Dialect::ra);
    if (payload) {
      PreparedMessage out;
      out.header.command_code = code;
      out.payload = std::move(*payload);
      return out;
    }
    if (const auto key = missing_field(payload.error())) {
      filled[*key] = 0;  // what an OCU asks by default: the first camera, waypoint 0, ...
      continue;
    }
    if (presence_vector && payload.error().detail == "unknown field 'presence_vector'")
      return invalid(message_label(code) + " has no presence vector (--pv)");
    return invalid(message_label(code) + ": " + describe_error(payload.error()));
  }
  return invalid(message_label(code) + ": cannot fill its fields");
}

jaus::Expected<PreparedMessage> prepare_message(const Json& message, jaus::wire::Dialect dialect) {
  auto bytes = jaus::msg::message_from_json(message, dialect);
  if (!bytes) return invalid(describe_error(bytes.error()));
  auto packet = jaus::decode_packet(*bytes);
  if (!packet) return invalid(describe_error(packet.error()));
  PreparedMessage out;
  out.header = packet->header;
  out.header.data_flag = jaus::DataFlag::single;  // the node splits large payloads itself
  out.payload.assign(packet->payload.begin(), packet->payload.end());
  return out;
}

jaus::Expected<Json> message_json(const Received& message, jaus::wire::Dialect dialect) {
  const jaus::Header& h = message.header;
  Json out;
  out["code"] = code_text(h.command_code);
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, h.command_code);
  if (!info) {
    out["name"] = nullptr;
    out["header"] = jaus::msg::header_to_json(h);
    out["payload"] = jaus::to_hex(message.payload);
    return out;
  }
  out["name"] = info->name;
  out["header"] = jaus::msg::header_to_json(h);
  auto fields = info->body_to_json(message.payload, dialect);
  if (!fields)
    return unexpected(jaus::make_error(jaus::ErrorCode::malformed, message_label(h.command_code) + " from " +
                                                                h.source.to_string() + " does not decode: " +
                                                                fields.error().message()));
  out["fields"] = std::move(*fields);
  return out;
}

std::string json_line(const Json& json) {
  return json.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace jaus::ocu
