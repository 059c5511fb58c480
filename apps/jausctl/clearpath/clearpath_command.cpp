// `jausctl clearpath decode|encode|list`: the Clearpath protocol codec on the
// command line. Output is JSON (decode) or hex (encode); bad input exits 2
// with one line on stderr.
#include <cctype>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/message_json.hpp"
#include "jaus/clearpath/messages.hpp"

namespace jausctl {
namespace {

namespace cp = jaus::clearpath;

int bad_input(const std::string& what) {
  std::cerr << "error: " << what << '\n';
  return kExitBadInput;
}

// Hex digits, optionally separated by spaces or colons, optional 0x prefix.
std::optional<std::vector<std::uint8_t>> parse_hex(std::string text) {
  if (text.size() > 1 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) text.erase(0, 2);
  std::string digits;
  for (const char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == ':') continue;
    if (!std::isxdigit(static_cast<unsigned char>(c))) return std::nullopt;
    digits += c;
  }
  if (digits.empty() || digits.size() % 2 != 0) return std::nullopt;
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i < digits.size(); i += 2)
    bytes.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
  return bytes;
}

std::string to_hex(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out;
  for (const auto b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0x0F];
  }
  return out;
}

// "auto": data types come from the platform; a command/request type is read
// as sent by the host unless only an ACK (2-byte result) explains it.
jaus::Expected<cp::Envelope> decode_with_direction(const cp::Frame& frame, const std::string& from) {
  if (from == "platform") return cp::decode(frame, cp::Direction::from_platform);
  if (from == "host") return cp::decode(frame, cp::Direction::to_platform);
  if (cp::kind_of(frame.header.type) == cp::MessageKind::data) return cp::decode(frame, cp::Direction::from_platform);
  auto as_sent = cp::decode(frame, cp::Direction::to_platform);
  if (as_sent || frame.payload.size() != 2) return as_sent;
  return cp::decode(frame, cp::Direction::from_platform);
}

int run_decode(const std::string& hex, const std::string& from) {
  const auto bytes = parse_hex(hex);
  if (!bytes) return bad_input("not a hex string (expected pairs of hex digits)");
  auto frame = cp::decode_frame(*bytes);
  if (!frame) return bad_input(frame.error().message());
  auto envelope = decode_with_direction(*frame, from);
  if (!envelope) return bad_input(envelope.error().message());
  std::cout << cp::to_json(*envelope).dump(2) << '\n';
  return kExitOk;
}

int run_encode(bool allow_out_of_range) {
  const std::string input{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  const auto json = nlohmann::json::parse(input, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) return bad_input("stdin is not valid JSON");
  auto envelope = cp::envelope_from_json(json);
  if (!envelope) return bad_input(envelope.error().message());
  if (!allow_out_of_range) {
    if (const auto range = cp::check_ranges(envelope->message); !range) return bad_input(range.error().message());
  }
  auto bytes = cp::encode(*envelope);
  if (!bytes) return bad_input(bytes.error().message());
  std::cout << to_hex(*bytes) << '\n';
  return kExitOk;
}

int run_list() {
  char type[8];
  for (const auto& info : cp::message_catalogue()) {
    std::snprintf(type, sizeof type, "0x%04X", info.type);
    std::cout << type << "  " << cp::to_string(info.kind) << "  " << info.name << '\n';
  }
  return kExitOk;
}

}  // namespace

void add_clearpath_commands(CLI::App& app, int& exit_code) {
  auto* group = app.add_subcommand("clearpath", "Clearpath protocol codec (decode, encode, list)");
  group->require_subcommand(1);

  auto* decode = group->add_subcommand("decode", "Decode one frame given in hex; prints JSON");
  auto hex = std::make_shared<std::string>();
  auto from = std::make_shared<std::string>("auto");
  decode->add_option("hex", *hex, "Frame bytes in hex (AA...)")->required();
  decode->add_option("--from", *from, "Who sent the frame: host, platform or auto (decides ACK vs request)")
      ->check(CLI::IsMember({"auto", "host", "platform"}));
  decode->callback([&exit_code, hex, from] { exit_code = run_decode(*hex, *from); });

  auto* encode = group->add_subcommand("encode", "Encode a message given as JSON on stdin; prints hex");
  auto allow = std::make_shared<bool>(false);
  encode->add_flag("--allow-out-of-range", *allow, "Encode values outside the documented ranges");
  encode->callback([&exit_code, allow] { exit_code = run_encode(*allow); });

  auto* list = group->add_subcommand("list", "List every message type of the protocol document");
  list->callback([&exit_code] { exit_code = run_list(); });
}

}  // namespace jausctl
