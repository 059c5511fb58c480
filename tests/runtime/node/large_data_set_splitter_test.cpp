#include "jaus/node/large_data_set_splitter.hpp"

#include <gtest/gtest.h>

#include <array>

#include "large_data_set_test_support.hpp"

namespace jaus::node {
namespace {

using test::image_header;
using test::patterned_payload;

TEST(LargeDataSetSplitter, UpTo4080BytesIsOnePacketWithFlag0) {
  for (std::size_t size : {std::size_t{0}, std::size_t{1}, kMaxPayloadSize}) {
    const auto payload = patterned_payload(size);
    auto splitter = LargeDataSetSplitter::create(image_header(7), payload);
    ASSERT_TRUE(splitter) << size;
    ASSERT_EQ(splitter->packet_count(), 1u);
    const PacketView packet = splitter->packet(0);
    EXPECT_EQ(packet.header.data_flag, DataFlag::single);
    EXPECT_EQ(packet.header.data_size, size);
    EXPECT_EQ(packet.header.sequence, 7);
    EXPECT_EQ(packet.payload.size(), size);
  }
}

TEST(LargeDataSetSplitter, SmallerPiecesForASlowRadio) {
  const auto payload = patterned_payload(2500);
  auto splitter = LargeDataSetSplitter::create(image_header(10), payload, 1000);
  ASSERT_TRUE(splitter);
  const auto packets = splitter->packets();
  ASSERT_EQ(packets.size(), 3u);
  const std::array<std::size_t, 3> sizes{1000, 1000, 500};
  for (std::size_t i = 0; i < packets.size(); ++i) {
    EXPECT_EQ(packets[i].payload.size(), sizes[i]) << i;
    EXPECT_EQ(packets[i].payload.data(), payload.data() + 1000 * i) << i;
    EXPECT_EQ(packets[i].header.sequence, 10 + i) << i;
  }
  EXPECT_EQ(packets.back().header.data_flag, DataFlag::last);
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(2500, 1000), 3u);
  // Out of range, the piece is clamped to 1..4080.
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(2500, 0), 2500u);
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(8160, 100000), 2u);
}

TEST(LargeDataSetSplitter, LargerPayloadsGoFirstMiddleLastWithConsecutiveNumbers) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize + 1);
  Header header = image_header(100);
  header.priority = 11;
  auto splitter = LargeDataSetSplitter::create(header, payload);
  ASSERT_TRUE(splitter);
  const auto packets = splitter->packets();
  ASSERT_EQ(packets.size(), 4u);
  const std::array expected_flags{DataFlag::first, DataFlag::middle, DataFlag::middle, DataFlag::last};
  const std::array<std::size_t, 4> expected_sizes{kMaxPayloadSize, kMaxPayloadSize, kMaxPayloadSize, 1};
  for (std::size_t i = 0; i < packets.size(); ++i) {
    EXPECT_EQ(packets[i].header.data_flag, expected_flags[i]);
    EXPECT_EQ(packets[i].header.data_size, expected_sizes[i]);
    EXPECT_EQ(packets[i].payload.size(), expected_sizes[i]);
    EXPECT_EQ(packets[i].payload.data(), payload.data() + i * kMaxPayloadSize);  // views, not copies
    EXPECT_EQ(packets[i].header.sequence, 100 + i);
    EXPECT_EQ(packets[i].header.priority, 11);
    EXPECT_EQ(packets[i].header.command_code, 0x4807);
    EXPECT_EQ(packets[i].header.source, header.source);
    EXPECT_EQ(packets[i].header.destination, header.destination);
  }
}

TEST(LargeDataSetSplitter, ExactlyTwoPacketsAt4081Bytes) {
  const auto payload = patterned_payload(kMaxPayloadSize + 1);
  auto splitter = LargeDataSetSplitter::create(image_header(0), payload);
  ASSERT_TRUE(splitter);
  ASSERT_EQ(splitter->packet_count(), 2u);
  EXPECT_EQ(splitter->packet(0).header.data_flag, DataFlag::first);
  EXPECT_EQ(splitter->packet(1).header.data_flag, DataFlag::last);
  EXPECT_EQ(splitter->packet(1).header.data_size, 1);
}

TEST(LargeDataSetSplitter, SequenceNumbersWrap) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  auto splitter = LargeDataSetSplitter::create(image_header(65534), payload);
  ASSERT_TRUE(splitter);
  EXPECT_EQ(splitter->packet(0).header.sequence, 65534);
  EXPECT_EQ(splitter->packet(1).header.sequence, 65535);
  EXPECT_EQ(splitter->packet(2).header.sequence, 0);
}

TEST(LargeDataSetSplitter, PacketsNeeded) {
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(0), 1u);
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(kMaxPayloadSize), 1u);
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(kMaxPayloadSize + 1), 2u);
  EXPECT_EQ(LargeDataSetSplitter::packets_needed(1024 * 1024), 258u);
}

TEST(LargeDataSetSplitter, EncodedPacketsDecodeBack) {
  const auto payload = patterned_payload(kMaxPayloadSize + 10);
  auto splitter = LargeDataSetSplitter::create(image_header(9), payload);
  ASSERT_TRUE(splitter);
  std::vector<std::uint8_t> buffer(kHeaderSize + kMaxPayloadSize);
  for (std::size_t i = 0; i < splitter->packet_count(); ++i) {
    auto size = splitter->encode(i, buffer);
    ASSERT_TRUE(size) << size.error().message();
    auto decoded = decode_packet(std::span(buffer).first(*size));
    ASSERT_TRUE(decoded) << decoded.error().message();
    EXPECT_EQ(decoded->header, splitter->packet(i).header);
    EXPECT_TRUE(std::equal(decoded->payload.begin(), decoded->payload.end(), splitter->packet(i).payload.begin(),
                           splitter->packet(i).payload.end()));
  }
}

TEST(LargeDataSetSplitter, EncodeRefusesASmallBufferAndABadIndex) {
  const auto payload = patterned_payload(100);
  auto splitter = LargeDataSetSplitter::create(image_header(0), payload);
  ASSERT_TRUE(splitter);
  std::array<std::uint8_t, kHeaderSize + 99> small{};
  auto too_small = splitter->encode(0, small);
  ASSERT_FALSE(too_small);
  EXPECT_EQ(too_small.error().code, ErrorCode::output_too_small);
  std::array<std::uint8_t, kHeaderSize + 100> enough{};
  auto bad_index = splitter->encode(1, enough);
  ASSERT_FALSE(bad_index);
  EXPECT_EQ(bad_index.error().code, ErrorCode::bad_value);
  EXPECT_TRUE(splitter->packet(5).payload.empty());
}

TEST(LargeDataSetSplitter, RefusesABadHeader) {
  const auto payload = patterned_payload(10);
  Header header = image_header(0);
  header.priority = 16;
  auto splitter = LargeDataSetSplitter::create(header, payload);
  ASSERT_FALSE(splitter);
  EXPECT_EQ(splitter.error().field, "priority");
}

TEST(LargeDataSetSplitter, RefusesMoreThan65535Packets) {
  // A view of a buffer never read: only its size matters here.
  static const std::uint8_t byte = 0;
  const std::span<const std::uint8_t> huge(&byte, kMaxPacketsPerSet * kMaxPayloadSize + 1);
  auto splitter = LargeDataSetSplitter::create(image_header(0), huge);
  ASSERT_FALSE(splitter);
  EXPECT_EQ(splitter.error().code, ErrorCode::payload_too_large);
}

}  // namespace
}  // namespace jaus::node
