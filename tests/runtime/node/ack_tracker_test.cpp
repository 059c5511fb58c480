#include "jaus/node/ack_tracker.hpp"

#include <gtest/gtest.h>

#include "jaus/node/ack_reply.hpp"
#include "jaus/base/virtual_time.hpp"

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

const Address kOcu{2, 1, 40, 1};
const Address kDriver{1, 1, 33, 1};

Header wrench_effort(std::uint16_t sequence) {
  Header header;
  header.command_code = 0x0405;  // Set Wrench Effort
  header.ack_nak = AckNak::ack_requested;
  header.source = kOcu;
  header.destination = kDriver;
  header.sequence = sequence;
  return header;
}

Header reply_from_driver(const Header& sent, Delivery delivery) {
  auto reply = ack_reply_for(sent, kDriver, delivery);
  EXPECT_TRUE(reply);
  return *reply;
}

TEST(AckReply, AcknowledgesWithTheSameCodeAndSequenceBackToTheSender) {
  Header received = wrench_effort(42);
  received.priority = 12;
  received.data_size = 20;
  const auto ack = ack_reply_for(received, kDriver, Delivery::delivered);
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->ack_nak, AckNak::ack);
  EXPECT_EQ(ack->command_code, 0x0405);
  EXPECT_EQ(ack->sequence, 42);
  EXPECT_EQ(ack->source, kDriver);
  EXPECT_EQ(ack->destination, kOcu);
  EXPECT_EQ(ack->data_size, 0);
  EXPECT_EQ(ack->data_flag, DataFlag::single);
  EXPECT_EQ(ack->priority, 12);
  EXPECT_EQ(ack->version, kVersionRa32);
  EXPECT_TRUE(encode_header(*ack));
}

TEST(AckReply, NaksWhatCannotBeDeliveredAndIgnoresWhatAskedNothing) {
  Header broadcast = wrench_effort(7);
  broadcast.destination = Address{1, 255, 33, 255};
  const auto nak = ack_reply_for(broadcast, kDriver, Delivery::undeliverable);
  ASSERT_TRUE(nak);
  EXPECT_EQ(nak->ack_nak, AckNak::nak);
  EXPECT_EQ(nak->source, kDriver);  // our real address, not the broadcast one
  Header plain = wrench_effort(7);
  plain.ack_nak = AckNak::none;
  EXPECT_FALSE(ack_reply_for(plain, kDriver, Delivery::delivered));
  plain.ack_nak = AckNak::ack;
  EXPECT_FALSE(ack_reply_for(plain, kDriver, Delivery::delivered));  // never acknowledge an ACK
}

TEST(AckTracker, AMatchingAckSettlesTheMessage) {
  rt::VirtualTime time;
  AckTracker tracker;
  const Header sent = wrench_effort(3);
  const std::vector<std::uint8_t> payload{1, 2, 3};
  ASSERT_EQ(tracker.track(sent, payload, time.now()), TrackResult::tracked);
  EXPECT_TRUE(tracker.is_pending(ack_key_of_sent(sent)));
  time.advance(300ms);
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered));
  ASSERT_TRUE(resolution);
  EXPECT_EQ(resolution->outcome, AckOutcome::acknowledged);
  EXPECT_EQ(resolution->key, ack_key_of_sent(sent));
  EXPECT_EQ(resolution->transmissions, 1u);
  EXPECT_EQ(tracker.pending(), 0u);
  EXPECT_FALSE(tracker.next_deadline());
  time.advance(10s);
  const auto due = tracker.poll(time.now());
  EXPECT_TRUE(due.retransmit.empty());
  EXPECT_TRUE(due.failed.empty());
  EXPECT_EQ(tracker.counters().acknowledged, 1u);
}

TEST(AckTracker, ANakRefusesTheMessage) {
  AckTracker tracker;
  const Header sent = wrench_effort(3);
  tracker.track(sent, {}, {});
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::undeliverable));
  ASSERT_TRUE(resolution);
  EXPECT_EQ(resolution->outcome, AckOutcome::refused);
  EXPECT_EQ(tracker.counters().refused, 1u);
  EXPECT_EQ(tracker.pending(), 0u);
}

TEST(AckTracker, RepliesThatDoNotMatchAreCountedAndIgnored) {
  AckTracker tracker;
  const Header sent = wrench_effort(3);
  tracker.track(sent, {}, {});
  Header wrong_sequence = reply_from_driver(wrench_effort(4), Delivery::delivered);
  Header wrong_code = reply_from_driver(sent, Delivery::delivered);
  wrong_code.command_code = 0x0406;
  Header wrong_peer = reply_from_driver(sent, Delivery::delivered);
  wrong_peer.source = Address{1, 1, 33, 2};
  Header wrong_local = reply_from_driver(sent, Delivery::delivered);
  wrong_local.destination = Address{2, 1, 40, 2};
  for (const Header& reply : {wrong_sequence, wrong_code, wrong_peer, wrong_local})
    EXPECT_FALSE(tracker.on_reply(reply));
  EXPECT_EQ(tracker.counters().unmatched_replies, 4u);
  Header not_a_reply = sent;
  EXPECT_FALSE(tracker.on_reply(not_a_reply));
  EXPECT_EQ(tracker.counters().unmatched_replies, 4u);
  EXPECT_EQ(tracker.pending(), 1u);
  // The right one still settles it, once.
  EXPECT_TRUE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered)));
  EXPECT_FALSE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered)));
  EXPECT_EQ(tracker.counters().unmatched_replies, 5u);
}

TEST(AckTracker, RetransmitsEverySecondThenGivesUpAfterThreeTransmissions) {
  rt::VirtualTime time;
  AckTracker tracker;  // defaults: 3 transmissions, 1 s apart
  const Header sent = wrench_effort(9);
  const std::vector<std::uint8_t> payload{0xAA, 0xBB};
  tracker.track(sent, payload, time.now());
  EXPECT_EQ(tracker.next_deadline(), time.now() + 1s);

  time.advance(999ms);
  EXPECT_TRUE(tracker.poll(time.now()).retransmit.empty());

  time.advance(1ms);  // t = 1 s
  auto due = tracker.poll(time.now());
  ASSERT_EQ(due.retransmit.size(), 1u);
  EXPECT_EQ(due.retransmit[0].header, sent);  // the very same packet
  EXPECT_EQ(due.retransmit[0].payload, payload);
  EXPECT_EQ(due.retransmit[0].transmission, 2u);
  EXPECT_TRUE(tracker.poll(time.now()).retransmit.empty());  // not twice for one deadline

  time.advance(1s);  // t = 2 s
  due = tracker.poll(time.now());
  ASSERT_EQ(due.retransmit.size(), 1u);
  EXPECT_EQ(due.retransmit[0].transmission, 3u);
  EXPECT_TRUE(due.failed.empty());

  time.advance(1s);  // t = 3 s: the third transmission went unanswered too
  due = tracker.poll(time.now());
  EXPECT_TRUE(due.retransmit.empty());
  ASSERT_EQ(due.failed.size(), 1u);
  EXPECT_EQ(due.failed[0].outcome, AckOutcome::exhausted);
  EXPECT_EQ(due.failed[0].transmissions, 3u);
  EXPECT_EQ(due.failed[0].key, ack_key_of_sent(sent));
  EXPECT_EQ(tracker.pending(), 0u);
  EXPECT_EQ(tracker.counters().retransmissions, 2u);
  EXPECT_EQ(tracker.counters().exhausted, 1u);
  // An ACK after giving up settles nothing.
  EXPECT_FALSE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered)));
}

TEST(AckTracker, AnAckAfterARetransmissionReportsTheTransmissions) {
  rt::VirtualTime time;
  AckTracker tracker({.retransmit_after = 200ms, .max_transmissions = 5});
  const Header sent = wrench_effort(1);
  tracker.track(sent, {}, time.now());
  time.advance(200ms);
  EXPECT_EQ(tracker.poll(time.now()).retransmit.size(), 1u);
  time.advance(200ms);
  EXPECT_EQ(tracker.poll(time.now()).retransmit.size(), 1u);
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered));
  ASSERT_TRUE(resolution);
  EXPECT_EQ(resolution->transmissions, 3u);
}

TEST(AckTracker, ALatePollDoesNotBurst) {
  AckTracker tracker;
  tracker.track(wrench_effort(1), {}, rt::TimePoint{});
  const rt::TimePoint late = rt::TimePoint{} + 10s;
  EXPECT_EQ(tracker.poll(late).retransmit.size(), 1u);  // one retransmission, not nine
  EXPECT_EQ(tracker.next_deadline(), late + 1s);
}

TEST(AckTracker, SchedulesSeveralMessagesIndependently) {
  rt::VirtualTime time;
  AckTracker tracker({.retransmit_after = 1s, .max_transmissions = 2});
  tracker.track(wrench_effort(1), {}, time.now());
  time.advance(500ms);
  tracker.track(wrench_effort(2), {}, time.now());
  time.advance(500ms);  // t = 1.0: only the first is due
  auto due = tracker.poll(time.now());
  ASSERT_EQ(due.retransmit.size(), 1u);
  EXPECT_EQ(due.retransmit[0].header.sequence, 1);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 500ms);
  time.advance(500ms);  // t = 1.5
  due = tracker.poll(time.now());
  ASSERT_EQ(due.retransmit.size(), 1u);
  EXPECT_EQ(due.retransmit[0].header.sequence, 2);
  time.advance(500ms);  // t = 2.0: the first is exhausted
  due = tracker.poll(time.now());
  ASSERT_EQ(due.failed.size(), 1u);
  EXPECT_EQ(due.failed[0].key.sequence, 1);
  EXPECT_EQ(tracker.pending(), 1u);
}

TEST(AckTracker, AMessageMayCarryItsOwnPolicy) {
  rt::VirtualTime time;
  AckTracker tracker;  // the node-wide default stays 3 transmissions, 1 s apart
  tracker.track(wrench_effort(1), {}, time.now(), AckPolicy{50ms, 4});
  tracker.track(wrench_effort(2), {}, time.now());
  EXPECT_EQ(tracker.next_deadline(), time.now() + 50ms);
  std::vector<std::uint32_t> fast_transmissions;
  for (int step = 1; step <= 4; ++step) {
    time.advance(50ms);
    const auto due = tracker.poll(time.now());
    for (const auto& r : due.retransmit) fast_transmissions.push_back(r.transmission);
    if (step < 4) {
      EXPECT_TRUE(due.failed.empty());
    } else {
      ASSERT_EQ(due.failed.size(), 1u);  // 50 ms after the fourth transmission
      EXPECT_EQ(due.failed[0].key.sequence, 1);
      EXPECT_EQ(due.failed[0].transmissions, 4u);
    }
  }
  EXPECT_EQ(fast_transmissions, (std::vector<std::uint32_t>{2, 3, 4}));
  EXPECT_EQ(tracker.next_deadline(), rt::TimePoint{} + 1s);  // the default one, untouched
  EXPECT_EQ(tracker.pending(), 1u);
}

TEST(AckTracker, APolicyOfZeroTransmissionsMeansOne) {
  AckTracker tracker;
  tracker.track(wrench_effort(1), {}, rt::TimePoint{}, AckPolicy{50ms, 0});
  const auto due = tracker.poll(rt::TimePoint{} + 50ms);
  EXPECT_TRUE(due.retransmit.empty());
  ASSERT_EQ(due.failed.size(), 1u);
  EXPECT_EQ(due.failed[0].transmissions, 1u);
}

TEST(AckTracker, OnlyAckRequestsAreTrackedAndOnlyAsManyAsAllowed) {
  AckTracker tracker({.max_pending = 2});
  Header plain = wrench_effort(1);
  plain.ack_nak = AckNak::none;
  EXPECT_EQ(tracker.track(plain, {}, {}), TrackResult::not_ack_requested);
  EXPECT_EQ(tracker.track(wrench_effort(1), {}, {}), TrackResult::tracked);
  EXPECT_EQ(tracker.track(wrench_effort(1), {}, {}), TrackResult::already_tracked);
  EXPECT_EQ(tracker.track(wrench_effort(2), {}, {}), TrackResult::tracked);
  EXPECT_EQ(tracker.track(wrench_effort(3), {}, {}), TrackResult::full);
  EXPECT_EQ(tracker.pending(), 2u);
  EXPECT_EQ(tracker.counters().rejected, 2u);
}

TEST(AckTracker, ABroadcastRequestIsSettledByTheFirstAnswer) {
  AckTracker tracker;
  Header sent = wrench_effort(5);
  sent.destination = Address{1, 255, 33, 255};
  tracker.track(sent, {}, {});
  Header from_elsewhere = reply_from_driver(sent, Delivery::delivered);
  from_elsewhere.source = Address{9, 1, 33, 1};  // another subsystem: not an addressee
  EXPECT_FALSE(tracker.on_reply(from_elsewhere));
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered));
  ASSERT_TRUE(resolution);
  EXPECT_EQ(resolution->key.peer, sent.destination);
}

TEST(AckTracker, OutcomesHaveNames) { EXPECT_EQ(to_string(AckOutcome::refused), "refused (NAK)"); }

}  // namespace
}  // namespace jaus::node
