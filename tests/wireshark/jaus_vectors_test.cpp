// Every JAUS vector of tests/data as a datagram in both framings (OPC from an
// OCU's port to 3794, JUDP back), dissected by tshark with the generated
// plugin and compared field by field with `jausctl msg decode` (the vectors
// are the open RA 3.3 implementation's: both sides read them in its dialect).
#include <gtest/gtest.h>

#include "../core/vector_file.hpp"
#include "jaus/base/hex.hpp"
#include "jaus_message_check.hpp"
#include "pcap_writer.hpp"

namespace jaus::test {
namespace {

std::vector<std::uint8_t> judp(const std::vector<std::uint8_t>& message) {
  std::vector<std::uint8_t> out = {0x01, 0x00, 0x00, static_cast<std::uint8_t>(message.size() >> 8),
                                   static_cast<std::uint8_t>(message.size())};
  out.insert(out.end(), message.begin(), message.end());
  return out;
}

std::vector<std::uint8_t> opc(const std::vector<std::uint8_t>& message) {
  std::vector<std::uint8_t> out = {'J', 'A', 'U', 'S', '0', '1', '.', '0'};
  out.insert(out.end(), message.begin(), message.end());
  return out;
}

TEST(TsharkJausVectors, EveryVectorInBothFramingsShowsWhatJausctlDecodes) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("vectors");
  const UdpEndpoint ocu{{127, 0, 0, 62}, 40000};
  const UdpEndpoint node{{127, 0, 0, 60}, 3794};
  std::vector<std::vector<std::uint8_t>> messages;
  PcapWriter pcap((session.dir() / "vectors.pcap").string());
  for (const auto& v : all_vectors()) {
    const auto parsed = jaus::parse_hex(v.hex);
    ASSERT_TRUE(parsed) << v.code << ": " << parsed.error().message();
    const auto& bytes = *parsed;
    messages.push_back(bytes);
    pcap.add(ocu, node, opc(bytes));
    pcap.add(node, ocu, judp(bytes));
  }
  pcap.close();

  std::string failure;
  const auto layers = session.dissect(session.dir() / "vectors.pcap", {"jaus.dialect:openjaus"}, failure);
  ASSERT_EQ(layers.size(), 2 * messages.size()) << failure;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    for (std::size_t framing = 0; framing < 2; ++framing) {
      const auto& layer = layers[2 * i + framing];
      ASSERT_FALSE(layer.is_null()) << "packet " << 2 * i + framing + 1 << " is not JAUS to tshark";
      EXPECT_EQ(layer["jaus.framing"], framing == 0 ? "OPC" : "JUDP");
      for (const auto& problem : check_jaus_message(session, layer, messages[i], "openjaus"))
        ADD_FAILURE() << "vector " << all_vectors()[i].code << (framing == 0 ? " (OPC)" : " (JUDP)") << ": " << problem;
    }
  }
}

}  // namespace
}  // namespace jaus::test
