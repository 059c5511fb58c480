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
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered), time.now());
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
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::undeliverable), rt::TimePoint{});
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
    EXPECT_FALSE(tracker.on_reply(reply, rt::TimePoint{}));
  EXPECT_EQ(tracker.counters().unmatched_replies, 4u);
  Header not_a_reply = sent;
  EXPECT_FALSE(tracker.on_reply(not_a_reply, rt::TimePoint{}));
  EXPECT_EQ(tracker.counters().unmatched_replies, 4u);
  EXPECT_EQ(tracker.pending(), 1u);
  // The right one still settles it, once.
  EXPECT_TRUE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered), rt::TimePoint{}));
  EXPECT_FALSE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered), rt::TimePoint{}));
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
  EXPECT_FALSE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered), time.now()));
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
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered), time.now());
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
  EXPECT_FALSE(tracker.on_reply(from_elsewhere, rt::TimePoint{}));
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered), rt::TimePoint{});
  ASSERT_TRUE(resolution);
  EXPECT_EQ(resolution->key.peer, sent.destination);
}

TEST(AckTracker, OutcomesHaveNames) { EXPECT_EQ(to_string(AckOutcome::refused), "refused (NAK)"); }


// ---- timed by the measured round trip (RetransmitTiming::measured, round_trip.hpp)

const AckPolicy kMeasured = AckPolicy::measured(3s, 10, 1s);
const Address kDriverNode{1, 1, 0, 0};  // whose round trip the driver's answers measure

Header wrench_effort_to(const Address& to, std::uint16_t sequence) {
  Header header = wrench_effort(sequence);
  header.destination = to;
  return header;
}

// Sends one message at the current time and answers it `after` later, polling
// (and counting retransmissions) every millisecond meanwhile.
std::uint32_t answered_after(AckTracker& tracker, rt::VirtualTime& time, std::uint16_t sequence, rt::Duration after,
                             AckPolicy policy = kMeasured) {
  const Header sent = wrench_effort(sequence);
  tracker.track(sent, {}, time.now(), policy);
  for (auto waited = 0ms; waited < after; waited += 1ms) {
    time.advance(1ms);
    (void)tracker.poll(time.now());
  }
  const auto resolution = tracker.on_reply(reply_from_driver(sent, Delivery::delivered), time.now());
  EXPECT_TRUE(resolution);
  return resolution ? resolution->transmissions : 0;
}

TEST(AckTrackerMeasured, TheFirstWaitIsTheInitialTimeoutThenTheMeasuredOne) {
  rt::VirtualTime time;
  AckTracker tracker;
  EXPECT_EQ(tracker.round_trip(kDriverNode), nullptr);
  tracker.track(wrench_effort(1), {}, time.now(), kMeasured);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 100ms);  // RoundTripOptions::initial_timeout
  time.advance(30ms);
  ASSERT_TRUE(tracker.on_reply(reply_from_driver(wrench_effort(1), Delivery::delivered), time.now()));
  const RoundTripEstimator* measured = tracker.round_trip(kDriverNode);
  ASSERT_NE(measured, nullptr);
  EXPECT_EQ(measured->smoothed(), 30ms);
  EXPECT_EQ(measured->samples(), 1u);
  // 30 ms + 4 x 15 ms of variation.
  tracker.track(wrench_effort(2), {}, time.now(), kMeasured);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 90ms);
}

TEST(AckTrackerMeasured, ARadiosRoundTripIsWaitedForInsteadOfRetransmittedInto) {
  rt::VirtualTime time;
  AckTracker tracker;
  // 250 ms each way and back: the first messages go out again before their
  // answer returns, so they measure nothing (Karn's rule); their timeout
  // stays doubled until one is answered having gone out once.
  EXPECT_EQ(answered_after(tracker, time, 1, 250ms), 2u);  // again at 100 ms
  EXPECT_EQ(answered_after(tracker, time, 2, 250ms), 2u);  // again at 200 ms
  EXPECT_EQ(tracker.round_trip(kDriverNode)->samples(), 0u);
  EXPECT_EQ(answered_after(tracker, time, 3, 250ms), 1u);  // waited 400 ms: measured
  EXPECT_EQ(tracker.round_trip(kDriverNode)->smoothed(), 250ms);
  std::uint32_t sent = 0;
  for (std::uint16_t sequence = 4; sequence < 24; ++sequence) sent += answered_after(tracker, time, sequence, 250ms);
  EXPECT_EQ(sent, 20u) << "every later command went out once";
  EXPECT_EQ(tracker.counters().retransmissions, 2u);
  const rt::Duration timeout = tracker.round_trip(kDriverNode)->timeout();
  EXPECT_GT(timeout, 250ms);
  EXPECT_LT(timeout, 300ms) << "the variation decays as the round trip holds";
}

TEST(AckTrackerMeasured, EachWaitDoublesUpToTheLongestAndTheDeadlineGivesUp) {
  rt::VirtualTime time;
  AckTracker tracker;
  tracker.track(wrench_effort(1), {}, time.now(), kMeasured);
  std::vector<rt::Duration> sent_at{0ms};
  std::optional<BasicAckResolution<AckKey>> given_up;
  rt::Duration given_up_at{};
  while (!given_up) {
    const auto due = tracker.next_deadline();
    ASSERT_TRUE(due);
    time.advance(*due - time.now());
    auto poll = tracker.poll(time.now());
    for (std::size_t i = 0; i < poll.retransmit.size(); ++i) sent_at.push_back(time.now() - rt::TimePoint{});
    if (!poll.failed.empty()) {
      given_up = poll.failed[0];
      given_up_at = time.now() - rt::TimePoint{};
    }
  }
  // 100, 200, 400, 800 ms, then 1 s (the longest wait) apart; given up 3 s after the first.
  EXPECT_EQ(sent_at, (std::vector<rt::Duration>{0ms, 100ms, 300ms, 700ms, 1500ms, 2500ms}));
  EXPECT_EQ(given_up_at, 3s);
  EXPECT_EQ(given_up->outcome, AckOutcome::exhausted);
  EXPECT_EQ(given_up->transmissions, 6u);
  // The peer's timeout stays doubled (bounded) until a message to it is answered having gone out once.
  EXPECT_EQ(tracker.round_trip(kDriverNode)->timeout(), 2s);
}

TEST(AckTrackerMeasured, WithoutBackOffEveryWaitIsTheMeasuredTimeout) {
  rt::VirtualTime time;
  AckTracker tracker;
  answered_after(tracker, time, 1, 5ms);  // 5 ms + 4 x 2.5 ms = 15 ms: the least timeout, 50 ms
  const AckPolicy stop = AckPolicy::measured(10s, 40, 500ms, /*doubling=*/false);
  tracker.track(wrench_effort(2), {}, time.now(), stop);
  const rt::TimePoint start = time.now();
  std::vector<rt::Duration> sent_at;
  for (int i = 0; i < 4; ++i) {
    time.advance(*tracker.next_deadline() - time.now());
    if (!tracker.poll(time.now()).retransmit.empty()) sent_at.push_back(time.now() - start);
  }
  EXPECT_EQ(sent_at, (std::vector<rt::Duration>{50ms, 100ms, 150ms, 200ms}));
}

TEST(AckTrackerMeasured, OnePeersRoundTripTimesNoOther) {
  rt::VirtualTime time;
  AckTracker tracker;
  answered_after(tracker, time, 1, 300ms);  // once again at 100 ms: measures nothing...
  answered_after(tracker, time, 2, 150ms);  // ...this one does (waited 200 ms)
  ASSERT_EQ(tracker.round_trip(kDriverNode)->smoothed(), 150ms);
  const Address elsewhere{1, 2, 33, 1};
  tracker.track(wrench_effort_to(elsewhere, 3), {}, time.now(), kMeasured);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 100ms);  // still the initial timeout
  EXPECT_EQ(tracker.round_trip(Address{1, 2, 0, 0}), nullptr);
  // Another component of the measured node shares its round trip.
  AckTracker fresh;
  rt::VirtualTime t2;
  answered_after(fresh, t2, 1, 40ms);
  fresh.track(wrench_effort_to(Address{1, 1, 41, 1}, 2), {}, t2.now(), kMeasured);
  EXPECT_EQ(fresh.next_deadline(), t2.now() + 120ms);  // 40 + 4 x 20 ms
}

TEST(AckTrackerMeasured, MessagesTimingOutTogetherDoubleThePeersTimeoutOnce) {
  rt::VirtualTime time;
  AckTracker tracker;
  for (std::uint16_t sequence = 1; sequence <= 3; ++sequence)
    tracker.track(wrench_effort(sequence), {}, time.now(), kMeasured);
  time.advance(100ms);
  EXPECT_EQ(tracker.poll(time.now()).retransmit.size(), 3u);
  EXPECT_EQ(tracker.round_trip(kDriverNode)->timeout(), 200ms);
}

TEST(AckTrackerMeasured, ABroadcastMeasuresNobody) {
  AckTracker tracker;
  Header sent = wrench_effort(5);
  sent.destination = Address{1, 255, 33, 255};
  tracker.track(sent, {}, rt::TimePoint{}, kMeasured);
  ASSERT_TRUE(tracker.on_reply(reply_from_driver(sent, Delivery::delivered), rt::TimePoint{} + 20ms));
  EXPECT_EQ(tracker.round_trip(kDriverNode), nullptr);
}

TEST(AckTrackerMeasured, TransmissionsOfAPendingMessageAreKnownUntilItIsForgotten) {
  AckTracker tracker;
  const Header sent = wrench_effort(1);
  tracker.track(sent, {}, rt::TimePoint{}, kMeasured);
  (void)tracker.poll(rt::TimePoint{} + 100ms);
  EXPECT_EQ(tracker.transmissions(ack_key_of_sent(sent)), 2u);
  EXPECT_EQ(tracker.forget(ack_key_of_sent(sent)), 2u);
  EXPECT_EQ(tracker.transmissions(ack_key_of_sent(sent)), std::nullopt);
  EXPECT_EQ(tracker.next_deadline(), std::nullopt);
}

TEST(AckTrackerMeasured, ToAPeerNotMeasuredYetAPolicyMayWaitLessThanTheInitialTimeout) {
  rt::VirtualTime time;
  AckTracker tracker;
  const AckPolicy stop = AckPolicy::measured(10s, 200, 500ms, /*doubling=*/false, /*first_unmeasured_wait=*/50ms);
  tracker.track(wrench_effort(1), {}, time.now(), stop);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 50ms);
  // Once measured, the measurement rules: 120 ms (40 + 4 x 20).
  tracker.forget(ack_key_of_sent(wrench_effort(1)));
  answered_after(tracker, time, 2, 40ms);
  tracker.track(wrench_effort(3), {}, time.now(), stop);
  EXPECT_EQ(tracker.next_deadline(), time.now() + 120ms);
}

TEST(AckTrackerMeasured, StopsToAPeerNotMeasuredYetComeToMeasureItsRoundTrip) {
  rt::VirtualTime time;
  AckTracker tracker;
  // A stop's pace never doubles within one message, and nothing is measured
  // from a message sent again: over a 300 ms round trip each stop would go
  // every 50 ms for ever. Instead each stop starts from twice the longest
  // wait that expired, until one is answered having gone out once.
  const AckPolicy stop = AckPolicy::measured(10s, 200, 500ms, /*doubling=*/false, /*first_unmeasured_wait=*/50ms);
  std::vector<std::uint32_t> copies;
  for (std::uint16_t sequence = 1; sequence <= 5; ++sequence)
    copies.push_back(answered_after(tracker, time, sequence, 300ms, stop));
  EXPECT_EQ(copies, (std::vector<std::uint32_t>{7, 4, 2, 1, 1}));  // waits of 50, 100, 200, 400, then the measured
  ASSERT_NE(tracker.round_trip(kDriverNode), nullptr);
  EXPECT_EQ(tracker.round_trip(kDriverNode)->smoothed(), 300ms);
}

}  // namespace
}  // namespace jaus::node
