// A real exchange: jausctl asks a default jausd (127.0.0.60) through a
// recording relay (127.0.0.61 for jausctl, 127.0.0.63 towards the node), in
// both framings, with a service connection and a large data set (Report
// Image); the recorded datagrams become a capture, tshark dissects it with
// the generated plugin, and every message is compared with `jausctl msg
// decode` (a reassembled large data set with the catalogue's decoder, which
// jausctl uses: one packet cannot carry it).
#include <gtest/gtest.h>

#include <iostream>
#include <map>

#include "../system/default_jausd.hpp"
#include "jaus/messages/catalogue.hpp"
#include "jaus_message_check.hpp"
#include "pcap_writer.hpp"
#include "udp_relay.hpp"

namespace jaus::test {
namespace {

const UdpEndpoint kNode{{127, 0, 0, 60}, 3794};
const UdpEndpoint kRelayFront{{127, 0, 0, 61}, 3794};
const UdpEndpoint kRelayBack{{127, 0, 0, 63}, 3794};

ProgramResult jausctl(TsharkSession& session, std::vector<std::string> args, const std::string& framing = "opc") {
  args.insert(args.begin(), JAUSCTL_PATH);
  args.insert(args.end(), {"--to", "127.0.0.61:3794", "--bind", "127.0.0.62", "--framing", framing});
  return run_program(args, session.dir() / "jausctl.out", std::chrono::seconds(30));
}

std::vector<std::uint8_t> unframed(const std::vector<std::uint8_t>& datagram) {
  const std::size_t prefix = datagram.size() >= 8 && datagram[0] == 'J' ? 8 : 5;
  return {datagram.begin() + static_cast<std::ptrdiff_t>(std::min(prefix, datagram.size())), datagram.end()};
}

TEST(TsharkJausdExchange, EveryMessageShowsWhatJausctlDecodes) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("exchange");
  DefaultJausd node("wireshark-exchange", 1, "127.0.0.60");
  ASSERT_TRUE(node.started());
  UdpRelay relay(kRelayFront, kRelayBack, kNode);
  ASSERT_TRUE(relay.ok()) << "cannot bind the relay on 127.0.0.61/63:3794";

  // The node answers once it is up: ask until it does (generous deadline for a loaded machine).
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool up = false;
  while (!up && std::chrono::steady_clock::now() < until)
    up = jausctl(session, {"status", "1.1.1.1", "--timeout", "1"}).exit_code == 0;
  ASSERT_TRUE(up) << "jausd did not answer through the relay: " << node.output();

  const std::vector<std::vector<std::string>> asks = {
      {"query", "1.1.38.1", "Query Global Pose"},
      {"query", "1.1.1.1", "Query Services"},
      {"query", "1.1.1.1", "Query Configuration", "--fields", "{\"query_field\":2}"},
      {"query", "1.1.37.1", "Query Image", "--timeout", "10"},
      {"subscribe", "1.1.42.1", "Report Velocity State", "--rate", "20", "--count", "3", "--for", "20"},
  };
  for (const auto& ask : asks) {
    const auto result = jausctl(session, ask);
    EXPECT_EQ(result.exit_code, 0) << ask[2] << ": " << result.err;
  }
  const auto judp = jausctl(session, {"query", "1.1.42.1", "Query Velocity State", "--timeout", "5"}, "judp");
  EXPECT_EQ(judp.exit_code, 0) << judp.err;
  relay.stop();

  const auto datagrams = relay.recorded();
  PcapWriter pcap((session.dir() / "exchange.pcap").string());
  for (const auto& d : datagrams) pcap.add(d.from, d.to, d.bytes);
  pcap.close();
  std::string failure;
  const auto layers = session.dissect(session.dir() / "exchange.pcap", {}, failure);
  ASSERT_EQ(layers.size(), datagrams.size()) << failure;

  std::map<std::string, int> seen;                        // message names checked
  std::map<std::string, std::vector<std::uint8_t>> sets;  // large data sets being reassembled, by sender and code
  bool reassembled = false;
  for (std::size_t i = 0; i < datagrams.size(); ++i) {
    SCOPED_TRACE("packet " + std::to_string(i + 1));
    ASSERT_FALSE(layers[i].is_null()) << "not JAUS to tshark";
    const auto message = unframed(datagrams[i].bytes);
    ASSERT_GE(message.size(), 16u);
    const unsigned flag = message[13] >> 4;
    const std::uint16_t code = static_cast<std::uint16_t>(message[2] | (message[3] << 8));
    if (flag == 0) {
      for (const auto& problem : check_jaus_message(session, layers[i], message, "ra")) ADD_FAILURE() << problem;
      ++seen[layers[i]["jaus.header"]["jaus.name"].get<std::string>()];
      continue;
    }
    const std::string key = std::to_string(datagrams[i].from.ip[3]) + ":" + std::to_string(code);
    if (flag == 1) sets[key].clear();
    sets[key].insert(sets[key].end(), message.begin() + 16, message.end());
    if (flag != 8) continue;
    const auto* info = msg::find_message(wire::Dialect::ra, code);
    ASSERT_NE(info, nullptr);
    const auto decoded = info->body_to_json(sets[key], wire::Dialect::ra);
    ASSERT_TRUE(decoded) << decoded.error().message();
    FieldValues expected, shown;
    const std::string prefix = "jaus." + slug(std::string(info->name));
    flatten_decoded(*decoded, prefix, expected);
    flatten_tshark(layers[i], "", shown);
    for (const auto& problem : compare_fields(expected, shown, prefix)) ADD_FAILURE() << "reassembled: " << problem;
    reassembled = true;
  }
  std::string summary;
  for (const auto& [name, count] : seen) summary += " " + name + " x" + std::to_string(count) + ";";
  std::cout << "checked" << summary << (reassembled ? " and a reassembled large data set" : "") << "\n";
  EXPECT_GE(seen["Report Global Pose"], 1);
  EXPECT_GE(seen["Report Services"], 1);
  EXPECT_GE(seen["Report Configuration"], 1);
  EXPECT_GE(seen["Report Velocity State"], 3);
  EXPECT_GE(seen["Confirm Service Connection"], 1);
  // The simulated camera's picture is larger than one packet.
  EXPECT_TRUE(reassembled || seen["Report Image"] >= 1);
}

}  // namespace
}  // namespace jaus::test
