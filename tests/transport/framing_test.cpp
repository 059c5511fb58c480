// Datagram framings (OPC "JAUS01.0" and JUDP): every vector framed both ways
// unframes to the same message; anything else is dropped with its reason.
#include <gtest/gtest.h>

#include "../core/vector_file.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/transport/framing.hpp"

namespace jaus::transport {
namespace {

std::vector<std::uint8_t> framed(Framing framing, const std::vector<std::uint8_t>& message) {
  const FramePrefix prefix = frame_prefix(framing, message.size());
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), message.begin(), message.end());
  return out;
}

std::vector<std::uint8_t> bytes_of(const std::string& hex) {
  auto out = parse_hex(hex);
  EXPECT_TRUE(out) << out.error().message();
  return out ? *out : std::vector<std::uint8_t>{};
}

TEST(Framing, EveryVectorUnframesInBothFramings) {
  for (const auto& vector : test::all_vectors()) {
    const auto message = bytes_of(vector.hex);
    for (const Framing framing : {Framing::opc, Framing::judp}) {
      const auto datagram = framed(framing, message);
      auto unframed = unframe(datagram);
      ASSERT_TRUE(unframed) << vector.code << " " << to_string(framing) << ": " << unframed.error().detail;
      EXPECT_EQ(unframed->framing, framing);
      EXPECT_EQ(unframed->packet.header.command_code, std::stoul(vector.code, nullptr, 16));
      EXPECT_EQ(unframed->packet.payload.size() + kHeaderSize, message.size());
    }
  }
}

TEST(Framing, PrefixesAreTheOnesOnTheWire) {
  const std::vector<std::uint8_t> message(16 + 0x123 - 16, 0);
  EXPECT_EQ(to_hex(frame_prefix(Framing::opc, message.size()).view()), "4A41555330312E30");
  EXPECT_EQ(to_hex(frame_prefix(Framing::judp, 0x123).view()), "0100000123");  // length big-endian
}

struct BadDatagram {
  const char* what;
  std::string hex;
  DropReason reason;
};

TEST(Framing, NonJausDatagramsAreDroppedWithTheirReason) {
  const std::string status_query = "0602022001210101012801020000" "0B0A";  // Query Component Status, empty
  ASSERT_TRUE(decode_packet(bytes_of(status_query)));
  const std::vector<BadDatagram> cases = {
      {"empty", "", DropReason::unknown_framing},
      {"garbage", "DEADBEEF", DropReason::unknown_framing},
      {"HTTP", "474554202F20485454502F312E310D0A", DropReason::unknown_framing},
      {"OPC prefix only", "4A41555330312E30", DropReason::truncated},
      {"OPC, header cut", "4A41555330312E30" + status_query.substr(0, 20), DropReason::truncated},
      {"OPC, one byte too many", "4A41555330312E30" + status_query + "00", DropReason::length_mismatch},
      {"JUDP prefix cut", "010000", DropReason::truncated},
      {"JUDP length too long", "0100000011" + status_query, DropReason::length_mismatch},
      {"JUDP length too short", "010000000F" + status_query, DropReason::length_mismatch},
      {"JUDP compressed header", "0101000010" + status_query, DropReason::unknown_framing},
      {"OPC, version 9", "4A41555330312E30" "0609" + status_query.substr(4), DropReason::bad_header},
      {"OPC, 4081-byte data size", "4A41555330312E30" + status_query.substr(0, 24) + "F10F0B0A",
       DropReason::bad_header},
  };
  for (const auto& c : cases) {
    auto result = unframe(bytes_of(c.hex));
    ASSERT_FALSE(result) << c.what;
    EXPECT_EQ(drop_reason(result.error()), c.reason) << c.what << ": " << result.error().message();
    EXPECT_FALSE(result.error().detail.empty()) << c.what;
    // Offsets are in the datagram: a header's fields come after the 8-byte OPC prefix.
    if (c.reason == DropReason::bad_header) {
      EXPECT_GE(result.error().offset, kOpcPrefix.size()) << c.what;
    }
  }
  const std::vector<std::uint8_t> huge(kMaxDatagramSize + 1, 0x4A);
  auto oversized = unframe(huge);
  ASSERT_FALSE(oversized);
  EXPECT_EQ(drop_reason(oversized.error()), DropReason::oversized);
}

TEST(Framing, EveryTruncationOfAFramedVectorIsAnError) {
  const auto message = bytes_of(test::all_vectors().front().hex);
  for (const Framing framing : {Framing::opc, Framing::judp}) {
    const auto datagram = framed(framing, message);
    for (std::size_t size = 0; size < datagram.size(); ++size)
      EXPECT_FALSE(unframe(std::span(datagram).first(size))) << to_string(framing) << " cut at " << size;
  }
}

}  // namespace
}  // namespace jaus::transport
