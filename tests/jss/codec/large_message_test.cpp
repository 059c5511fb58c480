// Large JSS messages (docs/jss.md, "The bytes on the wire"): split into first/middle/last packets
// with consecutive sequence numbers, put back together per source; every
// bound has its rule and its counter.
#include <gtest/gtest.h>

#include <chrono>

#include "jaus/jss/large_message.hpp"

namespace jaus::test::jss_large {

using namespace jaus::jss;
using namespace std::chrono_literals;

std::vector<std::uint8_t> contents_of(std::size_t n, std::uint16_t id = 0x4B03) {
  std::vector<std::uint8_t> out(n);
  out[0] = static_cast<std::uint8_t>(id);
  out[1] = static_cast<std::uint8_t>(id >> 8);
  for (std::size_t i = 2; i < n; ++i) out[i] = static_cast<std::uint8_t>(i * 7);
  return out;
}

JudpHeader header_from(JssId source, std::uint16_t sequence) {
  JudpHeader h;
  h.source = source;
  h.destination = {1, 1, 1};
  h.sequence = sequence;
  return h;
}

// Decoded packets of the datagrams (their contents view `datagrams`).
std::vector<JudpPacket> packets_of(const std::vector<std::vector<std::uint8_t>>& datagrams) {
  std::vector<JudpPacket> out;
  for (const auto& d : datagrams) {
    auto decoded = decode_judp_datagram(d);
    EXPECT_TRUE(decoded);
    if (decoded) out.push_back((*decoded)[0]);
  }
  return out;
}

TEST(JssLargeMessage, SplitFlagsAndSequenceNumbers) {
  const auto contents = contents_of(3500);
  const auto datagrams = make_judp_datagrams(header_from({42, 1, 1}, 65534), contents, 1400);
  ASSERT_TRUE(datagrams);
  const auto packets = packets_of(*datagrams);
  ASSERT_EQ(packets.size(), 3u);
  EXPECT_EQ(packets[0].header.data_flag, JudpDataFlag::first);
  EXPECT_EQ(packets[1].header.data_flag, JudpDataFlag::middle);
  EXPECT_EQ(packets[2].header.data_flag, JudpDataFlag::last);
  EXPECT_EQ(packets[0].header.sequence, 65534);
  EXPECT_EQ(packets[1].header.sequence, 65535);
  EXPECT_EQ(packets[2].header.sequence, 0);  // wraps
  EXPECT_EQ(message_id_of(packets[0].contents), 0x4B03);
  EXPECT_EQ(packets[0].contents.size() + packets[1].contents.size() + packets[2].contents.size(), 3500u);

  const auto single = make_judp_datagrams(header_from({42, 1, 1}, 5), contents_of(1400), 1400);
  ASSERT_TRUE(single);
  ASSERT_EQ(single->size(), 1u);
  EXPECT_EQ(packets_of(*single)[0].header.data_flag, JudpDataFlag::single);

  EXPECT_EQ(split_contents(contents, 1).error().code, ErrorCode::invalid_argument);
  JudpHeader broadcast = header_from({42, 1, 1}, 0);
  broadcast.destination = {65535, 255, 255};
  EXPECT_EQ(make_judp_datagrams(broadcast, contents, 1400).error().code, ErrorCode::payload_too_large);
}

TEST(JssLargeMessage, ReassemblesPerSourceEvenInterleaved) {
  const auto a = contents_of(3000, 0x4B03);
  const auto b = contents_of(2000, 0x4B04);
  const auto da = make_judp_datagrams(header_from({42, 1, 1}, 100), a, 1000);
  const auto db = make_judp_datagrams(header_from({43, 1, 1}, 100), b, 1000);
  const auto pa = packets_of(*da);
  const auto pb = packets_of(*db);
  LargeMessageReassembler r;
  const rt::TimePoint t{};
  std::optional<WholeMessage> whole_a, whole_b;
  for (std::size_t i = 0; i < 3; ++i) {
    auto got = r.add(pa[i], t);
    ASSERT_TRUE(got) << got.error().message();
    if (*got) whole_a = std::move(**got);
    if (i < pb.size()) {
      auto other = r.add(pb[i], t);
      ASSERT_TRUE(other) << other.error().message();
      if (*other) whole_b = std::move(**other);
    }
  }
  ASSERT_TRUE(whole_a && whole_b);
  EXPECT_EQ(whole_a->contents, a);
  EXPECT_EQ(whole_b->contents, b);
  EXPECT_EQ(whole_a->header.source, (JssId{42, 1, 1}));
  EXPECT_EQ(whole_a->header.sequence, 100);
  EXPECT_EQ(whole_a->header.data_flag, JudpDataFlag::single);
  EXPECT_EQ(r.counters().completed, 2u);
  EXPECT_EQ(r.sets_in_progress(), 0u);
  EXPECT_EQ(r.bytes_in_progress(), 0u);
}

TEST(JssLargeMessage, GapsStraysAndTimeouts) {
  const auto packets_data = make_judp_datagrams(header_from({42, 1, 1}, 10), contents_of(3000), 1000);
  const auto p = packets_of(*packets_data);
  const rt::TimePoint t{};
  {
    LargeMessageReassembler r;
    ASSERT_TRUE(r.add(p[0], t));
    const auto gap = r.add(p[2], t);  // the middle one was lost
    ASSERT_FALSE(gap);
    EXPECT_EQ(gap.error().code, ErrorCode::malformed);
    EXPECT_EQ(r.counters().stray, 1u);
    EXPECT_EQ(r.sets_in_progress(), 1u);
  }
  {
    LargeMessageReassembler r(ReassemblyLimits{.timeout = 2s});
    ASSERT_TRUE(r.add(p[0], t));
    ASSERT_TRUE(r.add(p[1], t + 1s));
    const auto late = r.add(p[2], t + 3s + 1ms);  // 2 s after the middle one
    ASSERT_FALSE(late);
    EXPECT_EQ(r.counters().timed_out, 1u);
    EXPECT_EQ(r.counters().stray, 1u);
    EXPECT_EQ(r.bytes_in_progress(), 0u);
  }
  {
    LargeMessageReassembler r;
    JudpPacket tiny = p[0];
    tiny.contents = tiny.contents.first(1);
    EXPECT_FALSE(r.add(tiny, t));
    EXPECT_EQ(r.counters().bad_first, 1u);
  }
}

TEST(JssLargeMessage, BoundsHaveRules) {
  const rt::TimePoint t{};
  // Bytes per message.
  {
    LargeMessageReassembler r(ReassemblyLimits{.max_set_bytes = 2500});
    const auto d = make_judp_datagrams(header_from({42, 1, 1}, 0), contents_of(3000), 1000);
    const auto p = packets_of(*d);
    ASSERT_TRUE(r.add(p[0], t));
    ASSERT_TRUE(r.add(p[1], t));
    EXPECT_EQ(r.add(p[2], t).error().code, ErrorCode::payload_too_large);
    EXPECT_EQ(r.counters().too_large, 1u);
    EXPECT_EQ(r.sets_in_progress(), 0u);
  }
  // Sets in progress: the source's own oldest goes first; then other sources are refused.
  {
    LargeMessageReassembler r(ReassemblyLimits{.max_sets = 3, .max_sets_per_source = 2});
    std::vector<std::vector<std::vector<std::uint8_t>>> keep;
    auto first_from = [&](JssId source, std::uint16_t sequence) {
      keep.push_back(*make_judp_datagrams(header_from(source, sequence), contents_of(3000), 1000));
      return packets_of(keep.back())[0];
    };
    ASSERT_TRUE(r.add(first_from({42, 1, 1}, 0), t));
    ASSERT_TRUE(r.add(first_from({42, 1, 1}, 10), t));
    ASSERT_TRUE(r.add(first_from({42, 1, 1}, 20), t));  // supersedes sequence 0
    EXPECT_EQ(r.counters().superseded, 1u);
    EXPECT_EQ(r.sets_in_progress(), 2u);
    ASSERT_TRUE(r.add(first_from({43, 1, 1}, 0), t));
    const auto refused = r.add(first_from({44, 1, 1}, 0), t);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::refused);
    EXPECT_EQ(r.counters().refused, 1u);
    EXPECT_EQ(r.sets_in_progress(), 3u);
  }
  // Total bytes.
  {
    LargeMessageReassembler r(ReassemblyLimits{.max_total_bytes = 1500});
    std::vector<std::vector<std::vector<std::uint8_t>>> keep;
    keep.push_back(*make_judp_datagrams(header_from({42, 1, 1}, 0), contents_of(3000), 1000));
    keep.push_back(*make_judp_datagrams(header_from({43, 1, 1}, 0), contents_of(3000), 1000));
    ASSERT_TRUE(r.add(packets_of(keep[0])[0], t));
    EXPECT_EQ(r.add(packets_of(keep[1])[0], t).error().code, ErrorCode::payload_too_large);
    EXPECT_LE(r.bytes_in_progress(), 1500u);
  }
}

}  // namespace jaus::test::jss_large
