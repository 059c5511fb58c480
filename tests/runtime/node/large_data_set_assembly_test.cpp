#include "jaus/core/large_data_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>

#include "jaus/node/large_data_set_splitter.hpp"
#include "jaus/base/virtual_time.hpp"
#include "large_data_set_test_support.hpp"

namespace jaus::node {
namespace {

using namespace std::chrono_literals;
using test::image_header;
using test::patterned_payload;

// One packet with its own copy of the bytes (so tests can alter it).
struct Packet {
  Header header;
  std::vector<std::uint8_t> payload;
};

std::vector<Packet> split(const Header& header, const std::vector<std::uint8_t>& payload) {
  auto splitter = LargeDataSetSplitter::create(header, payload);
  EXPECT_TRUE(splitter);
  std::vector<Packet> packets;
  for (const PacketView& view : splitter->packets())
    packets.push_back({view.header, {view.payload.begin(), view.payload.end()}});
  return packets;
}

RaLargeMessageAssembler::Result feed(RaLargeMessageAssembler& assembler, const Packet& packet, rt::TimePoint now = {},
                                     std::uint8_t doubt = 0) {
  return assembler.feed(packet.header, packet.payload, now, doubt);
}

Packet retransmission_of(Packet packet) {
  packet.header.data_flag = DataFlag::retransmitted;
  return packet;
}

// Each packet's doubt (the node gives its sender's standing) is kept with its
// set: the whole set carries the most of its packets', whichever completes it,
// and a set started anew starts from its new first packet's.
TEST(RaLargeMessageAssembler, AWholeSetCarriesTheMostDoubtOfItsPackets) {
  const auto payload = patterned_payload(3 * 4080);
  const auto packets = split(image_header(40), payload);
  ASSERT_GE(packets.size(), 3u);
  RaLargeMessageAssembler assembler;
  EXPECT_EQ(feed(assembler, packets[1], {}, 2).status, AssemblyStatus::pending);
  for (std::size_t i = 2; i < packets.size(); ++i)
    EXPECT_EQ(feed(assembler, packets[i]).status, AssemblyStatus::pending) << i;
  const auto whole = feed(assembler, packets[0]);
  ASSERT_EQ(whole.status, AssemblyStatus::complete);
  EXPECT_EQ(whole.message->doubt, 2u);

  // A middle packet of doubt 1, then another message (its first packet held
  // with other bytes): the new set starts from 0, and its own packets count.
  RaLargeMessageAssembler again;
  EXPECT_EQ(feed(again, packets[1], {}, 1).status, AssemblyStatus::pending);
  Packet other = packets[1];
  other.payload.front() ^= 0xFF;
  EXPECT_EQ(feed(again, other).issue, AssemblyIssue::superseded);
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (i == 1) continue;
    const auto result = feed(again, packets[i]);
    if (i + 1 == packets.size()) {
      ASSERT_EQ(result.status, AssemblyStatus::complete);
      EXPECT_EQ(result.message->doubt, 0u);
    }
  }
}

class LargeDataSetRoundTrip : public ::testing::TestWithParam<std::size_t> {};

TEST_P(LargeDataSetRoundTrip, SplitThenReassembleGivesThePayloadBack) {
  const auto payload = patterned_payload(GetParam());
  const auto packets = split(image_header(40), payload);
  RaLargeMessageAssembler assembler;
  for (std::size_t i = 0; i + 1 < packets.size(); ++i)
    EXPECT_EQ(feed(assembler, packets[i]).status, AssemblyStatus::pending) << i;
  const auto last = feed(assembler, packets.back());
  if (packets.size() == 1) {
    EXPECT_EQ(last.status, AssemblyStatus::single);  // the caller uses the packet itself
    EXPECT_EQ(packets[0].payload, payload);
    return;
  }
  ASSERT_EQ(last.status, AssemblyStatus::complete);
  ASSERT_TRUE(last.message);
  EXPECT_EQ(last.message->payload, payload);
  EXPECT_EQ(last.message->header, packets.front().header);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
  EXPECT_EQ(assembler.buffered_bytes(), 0u);
  EXPECT_EQ(assembler.counters().completed, 1u);
}

INSTANTIATE_TEST_SUITE_P(Sizes, LargeDataSetRoundTrip,
                         ::testing::Values(0, 1, kMaxPayloadSize, kMaxPayloadSize + 1, 3 * kMaxPayloadSize + 1,
                                           1024 * 1024));

// Feeds `packets` in the order given by `order`; expects completion on the last one only.
void expect_completes_in_order(const std::vector<Packet>& packets, const std::vector<std::size_t>& order,
                               const std::vector<std::uint8_t>& payload) {
  RaLargeMessageAssembler assembler;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto result = feed(assembler, packets[order[i]]);
    if (i + 1 < order.size()) {
      ASSERT_EQ(result.status, AssemblyStatus::pending) << "packet " << order[i];
    } else {
      ASSERT_EQ(result.status, AssemblyStatus::complete);
      EXPECT_EQ(result.message->payload, payload);
      EXPECT_EQ(result.message->header.data_flag, DataFlag::first);
    }
  }
}

TEST(RaLargeMessageAssembler, EveryArrivalOrderOfAFourPacketSet) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize + 17);
  const auto packets = split(image_header(1000), payload);
  ASSERT_EQ(packets.size(), 4u);
  std::vector<std::size_t> order{0, 1, 2, 3};
  int permutations = 0;
  do {
    SCOPED_TRACE(::testing::PrintToString(order));
    expect_completes_in_order(packets, order, payload);
    ++permutations;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(permutations, 24);
}

TEST(RaLargeMessageAssembler, EveryArrivalOrderAcrossTheSequenceWrap) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize + 17);
  const auto packets = split(image_header(65534), payload);  // 65534, 65535, 0, 1
  ASSERT_EQ(packets[2].header.sequence, 0);
  std::vector<std::size_t> order{0, 1, 2, 3};
  do {
    SCOPED_TRACE(::testing::PrintToString(order));
    expect_completes_in_order(packets, order, payload);
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(RaLargeMessageAssembler, DuplicatesAreIgnoredAndCounted) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  const auto packets = split(image_header(5), payload);
  RaLargeMessageAssembler assembler;
  EXPECT_EQ(feed(assembler, packets[0]).status, AssemblyStatus::pending);
  auto duplicate_first = feed(assembler, packets[0]);
  EXPECT_EQ(duplicate_first.status, AssemblyStatus::dropped);
  EXPECT_EQ(duplicate_first.issue, AssemblyIssue::duplicate);
  EXPECT_EQ(feed(assembler, packets[2]).status, AssemblyStatus::pending);
  EXPECT_EQ(feed(assembler, packets[2]).issue, AssemblyIssue::duplicate);
  // A duplicate with different bytes is still a duplicate: the first copy stays.
  Packet altered_middle = packets[1];
  altered_middle.payload[0] ^= 0xFF;
  EXPECT_EQ(feed(assembler, packets[1]).status, AssemblyStatus::complete);
  // Late copies of a completed set are recognised, not taken for a new set.
  EXPECT_EQ(feed(assembler, altered_middle).issue, AssemblyIssue::duplicate);
  EXPECT_EQ(feed(assembler, packets[2]).issue, AssemblyIssue::duplicate);
  EXPECT_EQ(feed(assembler, retransmission_of(packets[1])).issue, AssemblyIssue::duplicate);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
  EXPECT_EQ(assembler.counters().duplicates, 5u);
  EXPECT_EQ(assembler.counters().completed, 1u);
  // Except a first packet: it always starts a message (some senders number every set from 0).
  EXPECT_EQ(feed(assembler, packets[0]).status, AssemblyStatus::pending);
  EXPECT_EQ(assembler.sets_in_progress(), 1u);
}

TEST(RaLargeMessageAssembler, SendersThatNumberEverySetFromZero) {
  RaLargeMessageAssembler assembler;
  for (std::uint8_t image = 0; image < 4; ++image) {
    SCOPED_TRACE(static_cast<int>(image));
    // Images 2 and 3 are identical, as a still scene or a test pattern gives.
    const auto payload = patterned_payload(3 * kMaxPayloadSize - 1, image < 3 ? image : 2);
    const auto packets = split(image_header(0), payload);
    feed(assembler, packets[0]);
    feed(assembler, packets[1]);
    const auto done = feed(assembler, packets[2]);
    ASSERT_EQ(done.status, AssemblyStatus::complete);
    EXPECT_EQ(done.message->payload, payload);
  }
  EXPECT_EQ(assembler.counters().completed, 4u);
}

TEST(RaLargeMessageAssembler, AFirstPacketWithItsNumberHeldByOtherBytesStartsANewMessage) {
  const auto unfinished = split(image_header(0), patterned_payload(4 * kMaxPayloadSize, 1));
  const auto payload = patterned_payload(3 * kMaxPayloadSize, 2);
  const auto next = split(image_header(0), payload);
  RaLargeMessageAssembler assembler;
  feed(assembler, unfinished[0]);
  feed(assembler, unfinished[1]);
  EXPECT_EQ(feed(assembler, next[0]).issue, AssemblyIssue::superseded);
  EXPECT_EQ(feed(assembler, next[1]).status, AssemblyStatus::pending);
  const auto done = feed(assembler, next[2]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, PacketsOfTwoMessagesWithTheSameNumbersAreNeverMixed) {
  // The older message lost its last packet, the newer one its first; both
  // are numbered from 0. Nothing may complete from a mix of the two.
  const auto older = split(image_header(0), patterned_payload(6 * kMaxPayloadSize, 1));
  const auto payload = patterned_payload(4 * kMaxPayloadSize, 2);
  const auto newer = split(image_header(0), payload);
  for (const std::size_t newer_first_arrival : {std::size_t{1}, std::size_t{3}}) {
    SCOPED_TRACE(newer_first_arrival);
    RaLargeMessageAssembler assembler;
    for (std::size_t i = 0; i < 5; ++i) feed(assembler, older[i]);
    // 1 is a middle packet of both; 3 is the newer one's last and the older one's middle.
    const auto conflict = feed(assembler, newer[newer_first_arrival]);
    EXPECT_EQ(conflict.status, AssemblyStatus::pending);
    EXPECT_EQ(conflict.issue, AssemblyIssue::superseded);
    for (std::size_t i = 1; i < newer.size(); ++i)
      EXPECT_NE(feed(assembler, newer[i]).status, AssemblyStatus::complete) << i;
    // The newer first packet, late, completes the newer message alone.
    const auto done = feed(assembler, newer[0]);
    ASSERT_EQ(done.status, AssemblyStatus::complete);
    EXPECT_EQ(done.message->payload, payload);
  }
}

TEST(RaLargeMessageAssembler, DuplicateMiddleBeforeCompletion) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  const auto packets = split(image_header(5), payload);
  RaLargeMessageAssembler assembler;
  feed(assembler, packets[1]);
  EXPECT_EQ(feed(assembler, packets[1]).issue, AssemblyIssue::duplicate);
  feed(assembler, packets[0]);
  const auto done = feed(assembler, packets[2]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, ARetransmittedPacketReplacesTheOneWithItsNumber) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  const auto packets = split(image_header(300), payload);
  RaLargeMessageAssembler assembler;
  Packet corrupted = packets[1];
  std::fill(corrupted.payload.begin(), corrupted.payload.end(), 0xEE);
  feed(assembler, packets[0]);
  feed(assembler, corrupted);
  const auto replaced = feed(assembler, retransmission_of(packets[1]));
  EXPECT_EQ(replaced.status, AssemblyStatus::pending);
  EXPECT_EQ(replaced.issue, AssemblyIssue::replaced);
  const auto done = feed(assembler, packets[2]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
  EXPECT_EQ(assembler.counters().replaced, 1u);
}

TEST(RaLargeMessageAssembler, ARetransmissionFillsAGap) {
  const auto payload = patterned_payload(4 * kMaxPayloadSize);
  const auto packets = split(image_header(300), payload);
  RaLargeMessageAssembler assembler;
  feed(assembler, packets[0]);
  feed(assembler, packets[1]);
  feed(assembler, packets[3]);
  const auto done = feed(assembler, retransmission_of(packets[2]));  // packet 2 was lost
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, ARetransmittedLastPacketBeforeItsOriginalOnlyLacksItsRole) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  const auto packets = split(image_header(300), payload);
  RaLargeMessageAssembler assembler;
  feed(assembler, packets[0]);
  feed(assembler, retransmission_of(packets[2]));
  feed(assembler, packets[1]);
  const auto done = feed(assembler, packets[2]);  // the original, late
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, ARetransmissionWithoutASetIsDropped) {
  const auto packets = split(image_header(0), patterned_payload(2 * kMaxPayloadSize));
  RaLargeMessageAssembler assembler;
  const auto result = feed(assembler, retransmission_of(packets[1]));
  EXPECT_EQ(result.status, AssemblyStatus::dropped);
  EXPECT_EQ(result.issue, AssemblyIssue::unmatched_retransmission);
  EXPECT_EQ(assembler.counters().stray, 1u);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
}

TEST(RaLargeMessageAssembler, AnIncompleteSetTimesOutUnderVirtualTime) {
  rt::VirtualTime time;
  const auto packets = split(image_header(77), patterned_payload(4 * kMaxPayloadSize));
  RaLargeMessageAssembler assembler;  // default timeout: 5 s
  feed(assembler, packets[0], time.now());
  time.advance(2s);
  feed(assembler, packets[1], time.now());
  feed(assembler, packets[3], time.now());  // packets[2] never arrives
  EXPECT_EQ(assembler.next_deadline(), time.now() + 5s);

  time.advance(4999ms);
  EXPECT_TRUE(assembler.expire(time.now()).empty());
  // Duplicates are no progress: they do not keep the set alive.
  EXPECT_EQ(feed(assembler, packets[1], time.now()).issue, AssemblyIssue::duplicate);
  time.advance(1ms);
  const auto expired = assembler.expire(time.now());
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_EQ(expired[0].key, (RaLargeMessageAssembler::Key{packets[0].header.source, packets[0].header.destination, 0x4807}));
  EXPECT_EQ(expired[0].reason, AssemblyIssue::timed_out);
  EXPECT_EQ(expired[0].pieces, 3u);
  EXPECT_EQ(expired[0].bytes, 3 * kMaxPayloadSize);
  EXPECT_EQ(assembler.counters().timed_out, 1u);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
  EXPECT_EQ(assembler.buffered_bytes(), 0u);
  EXPECT_FALSE(assembler.next_deadline());

  // The straggler arrives too late: it cannot complete anything.
  const auto late = feed(assembler, packets[2], time.now());
  EXPECT_EQ(late.status, AssemblyStatus::pending);
  EXPECT_EQ(assembler.sets_in_progress(), 1u);
}

TEST(RaLargeMessageAssembler, AStaleSetIsDiscardedWhenItsKeyIsSeenAgain) {
  rt::VirtualTime time;
  const auto payload = patterned_payload(2 * kMaxPayloadSize);
  const auto old_packets = split(image_header(10), payload);
  const auto new_packets = split(image_header(12), payload);
  RaLargeMessageAssembler assembler({.timeout = 1s});
  feed(assembler, old_packets[0], time.now());
  time.advance(1s);
  EXPECT_EQ(feed(assembler, new_packets[0], time.now()).issue, AssemblyIssue::none);  // not "superseded"
  EXPECT_EQ(assembler.counters().timed_out, 1u);
  EXPECT_EQ(feed(assembler, new_packets[1], time.now()).status, AssemblyStatus::complete);
}

TEST(RaLargeMessageAssembler, AnOversizeSetIsDiscardedWithItsRest) {
  const auto packets = split(image_header(0), patterned_payload(4 * kMaxPayloadSize));
  RaLargeMessageAssembler assembler({.max_message_size = 2 * kMaxPayloadSize + 100});
  EXPECT_EQ(feed(assembler, packets[0]).status, AssemblyStatus::pending);
  EXPECT_EQ(feed(assembler, packets[1]).status, AssemblyStatus::pending);
  const auto over = feed(assembler, packets[2]);
  EXPECT_EQ(over.status, AssemblyStatus::dropped);
  EXPECT_EQ(over.issue, AssemblyIssue::too_large);
  EXPECT_EQ(assembler.buffered_bytes(), 0u);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
  EXPECT_EQ(feed(assembler, packets[3]).issue, AssemblyIssue::rest_of_discarded_set);
  EXPECT_EQ(assembler.counters().too_large, 1u);
  EXPECT_EQ(assembler.counters().stray, 1u);

  // The sender's next message, within the limit, goes through.
  const auto payload = patterned_payload(2 * kMaxPayloadSize);
  const auto next = split(image_header(4), payload);
  feed(assembler, next[0]);
  const auto done = feed(assembler, next[1]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, PacketsPerSetAreBounded) {
  const auto packets = split(image_header(0), patterned_payload(5 * kMaxPayloadSize + 40));  // 6 packets
  RaLargeMessageAssembler assembler({.max_pieces_per_set = 3});
  feed(assembler, packets[0]);
  feed(assembler, packets[1]);
  feed(assembler, packets[2]);
  // With the first packet known, number 3 lies beyond what a set may span.
  EXPECT_EQ(feed(assembler, packets[3]).issue, AssemblyIssue::inconsistent);

  // Without it, the fourth packet held outgrows the set.
  RaLargeMessageAssembler headless({.max_pieces_per_set = 3});
  feed(headless, packets[1]);
  feed(headless, packets[2]);
  feed(headless, packets[3]);
  EXPECT_EQ(feed(headless, packets[4]).issue, AssemblyIssue::too_large);
  EXPECT_EQ(feed(headless, packets[5]).issue, AssemblyIssue::rest_of_discarded_set);
  EXPECT_EQ(headless.counters().too_large, 1u);
  EXPECT_EQ(headless.buffered_bytes(), 0u);
}

TEST(RaLargeMessageAssembler, ARetransmissionThatOutgrowsTheLimitDiscardsTheSet) {
  const auto packets = split(image_header(0), patterned_payload(2 * kMaxPayloadSize + 10));
  RaLargeMessageAssembler assembler({.max_message_size = kMaxPayloadSize + 5});
  Packet short_first = packets[0];
  short_first.payload.resize(100);
  short_first.header.data_size = 100;
  feed(assembler, short_first);
  feed(assembler, packets[2]);  // 110 bytes held, the middle one missing
  EXPECT_EQ(feed(assembler, retransmission_of(packets[0])).issue, AssemblyIssue::too_large);  // would be 4090
  EXPECT_EQ(assembler.buffered_bytes(), 0u);
}

TEST(RaLargeMessageAssembler, ConcurrentSetsAreBounded) {
  RaLargeMessageAssembler assembler({.max_sets = 2});
  const auto payload = patterned_payload(2 * kMaxPayloadSize);
  const auto a = split(image_header(0, Address{1, 1, 37, 1}), payload);
  const auto b = split(image_header(0, Address{1, 1, 37, 2}), payload);
  const auto c = split(image_header(0, Address{1, 1, 37, 3}), payload);
  feed(assembler, a[0]);
  feed(assembler, b[0]);
  const auto refused = feed(assembler, c[0]);
  EXPECT_EQ(refused.status, AssemblyStatus::dropped);
  EXPECT_EQ(refused.issue, AssemblyIssue::refused);
  EXPECT_EQ(assembler.counters().refused, 1u);
  // Finishing one makes room.
  EXPECT_EQ(feed(assembler, a[1]).status, AssemblyStatus::complete);
  EXPECT_EQ(feed(assembler, c[0]).status, AssemblyStatus::pending);
  EXPECT_EQ(feed(assembler, c[1]).status, AssemblyStatus::complete);
}

TEST(RaLargeMessageAssembler, CompletedSetsAreRememberedWithinBounds) {
  RaLargeMessageAssembler assembler({.max_sets = 2});
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  std::vector<std::vector<Packet>> sets;
  for (std::uint8_t instance = 1; instance <= 10; ++instance) {
    sets.push_back(split(image_header(0, Address{1, 1, 37, instance}), payload));
    for (const Packet& packet : sets.back()) feed(assembler, packet);
  }
  EXPECT_EQ(assembler.counters().completed, 10u);
  // The most recent sets are remembered: their late copies are duplicates.
  EXPECT_EQ(feed(assembler, sets[9][1]).issue, AssemblyIssue::duplicate);
  // The oldest were forgotten (at most 2 x max_sets entries): a late copy opens a set.
  EXPECT_EQ(feed(assembler, sets[0][1]).status, AssemblyStatus::pending);
  EXPECT_EQ(assembler.sets_in_progress(), 1u);
}

TEST(RaLargeMessageAssembler, StaleSetsMakeRoomForNewOnes) {
  rt::VirtualTime time;
  RaLargeMessageAssembler assembler({.max_sets = 1, .timeout = 5s});
  const auto payload = patterned_payload(2 * kMaxPayloadSize);
  const auto a = split(image_header(0, Address{1, 1, 37, 1}), payload);
  const auto b = split(image_header(0, Address{1, 1, 37, 2}), payload);
  feed(assembler, a[0], time.now());
  EXPECT_EQ(feed(assembler, b[0], time.now()).issue, AssemblyIssue::refused);
  time.advance(5s);
  EXPECT_EQ(feed(assembler, b[0], time.now()).status, AssemblyStatus::pending);
  EXPECT_EQ(assembler.counters().timed_out, 1u);
}

TEST(RaLargeMessageAssembler, InterleavedSetsFromTwoSources) {
  const auto payload_a = patterned_payload(3 * kMaxPayloadSize, 1);
  const auto payload_b = patterned_payload(3 * kMaxPayloadSize - 5, 2);
  // Same command code and the same sequence numbers: only the source tells them apart.
  const auto a = split(image_header(20, Address{1, 1, 37, 1}), payload_a);
  const auto b = split(image_header(20, Address{3, 2, 37, 1}), payload_b);
  RaLargeMessageAssembler assembler;
  feed(assembler, a[0]);
  feed(assembler, b[2]);
  feed(assembler, b[0]);
  feed(assembler, a[2]);
  EXPECT_EQ(assembler.sets_in_progress(), 2u);
  const auto done_b = feed(assembler, b[1]);
  const auto done_a = feed(assembler, a[1]);
  ASSERT_EQ(done_a.status, AssemblyStatus::complete);
  ASSERT_EQ(done_b.status, AssemblyStatus::complete);
  EXPECT_EQ(done_a.message->payload, payload_a);
  EXPECT_EQ(done_b.message->payload, payload_b);
  EXPECT_EQ(done_a.message->header.source, (Address{1, 1, 37, 1}));
  EXPECT_EQ(done_b.message->header.source, (Address{3, 2, 37, 1}));
}

TEST(RaLargeMessageAssembler, InterleavedCommandCodesFromOneSource) {
  const auto image = patterned_payload(2 * kMaxPayloadSize + 1, 3);
  const auto map = patterned_payload(2 * kMaxPayloadSize + 2, 4);
  Header map_header = image_header(50);
  map_header.command_code = 0x4A21;
  const auto image_packets = split(image_header(47), image);  // numbers 47-49, then the map's 50-52
  const auto map_packets = split(map_header, map);
  RaLargeMessageAssembler assembler;
  feed(assembler, image_packets[0]);
  feed(assembler, map_packets[0]);
  feed(assembler, map_packets[1]);
  feed(assembler, image_packets[1]);
  const auto single = feed(assembler, Packet{image_header(60), {}});  // a single packet passes straight through
  EXPECT_EQ(single.status, AssemblyStatus::single);
  const auto done_image = feed(assembler, image_packets[2]);
  const auto done_map = feed(assembler, map_packets[2]);
  ASSERT_EQ(done_image.status, AssemblyStatus::complete);
  ASSERT_EQ(done_map.status, AssemblyStatus::complete);
  EXPECT_EQ(done_image.message->payload, image);
  EXPECT_EQ(done_map.message->payload, map);
  EXPECT_EQ(done_map.message->header.command_code, 0x4A21);
  EXPECT_EQ(assembler.counters().singles, 1u);
}

TEST(RaLargeMessageAssembler, ANewFirstPacketSupersedesAnUnfinishedSet) {
  const auto abandoned = split(image_header(0), patterned_payload(3 * kMaxPayloadSize, 5));
  const auto payload = patterned_payload(2 * kMaxPayloadSize, 6);
  const auto next = split(image_header(3), payload);
  RaLargeMessageAssembler assembler;
  feed(assembler, abandoned[0]);
  feed(assembler, abandoned[1]);
  const auto started = feed(assembler, next[0]);
  EXPECT_EQ(started.status, AssemblyStatus::pending);
  EXPECT_EQ(started.issue, AssemblyIssue::superseded);
  EXPECT_EQ(assembler.counters().superseded, 1u);
  const auto done = feed(assembler, next[1]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, StrayPacketsOutsideTheSetAreDroppedAsInconsistent) {
  const auto payload = patterned_payload(3 * kMaxPayloadSize);
  const auto packets = split(image_header(100), payload);
  RaLargeMessageAssembler assembler;
  Packet stray = packets[1];
  stray.header.sequence = 90;  // before the first packet: cannot belong to this set
  feed(assembler, stray);
  feed(assembler, packets[1]);
  feed(assembler, packets[0]);  // now 90 is known to lie outside: dropped
  EXPECT_EQ(assembler.counters().stray, 1u);
  Packet second_last = packets[2];
  second_last.header.sequence = 101;
  feed(assembler, packets[2]);
  EXPECT_EQ(feed(assembler, second_last).issue, AssemblyIssue::duplicate);  // 101 already held
  assembler = RaLargeMessageAssembler{};
  feed(assembler, packets[0]);
  feed(assembler, packets[2]);
  Packet another_last = packets[2];
  another_last.header.sequence = 103;
  EXPECT_EQ(feed(assembler, another_last).issue, AssemblyIssue::inconsistent);
  Packet beyond_last = packets[1];
  beyond_last.header.sequence = 103;
  EXPECT_EQ(feed(assembler, beyond_last).issue, AssemblyIssue::inconsistent);
  const auto done = feed(assembler, packets[1]);
  ASSERT_EQ(done.status, AssemblyStatus::complete);
  EXPECT_EQ(done.message->payload, payload);
}

TEST(RaLargeMessageAssembler, APacketWhoseSizeDisagreesIsDropped) {
  RaLargeMessageAssembler assembler;
  Header header = image_header(0);
  header.data_flag = DataFlag::first;
  header.data_size = 10;
  const std::vector<std::uint8_t> nine(9);
  const auto result = assembler.feed(header, nine, {});
  EXPECT_EQ(result.status, AssemblyStatus::dropped);
  EXPECT_EQ(result.issue, AssemblyIssue::bad_packet);
  header.data_size = 9;
  header.data_flag = static_cast<DataFlag>(3);
  EXPECT_EQ(assembler.feed(header, nine, {}).issue, AssemblyIssue::bad_packet);
  EXPECT_EQ(assembler.counters().bad_packets, 2u);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
}

TEST(RaLargeMessageAssembler, ShuffledArrivalWithDuplicatesAndRetransmissionsAcrossTheWrap) {
  const auto payload = patterned_payload(20 * kMaxPayloadSize - 7);
  const auto packets = split(image_header(65530), payload);
  ASSERT_EQ(packets.size(), 20u);
  for (std::uint32_t seed = 1; seed <= 50; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(seed);
    std::vector<Packet> arrivals = packets;
    for (int i = 0; i < 10; ++i) arrivals.push_back(packets[rng() % packets.size()]);
    for (int i = 0; i < 5; ++i) arrivals.push_back(retransmission_of(packets[rng() % packets.size()]));
    std::shuffle(arrivals.begin(), arrivals.end(), rng);
    RaLargeMessageAssembler assembler;
    int completions = 0;
    for (const Packet& packet : arrivals) {
      auto result = feed(assembler, packet);
      if (result.status != AssemblyStatus::complete) continue;
      ++completions;
      EXPECT_EQ(result.message->payload, payload);
    }
    EXPECT_EQ(completions, 1);
    // A copy of the first packet after completion opens a set (it may start
    // a new message; later copies join it); it never completes and times out.
    EXPECT_LE(assembler.expire(rt::TimePoint{} + 5s).size(), 1u);
  }
}

TEST(RaLargeMessageAssembler, RandomPacketsNeverBreakTheLimits) {
  const AssemblyLimits options{
      .max_message_size = 20000, .max_pieces_per_set = 16, .max_sets = 4, .timeout = 1s};
  RaLargeMessageAssembler assembler(options);
  std::mt19937 rng(20260101);
  const std::array flags{DataFlag::single, DataFlag::first, DataFlag::middle, DataFlag::middle,
                         DataFlag::retransmitted, DataFlag::last};
  const auto bytes = patterned_payload(kMaxPayloadSize);
  rt::TimePoint now{};
  std::uint64_t singles = 0;
  std::uint64_t completed = 0;
  for (int i = 0; i < 20000; ++i) {
    Header header = image_header(static_cast<std::uint16_t>(65530 + rng() % 16),
                                 Address{1, 1, 37, static_cast<std::uint8_t>(1 + rng() % 6)});
    header.command_code = rng() % 2 ? 0x4807 : 0x4A21;
    header.data_flag = flags[rng() % flags.size()];
    const std::size_t size = rng() % 3 == 0 ? rng() % kMaxPayloadSize : rng() % 64;
    header.data_size = static_cast<std::uint16_t>(size);
    const auto result = assembler.feed(header, std::span(bytes).first(size), now);
    singles += result.status == AssemblyStatus::single;
    if (result.status == AssemblyStatus::complete) {
      ++completed;
      ASSERT_TRUE(result.message);
      EXPECT_LE(result.message->payload.size(), options.max_message_size);
    }
    ASSERT_LE(assembler.sets_in_progress(), options.max_sets);
    ASSERT_LE(assembler.buffered_bytes(), options.max_sets * options.max_message_size);
    ASSERT_LE(assembler.buffered_bytes(), options.max_total_bytes);
    now += std::chrono::milliseconds(rng() % 40);
    if (i % 100 == 0) assembler.expire(now);
  }
  EXPECT_EQ(assembler.counters().singles, singles);
  EXPECT_EQ(assembler.counters().completed, completed);
  EXPECT_GT(completed, 0u);  // the generator does produce whole sets now and then
  assembler.expire(now + 1s);
  EXPECT_EQ(assembler.sets_in_progress(), 0u);
  EXPECT_EQ(assembler.buffered_bytes(), 0u);
}

TEST(RaLargeMessageAssembler, IssuesHaveNames) {
  EXPECT_EQ(to_string(AssemblyIssue::timed_out), "large message incomplete at timeout, discarded");
  EXPECT_EQ(to_string(AssemblyIssue::duplicate), "duplicate piece");
}

}  // namespace
}  // namespace jaus::node
