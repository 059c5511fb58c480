// The command-line values of --dialect jss (JSS IDs, JSS messages by ID or
// name) and `jausctl msg decode | encode | list --dialect jss`, on the JSS
// catalogue. No I/O but the output of the msg commands.
#include <charconv>
#include <cstdio>
#include <optional>
#include <random>

#include "jaus/base/hex.hpp"
#include "jaus/ocu/names.hpp"
#include "jss_commands.hpp"

namespace jausctl::ocu {

namespace {

bool parse_hex_u16(std::string_view text, std::uint16_t& out) {
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) text.remove_prefix(2);
  if (text.empty() || text.size() > 4) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out, 16);
  return ec == std::errc{} && end == text.data() + text.size();
}

// Each run its own JSS ID unless --as says otherwise (as the RA commands:
// a control or emergency hold left by one run is not the next run's).
std::string fresh_jss_id() {
  std::random_device entropy;
  std::uniform_int_distribution<int> node(1, 254);
  return std::to_string(kDefaultJssOcuId.subsystem) + "." + std::to_string(node(entropy)) + "." +
         std::to_string(kDefaultJssOcuId.component);
}

// The top-level field a JSON decode missed: the codec says "'presence_vector' is missing".
std::optional<std::string> missing_field(const jaus::Error& e) {
  static constexpr std::string_view kMissing = "' is missing";
  const std::string& d = e.detail;
  if (e.code != jaus::ErrorCode::json || d.size() <= kMissing.size() + 1 || d.front() != '\'' ||
      d.compare(d.size() - kMissing.size(), kMissing.size(), kMissing) != 0)
    return std::nullopt;
  std::string name = d.substr(1, d.size() - kMissing.size() - 1);
  if (name.find_first_of("'.[ ") != std::string::npos) return std::nullopt;
  return name;
}

std::string one_line(const Json& json) { return json.dump(-1, ' ', false, Json::error_handler_t::replace); }

}  // namespace

Parsed<jaus::jss::JssId> parse_jss_id(std::string_view text, bool allow_broadcast) {
  const auto id = jaus::jss::JssId::parse(text);
  if (!id) return invalid("bad JSS ID '" + std::string(text) + "': expected S.N.C (subsystem.node.component)");
  if (id->subsystem == 0 || id->node == 0 || id->component == 0)
    return invalid("bad JSS ID '" + std::string(text) + "': 0 is not a valid ID at any level");
  if (id->is_broadcast() && !allow_broadcast)
    return invalid("bad JSS ID '" + std::string(text) + "': a broadcast ID (65535, 255) is not allowed here");
  return *id;
}

Parsed<const jaus::msg::MessageInfo*> parse_jss_message(std::string_view text) {
  std::uint16_t id = 0;
  if (parse_hex_u16(text, id)) {
    if (const auto* info = jaus::msg::find_message(jaus::wire::Dialect::jss, id)) return info;
    return invalid("unknown JSS message ID " + code_text(id) + " (jausctl msg list --dialect jss shows every ID)");
  }
  if (const auto* info = jaus::msg::find_message(jaus::wire::Dialect::jss, text)) return info;
  return invalid("unknown JSS message '" + std::string(text) +
                 "': expected an ID such as 0x2404 or a name such as \"Query Velocity State\"");
}

Parsed<JssCommon> parse_jss_common(const JssCommonText& text) {
  JssCommon out;
  auto peers = parse_peers(text.to, text.multicast);
  if (!peers) return jaus::unexpected(peers.error());
  out.session.to = std::move(peers->to);
  out.session.multicast = peers->multicast;
  auto bind = parse_endpoint_text(text.bind, 0, true);
  if (!bind) return invalid("--bind: " + bind.error().message());
  out.session.bind = *bind;
  auto self = parse_jss_id(text.as.empty() ? fresh_jss_id() : text.as, false);
  if (!self) return invalid("--as: " + self.error().message());
  out.session.self = *self;
  auto timeout = parse_seconds(text.timeout);
  if (!timeout) return invalid("--timeout: " + timeout.error().message());
  out.timeout = *timeout;
  return out;
}

Parsed<JssPreparedQuery> prepare_jss_query(const jaus::msg::MessageInfo& query, const Json& fields) {
  if (query.message_class != jaus::msg::MessageClass::query)
    return invalid(std::string(query.name) + " (" + code_text(query.code) + ") is not a query");
  const std::uint16_t report_id = static_cast<std::uint16_t>(query.code + 0x2000);  // Query X -> Report X
  if (!jaus::msg::find_message(jaus::wire::Dialect::jss, report_id))
    return invalid("no report is known for " + std::string(query.name));
  if (!fields.is_object()) return invalid("--fields must be a JSON object");
  Json message{{"id", code_text(query.code)}, {"fields", fields}};
  // Fields not given are 0 (as for RA queries): each one the codec misses is added, once.
  for (std::size_t added = 0;; ++added) {
    auto contents = jaus::jss::contents_from_json(message);
    if (contents) return JssPreparedQuery{std::move(*contents), report_id};
    const jaus::Error& e = contents.error();
    const auto field = missing_field(e);
    if (!field || message["fields"].contains(*field) || added >= 16)
      return invalid(std::string(query.name) + ": " + describe_error(e));
    message["fields"][*field] = 0;
  }
}

Parsed<std::vector<std::uint8_t>> prepare_jss_message(const Json& message) {
  if (!message.is_object()) return invalid("the message must be a JSON object such as {\"name\":\"Resume\"}");
  Json m = message;
  if (!m.contains("fields")) m["fields"] = Json::object();
  auto contents = jaus::jss::contents_from_json(m);
  if (!contents) return invalid(describe_error(contents.error()));
  return std::move(*contents);
}

int jss_msg_decode(const std::string& hex, CommandIo io) {
  const auto bytes = jaus::parse_hex(hex);
  if (!bytes) {
    io.err << "jausctl msg decode: bad hex: " << bytes.error().message() << "\n";
    return kExitBadInput;
  }
  // A datagram starts with the AS5669A version byte; anything else is contents (message ID + body).
  auto json = !bytes->empty() && (*bytes)[0] == jaus::jss::kAs5669aVersion ? jaus::jss::datagram_to_json(*bytes)
                                                                           : jaus::jss::contents_to_json(*bytes);
  if (!json) {
    io.err << "jausctl msg decode: " << json.error().message() << "\n";
    return kExitBadInput;
  }
  io.out << one_line(*json) << "\n";
  return kExitOk;
}

int jss_msg_encode(const std::string& json_text, CommandIo io) {
  const auto json = Json::parse(json_text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) {
    io.err << "jausctl msg encode: stdin is not a JSON object\n";
    return kExitBadInput;
  }
  // With a header: one datagram; else the contents alone.
  auto bytes = json.contains("header") ? jaus::jss::datagram_from_json(json) : jaus::jss::contents_from_json(json);
  if (!bytes) {
    io.err << "jausctl msg encode: " << bytes.error().message() << "\n";
    return kExitBadInput;
  }
  io.out << jaus::to_hex(*bytes) << "\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
