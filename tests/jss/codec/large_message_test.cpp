// Large JSS messages (docs/jss.md, "The bytes on the wire"): split into first/middle/last packets
// with consecutive sequence numbers, put back together per source and
// destination by the one assembler (jaus/core/large_message_assembler.hpp), in
// any order, a copy of a piece taken once; every bound has its rule and its counter.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <numeric>

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

using Assembled = JssLargeMessageAssembler::Result;

Assembled feed(JssLargeMessageAssembler& assembler, const JudpPacket& packet, rt::TimePoint now = {}) {
  return assembler.feed(packet.header, packet.contents, now);
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
  JssLargeMessageAssembler r;
  std::optional<AssembledMessage<JudpHeader>> whole_a, whole_b;
  for (std::size_t i = 0; i < 3; ++i) {
    auto got = feed(r, pa[i]);
    ASSERT_NE(got.status, AssemblyStatus::dropped) << to_string(got.issue);
    if (got.message) whole_a = std::move(got.message);
    if (i < pb.size()) {
      auto other = feed(r, pb[i]);
      ASSERT_NE(other.status, AssemblyStatus::dropped) << to_string(other.issue);
      if (other.message) whole_b = std::move(other.message);
    }
  }
  ASSERT_TRUE(whole_a && whole_b);
  EXPECT_EQ(whole_a->payload, a);
  EXPECT_EQ(whole_b->payload, b);
  EXPECT_EQ(whole_a->header.source, (JssId{42, 1, 1}));
  EXPECT_EQ(whole_a->header.sequence, 100);
  EXPECT_EQ(whole_a->header.data_flag, JudpDataFlag::single);
  EXPECT_EQ(r.counters().completed, 2u);
  EXPECT_EQ(r.sets_in_progress(), 0u);
  EXPECT_EQ(r.buffered_bytes(), 0u);
}

TEST(JssLargeMessage, ASinglePacketIsWholeAtOnce) {
  const auto d = make_judp_datagrams(header_from({42, 1, 1}, 7), contents_of(20), 1400);
  JssLargeMessageAssembler r;
  const auto single = feed(r, packets_of(*d)[0]);
  EXPECT_EQ(single.status, AssemblyStatus::single);
  EXPECT_FALSE(single.message);  // the caller uses the packet as it is: nothing copied
  EXPECT_EQ(r.counters().singles, 1u);
  EXPECT_EQ(r.sets_in_progress(), 0u);
}

// As RA peers have always been taken: every arrival order, with a copy of one
// piece anywhere in it (a retransmission), gives the message once.
TEST(JssLargeMessage, OutOfOrderWithARetransmittedPieceIsPutTogetherOnce) {
  const auto contents = contents_of(3500);
  const auto d = make_judp_datagrams(header_from({42, 1, 1}, 65534), contents, 1000);  // 4 pieces, wrapping
  const auto pieces = packets_of(*d);
  ASSERT_EQ(pieces.size(), 4u);
  std::vector<std::size_t> order(pieces.size());
  std::iota(order.begin(), order.end(), 0);
  int orders = 0;
  do {
    for (std::size_t copied = 0; copied < pieces.size(); ++copied) {
      JssLargeMessageAssembler r;
      std::vector<std::size_t> arrivals = order;
      arrivals.insert(arrivals.begin() + static_cast<std::ptrdiff_t>(1 + copied % 3), copied);
      int whole = 0;
      for (const std::size_t i : arrivals) {
        auto got = feed(r, pieces[i]);
        if (got.status != AssemblyStatus::complete) continue;
        ++whole;
        EXPECT_EQ(got.message->payload, contents);
        EXPECT_EQ(got.message->header.sequence, 65534);
        EXPECT_EQ(got.message->header.data_flag, JudpDataFlag::single);
      }
      // The copy that comes after completion is a late duplicate: never a second message.
      EXPECT_EQ(feed(r, pieces[copied]).issue, AssemblyIssue::duplicate);
      EXPECT_EQ(whole, 1);
      EXPECT_EQ(r.counters().completed, 1u);
      EXPECT_EQ(r.counters().duplicates, 2u);
      EXPECT_EQ(r.buffered_bytes(), 0u);
    }
    ++orders;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(orders, 24);
}

TEST(JssLargeMessage, ConsecutiveMessagesOfOneSenderEachCompleteInAnyOrder) {
  const auto a = contents_of(2500, 0x4B03);
  const auto b = contents_of(2500, 0x4B04);
  const auto da = make_judp_datagrams(header_from({42, 1, 1}, 10), a, 1000);  // 10..12
  const auto db = make_judp_datagrams(header_from({42, 1, 1}, 13), b, 1000);  // 13..15
  const auto pa = packets_of(*da);
  const auto pb = packets_of(*db);
  JssLargeMessageAssembler r;
  EXPECT_EQ(feed(r, pa[2]).status, AssemblyStatus::pending);
  EXPECT_EQ(feed(r, pa[0]).status, AssemblyStatus::pending);
  EXPECT_EQ(feed(r, pa[1]).message->payload, a);
  EXPECT_EQ(feed(r, pb[1]).status, AssemblyStatus::pending);  // past the first message's range: the next one
  EXPECT_EQ(feed(r, pb[2]).status, AssemblyStatus::pending);
  const auto whole_b = feed(r, pb[0]);
  ASSERT_EQ(whole_b.status, AssemblyStatus::complete);
  EXPECT_EQ(whole_b.message->payload, b);
  EXPECT_EQ(message_id_of(whole_b.message->payload), 0x4B04);
  EXPECT_EQ(r.counters().completed, 2u);
}

TEST(JssLargeMessage, GapsAndTimeouts) {
  const auto packets_data = make_judp_datagrams(header_from({42, 1, 1}, 10), contents_of(3000), 1000);
  const auto p = packets_of(*packets_data);
  const rt::TimePoint t{};
  {
    JssLargeMessageAssembler r;
    EXPECT_EQ(feed(r, p[0], t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, p[2], t).status, AssemblyStatus::pending);  // the middle one is late, or lost
    EXPECT_EQ(r.sets_in_progress(), 1u);
    EXPECT_EQ(r.counters().completed, 0u);
    // Lost: the set times out, counted and reported.
    EXPECT_TRUE(r.expire(t + 1s).empty());
    const auto expired = r.expire(t + 2s);
    ASSERT_EQ(expired.size(), 1u);
    EXPECT_EQ(expired[0].key, (JssLargeMessageAssembler::Key{{42, 1, 1}, {1, 1, 1}, 0}));
    EXPECT_EQ(expired[0].reason, AssemblyIssue::timed_out);
    EXPECT_EQ(expired[0].pieces, 2u);
    EXPECT_EQ(r.counters().timed_out, 1u);
    EXPECT_EQ(r.buffered_bytes(), 0u);
  }
  {
    JssLargeMessageAssembler r(AssemblyLimits{.timeout = 2s});
    EXPECT_EQ(feed(r, p[0], t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, p[1], t + 1s).status, AssemblyStatus::pending);
    const auto late = feed(r, p[2], t + 3s + 1ms);  // 2 s after the middle one: the set is gone
    EXPECT_EQ(late.status, AssemblyStatus::pending);  // and the late piece starts another, never completed
    EXPECT_EQ(r.counters().timed_out, 1u);
    EXPECT_EQ(r.counters().completed, 0u);
    EXPECT_EQ(r.buffered_bytes(), p[2].contents.size());
  }
  {
    JssLargeMessageAssembler r;
    JudpPacket tiny = p[0];
    tiny.contents = tiny.contents.first(1);
    EXPECT_EQ(feed(r, tiny, t).issue, AssemblyIssue::bad_first);
    EXPECT_EQ(r.counters().bad_first, 1u);
    EXPECT_EQ(r.sets_in_progress(), 0u);
  }
}

TEST(JssLargeMessage, BoundsHaveRules) {
  const rt::TimePoint t{};
  // Bytes per message: the set goes, and the rest of its pieces with it.
  {
    JssLargeMessageAssembler r(AssemblyLimits{.max_message_size = 2500});
    const auto d = make_judp_datagrams(header_from({42, 1, 1}, 0), contents_of(4000), 1000);
    const auto p = packets_of(*d);
    EXPECT_EQ(feed(r, p[0], t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, p[1], t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, p[2], t).issue, AssemblyIssue::too_large);
    EXPECT_EQ(feed(r, p[3], t).issue, AssemblyIssue::rest_of_discarded_set);
    EXPECT_EQ(r.counters().too_large, 1u);
    EXPECT_EQ(r.counters().stray, 1u);
    EXPECT_EQ(r.sets_in_progress(), 0u);
    EXPECT_EQ(r.buffered_bytes(), 0u);
  }
  // Sets in progress: the source's own oldest goes first; then other sources are refused.
  {
    JssLargeMessageAssembler r(AssemblyLimits{.max_sets = 3, .max_sets_per_source = 2});
    std::vector<std::vector<std::vector<std::uint8_t>>> keep;
    auto first_from = [&](JssId source, std::uint8_t to_component) {
      JudpHeader h = header_from(source, 0);
      h.destination.component = to_component;
      keep.push_back(*make_judp_datagrams(h, contents_of(3000), 1000));
      return packets_of(keep.back())[0];
    };
    EXPECT_EQ(feed(r, first_from({42, 1, 1}, 1), t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, first_from({42, 1, 1}, 2), t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, first_from({42, 1, 1}, 3), t).status, AssemblyStatus::pending);  // discards the one to 1
    EXPECT_EQ(r.counters().superseded, 1u);
    EXPECT_EQ(r.sets_in_progress(), 2u);
    EXPECT_EQ(feed(r, first_from({43, 1, 1}, 1), t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, first_from({44, 1, 1}, 1), t).issue, AssemblyIssue::refused);
    EXPECT_EQ(r.counters().refused, 1u);
    EXPECT_EQ(r.sets_in_progress(), 3u);
    // Stale sets make room.
    EXPECT_EQ(feed(r, first_from({44, 1, 1}, 1), t + 5s).status, AssemblyStatus::pending);
    EXPECT_EQ(r.counters().timed_out, 3u);
  }
  // Total bytes.
  {
    JssLargeMessageAssembler r(AssemblyLimits{.max_total_bytes = 1500});
    std::vector<std::vector<std::vector<std::uint8_t>>> keep;
    keep.push_back(*make_judp_datagrams(header_from({42, 1, 1}, 0), contents_of(3000), 1000));
    keep.push_back(*make_judp_datagrams(header_from({43, 1, 1}, 0), contents_of(3000), 1000));
    EXPECT_EQ(feed(r, packets_of(keep[0])[0], t).status, AssemblyStatus::pending);
    EXPECT_EQ(feed(r, packets_of(keep[1])[0], t).issue, AssemblyIssue::too_large);
    EXPECT_EQ(r.counters().too_large, 1u);
    EXPECT_LE(r.buffered_bytes(), 1500u);
  }
}

}  // namespace jaus::test::jss_large
