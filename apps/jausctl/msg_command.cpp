// `jausctl msg decode HEX | encode | list | doc | wireshark`: the JAUS message
// codec on the command line. Output is JSON (decode) or hex (encode); errors
// are one line on stderr naming the offset or field, with exit code 2.
// `wireshark` writes the Lua dissector generated from the descriptions (JAUS
// and Clearpath: apps/wireshark, docs/wireshark.md). With --dialect jss,
// decode, encode, list and doc work on SAE JAUS (JSS) messages and AS5669A
// datagrams by the JSS catalogue (docs/jss-messages.md).
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/jss/catalogue.hpp"
#include "jaus/messages/catalogue.hpp"
#include "ocu/jss_commands.hpp"
#include "wireshark_plugin.hpp"

namespace jausctl {

namespace {

jaus::wire::Dialect parse_dialect(const std::string& name) {
  if (name == "jss") return jaus::wire::Dialect::jss;
  return name == "openjaus" ? jaus::wire::Dialect::openjaus : jaus::wire::Dialect::ra;
}

int decode(const std::string& hex, const std::string& dialect) {
  const auto bytes = jaus::parse_hex(hex);
  if (!bytes) {
    std::cerr << "jausctl msg decode: bad hex: " << bytes.error().message() << "\n";
    return kExitBadInput;
  }
  auto json = jaus::msg::message_to_json(*bytes, parse_dialect(dialect));
  if (!json) {
    std::cerr << "jausctl msg decode: " << json.error().message() << "\n";
    return kExitBadInput;
  }
  // Text fields are ASCII by the RA; bytes that are not valid UTF-8 print as U+FFFD.
  std::cout << json->dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  return kExitOk;
}

int encode(const std::string& dialect) {
  const std::string input{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  const auto json = nlohmann::ordered_json::parse(input, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) {
    std::cerr << "jausctl msg encode: stdin is not valid JSON\n";
    return kExitBadInput;
  }
  auto bytes = jaus::msg::message_from_json(json, parse_dialect(dialect));
  if (!bytes) {
    std::cerr << "jausctl msg encode: " << bytes.error().message() << "\n";
    return kExitBadInput;
  }
  std::cout << jaus::to_hex(*bytes) << "\n";
  return kExitOk;
}

// One line a message of the dialect's set: code, name, (subgroup or JSS service, class).
int list(jaus::wire::Dialect dialect) {
  for (const auto& m : jaus::msg::catalogue(dialect)) {
    char code[8];
    std::snprintf(code, sizeof code, "0x%04X", m.code);
    const auto group = m.set == jaus::wire::Dialect::jss ? jaus::jss::service_name(m.service_uri)
                                                          : jaus::msg::message_subgroup(m.code);
    std::cout << code << "  " << m.name << "  (" << group << ", " << jaus::msg::to_string(m.message_class) << ")\n";
  }
  return kExitOk;
}

int wireshark(const std::string& output) {
  const std::string plugin = jaus::wireshark::plugin_lua();
  if (output.empty() || output == "-") {
    std::cout << plugin;
    return kExitOk;
  }
  std::ofstream out(output, std::ios::binary);
  out << plugin;
  if (!out.flush()) {
    std::cerr << "jausctl msg wireshark: cannot write " << output << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void add_msg_commands(CLI::App& app, int& exit_code) {
  auto* msg = app.add_subcommand("msg", "JAUS message codec: decode, encode, list, doc, wireshark");
  msg->require_subcommand(1);

  auto dialect = std::make_shared<std::string>("ra");
  auto add_dialect = [dialect](CLI::App* cmd) {
    cmd->add_option("--dialect", *dialect,
                    "ra: Part 3 as written (default); openjaus: the common RA 3.3 peer's quirks; jss: SAE JAUS")
        ->check(CLI::IsMember({"ra", "openjaus", "jss"}));
  };

  auto hex = std::make_shared<std::string>();
  auto* decode_cmd = msg->add_subcommand("decode", "Decode a message (16-byte header + payload, hex) to JSON");
  decode_cmd->add_option("hex", *hex, "the message as hex")->required();
  add_dialect(decode_cmd);
  decode_cmd->callback([&exit_code, hex, dialect] {
    exit_code = *dialect == "jss" ? ocu::jss_msg_decode(*hex, {std::cout, std::cerr}) : decode(*hex, *dialect);
  });

  auto* encode_cmd = msg->add_subcommand("encode", "Encode a message from JSON on stdin (as `decode` prints it) to hex");
  add_dialect(encode_cmd);
  encode_cmd->callback([&exit_code, dialect] {
    if (*dialect != "jss") return void(exit_code = encode(*dialect));
    const std::string input{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
    exit_code = ocu::jss_msg_encode(input, {std::cout, std::cerr});
  });

  auto* doc_cmd = msg->add_subcommand(
      "doc", "Print docs/messages.md (jss: docs/jss-messages.md), generated from the descriptions");
  add_dialect(doc_cmd);
  doc_cmd->callback([&exit_code, dialect] {
    std::cout << (*dialect == "jss" ? jaus::jss::messages_markdown() : jaus::msg::messages_markdown());
    exit_code = kExitOk;
  });

  auto output = std::make_shared<std::string>();
  auto* wireshark_cmd = msg->add_subcommand(
      "wireshark", "Print the Wireshark Lua dissector for JAUS and Clearpath over UDP, from the descriptions");
  wireshark_cmd->add_option("-o,--output", *output, "write it to this file instead of stdout");
  wireshark_cmd->callback([&exit_code, output] { exit_code = wireshark(*output); });

  auto* list_cmd = msg->add_subcommand("list", "List every supported message: code, name, subgroup (jss: service), class");
  add_dialect(list_cmd);
  list_cmd->callback([&exit_code, dialect] {
    exit_code = list(parse_dialect(*dialect));
  });
}

}  // namespace jausctl
