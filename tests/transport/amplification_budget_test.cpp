// Issue 43: an endpoint not yet verified is sent what it sent plus an
// allowance (a token bucket per endpoint, one for all of them), never held
// hostage to a challenge it may not answer; a command acts only if its reply
// can be sent. The guard alone, under virtual time (docs/safety.md,
// "Hostile network").
#include <gtest/gtest.h>

#include <vector>

#include "jaus/transport/amplification_guard.hpp"

namespace jaus::transport::budget_test {  // its own names in the suite's unity build
namespace {

using namespace std::chrono_literals;
using Verdict = AmplificationGuard::Verdict;

const Address kOcu{2, 1, 40, 1};

// A header-only message `code` from `source` (what received() reads).
Header header_of(std::uint16_t code, const Address& source = kOcu, AckNak ack_nak = AckNak::none,
                 std::uint16_t sequence = 0) {
  Header h;
  h.command_code = code;
  h.source = source;
  h.destination = Address{1, 1, 1, 1};
  h.ack_nak = ack_nak;
  h.sequence = sequence;
  return h;
}

// A reply of `size` bytes, header included (a single message, not part of a large data set).
std::vector<std::uint8_t> reply(std::size_t size) { return std::vector<std::uint8_t>(size, 0); }

// The size with OPC framing (8-byte prefix) of a message of `size` bytes.
constexpr std::size_t opc(std::size_t size) { return 8 + size; }

class AmplificationBudget : public ::testing::Test {
 protected:
  AmplificationGuard guard{AmplificationGuardOptions{}, {5, 6}};
  rt::TimePoint now{};
};

// An OCU that never answers a challenge (OpenJAUS, most OCUs written from
// the spec) polls the node's queries a few times a second and drives at
// 10 Hz: for ten minutes of virtual time every reply goes at once, every
// Set Wrench Effort is admitted, nothing is held, dropped or refused.
TEST_F(AmplificationBudget, ANeverAckingPeerPollingQueriesIsAnsweredEveryTimeForMinutes) {
  const Ipv4Endpoint ocu{0x7F000002, 40000};
  guard.track(ocu);
  // Query (bytes with OPC framing) -> reply, the default jausd's sizes or larger:
  // Component Status, Identification, Configuration, Services, Global Pose.
  const std::vector<std::pair<std::size_t, std::size_t>> polls = {
      {opc(16), 16 + 6}, {opc(17), 16 + 40}, {opc(16), 16 + 120}, {opc(16), 16 + 600}, {opc(18), 16 + 50}};
  std::size_t replies = 0, drives = 0;
  for (int tick = 0; tick < 10 * 60 * 20; ++tick) {  // 50 ms ticks
    now += 50ms;
    (void)guard.expire(now);
    if (tick % 2 == 0) {  // Set Wrench Effort, 10 Hz
      guard.received(ocu, opc(16 + 13), kOcu, header_of(0x0405));
      ASSERT_TRUE(guard.admit_command(ocu, Framing::opc, now)) << "tick " << tick;
      ++drives;
    }
    if (tick % 5 == 0) {  // a query every 250 ms: 4 a second, in turn
      const auto& [query, answer] = polls[static_cast<std::size_t>(tick / 5) % polls.size()];
      guard.received(ocu, query, kOcu, header_of(0x2002));
      ASSERT_EQ(guard.offer(ocu, Framing::opc, reply(answer), now), Verdict::send) << "tick " << tick;
      ++replies;
    }
  }
  EXPECT_EQ(replies, 2400u);
  EXPECT_EQ(drives, 6000u);
  const auto& c = guard.counters();
  EXPECT_EQ(c.replies_held, 0u);
  EXPECT_EQ(c.replies_dropped_unverified, 0u);
  EXPECT_EQ(c.commands_refused, 0u);
  EXPECT_TRUE(guard.unverified(ocu));  // never verified, answered all the same
}

// 1000 forged sources, each sending 10 small queries a second for 10 s and
// each query answered with a 1 KiB report: what leaves toward the victims is
// at most the global burst plus the global rate, whatever their number.
TEST_F(AmplificationBudget, ASpoofedFloodFromAThousandSourcesGetsAtMostTheGlobalBudget) {
  AmplificationGuardOptions options;
  AmplificationGuard flooded(options, {7, 8});
  std::vector<Ipv4Endpoint> sources;
  for (std::uint32_t i = 0; i < 1000; ++i) sources.push_back(Ipv4Endpoint{0x0A000000 + i, 3794});
  for (const auto& s : sources) flooded.track(s);
  std::size_t sent = 0, offered = 0;
  const rt::TimePoint start = now;
  for (int tick = 0; tick < 100; ++tick) {  // 100 ms ticks, 10 s
    now += 100ms;
    (void)flooded.expire(now);
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const Address forged{static_cast<std::uint8_t>(1 + i % 200), static_cast<std::uint8_t>(1 + i / 200), 40, 1};
      flooded.received(sources[i], opc(17), forged, header_of(0x2B00, forged));
      ++offered;
      if (flooded.offer(sources[i], Framing::opc, reply(1024), now) == Verdict::send) sent += opc(1024);
      // The link challenges after a reply is held or dropped: counted too.
      if (const auto challenge = flooded.challenge(sources[i], Framing::opc, 1, 1, now)) sent += opc(kHeaderSize);
    }
  }
  const double seconds = std::chrono::duration<double>(now - start).count();
  const double ceiling = static_cast<double>(options.unverified_total_burst_bytes) +
                         seconds * static_cast<double>(options.unverified_total_bytes_per_second);
  const auto& c = flooded.counters();
  EXPECT_EQ(c.bytes_sent_unverified, sent);
  EXPECT_LE(static_cast<double>(c.bytes_sent_unverified), ceiling);
  // Most of it went out: the limit is the global rate, not a stall.
  EXPECT_GE(static_cast<double>(c.bytes_sent_unverified), 0.9 * seconds * options.unverified_total_bytes_per_second);
  EXPECT_EQ(c.bytes_received_unverified, offered * opc(17));
  EXPECT_LT(c.bytes_sent_unverified, c.bytes_received_unverified);  // no amplification at all, in sum
  EXPECT_LE(flooded.held_bytes(), options.max_held_bytes_total);
}

// A Request Component Control whose Confirm Control could not be sent is
// refused at entry; once admitted, its reply's bytes are set aside, so the
// Confirm goes even if others spend the global budget in between.
TEST_F(AmplificationBudget, ARequestControlWhoseConfirmCannotBeSentIsNotGranted) {
  AmplificationGuardOptions options;
  options.unverified_total_burst_bytes = 2048;
  options.unverified_total_bytes_per_second = 1024;
  AmplificationGuard small(options, {9, 10});
  const Ipv4Endpoint ocu{0x7F000002, 40000}, flooder{0x7F000003, 50000};
  small.track(ocu);
  small.track(flooder);
  // Another endpoint spends the global budget.
  small.received(flooder, opc(17), Address{3, 1, 40, 1}, header_of(0x2B00, Address{3, 1, 40, 1}));
  EXPECT_EQ(small.offer(flooder, Framing::opc, reply(2030), now), Verdict::send);  // 10 bytes left
  // A stop acts whatever the budget (the link delivers it): its ACK's bytes are not there, nothing is refused.
  small.received(ocu, opc(16 + 2), kOcu, header_of(0x0006));  // Set Emergency
  EXPECT_FALSE(small.reserve_reply(ocu, now));
  EXPECT_EQ(small.counters().commands_refused, 0u);
  small.received(ocu, opc(16 + 2), kOcu, header_of(0x000D));  // Request Component Control
  EXPECT_FALSE(small.admit_command(ocu, Framing::opc, now));
  EXPECT_EQ(small.counters().commands_refused, 1u);
  // Refused: a challenge is due (an OCU that answers it gets its next command through), when the budget has room.
  EXPECT_FALSE(small.challenge(ocu, Framing::opc, 1, 1, now));  // none now: the global bucket is empty
  // Half a second later the global bucket has room again (522 bytes): the challenge goes, the next Request
  // Control is admitted and its reply's bytes set aside.
  now += 500ms;
  ASSERT_TRUE(small.challenge(ocu, Framing::opc, 1, 1, now));  // 24 bytes of the 522
  small.received(ocu, opc(16 + 2), kOcu, header_of(0x000D));
  ASSERT_TRUE(small.admit_command(ocu, Framing::opc, now));  // 64 more
  EXPECT_EQ(small.offer(flooder, Framing::opc, reply(426), now), Verdict::send);  // spends the rest...
  EXPECT_EQ(small.offer(flooder, Framing::opc, reply(100), now), Verdict::held);  // ...of the global bucket
  // ...yet the Confirm Control (header and response code) and its ACK go: they were set aside.
  EXPECT_EQ(small.offer(ocu, Framing::opc, reply(16 + 1), now), Verdict::send);
  EXPECT_EQ(small.offer(ocu, Framing::opc, reply(16), now), Verdict::send);
  EXPECT_EQ(small.offer(ocu, Framing::opc, reply(16), now), Verdict::held);  // and no more
  EXPECT_EQ(small.counters().commands_refused, 1u);
}

// Answering the challenge lifts every limit: what was held goes, and from
// then on replies of any size go at once and every command is admitted.
TEST_F(AmplificationBudget, AnsweringTheChallengeLiftsTheLimits) {
  const Ipv4Endpoint ocu{0x7F000002, 40000};
  guard.track(ocu);
  guard.received(ocu, opc(17), kOcu, header_of(0x2800));  // Query Image
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 30000), now), Verdict::held);  // beyond 4 KiB and its bytes
  // An ACK within the budget is never withheld behind a held reply.
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16), now), Verdict::send);
  const auto challenge = guard.challenge(ocu, Framing::opc, 1, 1, now);
  ASSERT_TRUE(challenge);
  EXPECT_EQ(challenge->command_code, kChallengeCode);
  EXPECT_EQ(challenge->ack_nak, AckNak::ack_requested);
  EXPECT_FALSE(guard.challenge(ocu, Framing::opc, 1, 1, now));  // one at a time
  EXPECT_TRUE(guard.received(ocu, opc(16), kOcu, header_of(kChallengeCode, kOcu, AckNak::ack, challenge->sequence)));
  EXPECT_FALSE(guard.unverified(ocu));
  const auto released = guard.release(ocu);
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].packet.size(), 16u + 30000u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 60000), now), Verdict::send);
  EXPECT_TRUE(guard.admit_command(ocu, Framing::opc, now));
  EXPECT_EQ(guard.counters().endpoints_verified, 1u);
}

// A held reply whose challenge goes unanswered expires (counted, reported
// once per endpoint); that endpoint's replies beyond the budget are then
// dropped at once, one streak until a reply goes again; a challenge is
// still sent now and then, and answering it still lifts the limits.
TEST_F(AmplificationBudget, AHeldReplyExpiresOnceThenRepliesBeyondTheBudgetAreDroppedInStreaks) {
  const Ipv4Endpoint ocu{0x7F000002, 40000};
  guard.track(ocu);
  guard.received(ocu, opc(17), kOcu, header_of(0x2800));
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 8000), now), Verdict::held);
  ASSERT_TRUE(guard.challenge(ocu, Framing::opc, 1, 1, now));
  EXPECT_TRUE(guard.expire(now + 1s).empty());
  const auto expired = guard.expire(now + 2s);
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_EQ(expired[0].endpoint, ocu);
  EXPECT_EQ(expired[0].replies, 1u);
  EXPECT_EQ(guard.counters().held_replies_expired, 1u);
  now += 3s;
  guard.received(ocu, opc(17), kOcu, header_of(0x2800));
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 8000), now), Verdict::dropped);
  EXPECT_TRUE(guard.last_drop_began_streak());
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 8000), now), Verdict::dropped);
  EXPECT_FALSE(guard.last_drop_began_streak());
  const auto again = guard.challenge(ocu, Framing::opc, 1, 1, now);  // due: a reply was dropped
  ASSERT_TRUE(again);
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(60), now), Verdict::send);  // ends the streak
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 8000), now), Verdict::dropped);
  EXPECT_TRUE(guard.last_drop_began_streak());
  const auto& c = guard.counters();
  EXPECT_EQ(c.drop_streaks, 2u);
  EXPECT_EQ(c.replies_dropped_unverified, 1u + 3u);
  EXPECT_TRUE(guard.received(ocu, opc(16), kOcu, header_of(kChallengeCode, kOcu, AckNak::ack, again->sequence)));
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16 + 8000), now), Verdict::send);
}

// A large data set's later parts stay in order behind a held part; a
// single message within the budget does not wait for them.
TEST_F(AmplificationBudget, LaterPartsOfALargeDataSetStayBehindAHeldPart) {
  const Ipv4Endpoint ocu{0x7F000002, 40000};
  guard.track(ocu);
  guard.received(ocu, opc(17), kOcu, header_of(0x2800));
  auto part = [](DataFlag flag, std::size_t size) {
    std::vector<std::uint8_t> packet(size, 0);
    Header h = header_of(0x4800, Address{1, 1, 37, 1});
    h.data_flag = flag;
    h.data_size = static_cast<std::uint16_t>(size - kHeaderSize);
    encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(packet.data(), kHeaderSize));
    return packet;
  };
  EXPECT_EQ(guard.offer(ocu, Framing::opc, part(DataFlag::first, 4000), now), Verdict::send);
  EXPECT_EQ(guard.offer(ocu, Framing::opc, part(DataFlag::middle, 4000), now), Verdict::held);
  EXPECT_EQ(guard.offer(ocu, Framing::opc, part(DataFlag::last, 100), now), Verdict::held);  // fits, but in order
  EXPECT_EQ(guard.offer(ocu, Framing::opc, reply(16), now), Verdict::send);  // an ACK does not wait
}

// verify_endpoints' budgets of 0 are the old rule: no byte beyond what the endpoint sent.
TEST_F(AmplificationBudget, WithoutAnAllowanceAnEndpointGetsNoMoreThanItSent) {
  AmplificationGuardOptions options;
  options.unverified_burst_bytes = 0;
  options.unverified_bytes_per_second = 0;
  AmplificationGuard strict(options, {11, 12});
  const Ipv4Endpoint ocu{0x7F000002, 40000};
  strict.track(ocu);
  strict.received(ocu, opc(17), kOcu, header_of(0x2B00));
  EXPECT_EQ(strict.offer(ocu, Framing::opc, reply(17), now), Verdict::send);
  EXPECT_EQ(strict.offer(ocu, Framing::opc, reply(1), now), Verdict::held);
  now += 1h;
  EXPECT_EQ(strict.offer(ocu, Framing::opc, reply(1), now), Verdict::held);
  EXPECT_EQ(strict.counters().bytes_sent_unverified, opc(17));
}

}  // namespace
}  // namespace jaus::transport::budget_test
