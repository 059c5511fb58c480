#include "jaus/node/duplicate_filter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

const Address kOcu{2, 1, 40, 1};
const Address kDriver{1, 1, 33, 1};
constexpr std::uint16_t kResume = 0x0004;
constexpr std::uint16_t kStandby = 0x0003;
constexpr std::uint16_t kClearEmergency = 0x0007;
constexpr std::uint16_t kRequestControl = 0x000D;

Header command(std::uint16_t code, std::uint16_t sequence, AckNak ack = AckNak::ack_requested) {
  Header h;
  h.command_code = code;
  h.ack_nak = ack;
  h.source = kOcu;
  h.destination = kDriver;
  h.sequence = sequence;
  return h;
}

const std::vector<std::uint8_t> kPayload{1, 0};
const rt::TimePoint t0{};

TEST(DuplicateFilter, ARetransmittedCopyIsADuplicate) {
  DuplicateFilter filter;
  EXPECT_EQ(filter.check(command(kResume, 7), kPayload, t0), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.check(command(kResume, 7), kPayload, t0 + 50ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 7), kPayload, t0 + 100ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.counters().duplicates, 2u);
  // The next message of the stream is not one.
  EXPECT_EQ(filter.check(command(kResume, 8), kPayload, t0 + 150ms), DuplicateVerdict::first_copy);
}

TEST(DuplicateFilter, StopsAreNeverFiltered) {
  DuplicateFilter filter;
  for (const std::uint16_t stop : {0x0006, 0x0003, 0x0002}) {
    EXPECT_TRUE(DuplicateFilter::always_delivered(stop));
    EXPECT_EQ(filter.check(command(stop, 0), kPayload, t0), DuplicateVerdict::not_filtered);
    EXPECT_EQ(filter.check(command(stop, 0), kPayload, t0 + 1ms), DuplicateVerdict::not_filtered);
  }
  EXPECT_FALSE(DuplicateFilter::always_delivered(kClearEmergency));
  EXPECT_EQ(filter.size(), 0u);
}

TEST(DuplicateFilter, OnlyAckRequestedSinglePacketsAreFiltered) {
  DuplicateFilter filter;
  EXPECT_EQ(filter.check(command(kResume, 1, AckNak::none), kPayload, t0), DuplicateVerdict::not_filtered);
  EXPECT_EQ(filter.check(command(kResume, 1, AckNak::none), kPayload, t0), DuplicateVerdict::not_filtered);
  Header part = command(kResume, 2);
  part.data_flag = DataFlag::first;
  EXPECT_EQ(filter.check(part, kPayload, t0), DuplicateVerdict::not_filtered);
  EXPECT_EQ(filter.check(part, kPayload, t0), DuplicateVerdict::not_filtered);
}

TEST(DuplicateFilter, ADifferentPayloadSourceOrDestinationIsNotACopy) {
  DuplicateFilter filter;
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), kPayload, t0), DuplicateVerdict::first_copy);
  // Another message under a number used within the window: its sender started again.
  const std::vector<std::uint8_t> other{2, 0};
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), other, t0 + 10ms), DuplicateVerdict::new_session);
  const std::vector<std::uint8_t> longer{2, 0, 0};
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), longer, t0 + 20ms), DuplicateVerdict::new_session);
  EXPECT_EQ(filter.check(command(kResume, 3), longer, t0 + 25ms), DuplicateVerdict::new_session);  // another code
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), longer, t0 + 28ms), DuplicateVerdict::new_session);
  Header from_elsewhere = command(kClearEmergency, 3);
  from_elsewhere.source = Address{3, 1, 40, 1};
  EXPECT_EQ(filter.check(from_elsewhere, longer, t0 + 30ms), DuplicateVerdict::first_copy);
  Header to_elsewhere = command(kClearEmergency, 3);
  to_elsewhere.destination = Address{1, 1, 33, 2};
  EXPECT_EQ(filter.check(to_elsewhere, longer, t0 + 40ms), DuplicateVerdict::first_copy);
  // The latest message under the number is what a copy must repeat now.
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), longer, t0 + 50ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.counters().duplicates, 1u);
  EXPECT_EQ(filter.counters().new_sessions, 4u);
}

TEST(DuplicateFilter, ACopyOutsideTheWindowIsDelivered) {
  DuplicateFilter filter({.window = 2s});
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0 + 2s), DuplicateVerdict::duplicate);
  // The window runs from the last copy seen: 2 s after t0 + 2 s.
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0 + 4s), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0 + 6s + 1ms), DuplicateVerdict::first_copy);
}

TEST(DuplicateFilter, TheTableIsBoundedAndForgetsTheLeastRecentlySeen) {
  DuplicateFilter filter({.window = 2s, .max_entries = 3});
  for (std::uint16_t s = 10; s < 13; ++s)
    EXPECT_EQ(filter.check(command(kResume, s), kPayload, t0), DuplicateVerdict::first_copy);
  // Sequence 10 seen again: 11 is now the least recently seen.
  EXPECT_EQ(filter.check(command(kResume, 10), kPayload, t0 + 1ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 13), kPayload, t0 + 2ms), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.size(), 3u);
  EXPECT_EQ(filter.counters().forgotten, 1u);
  EXPECT_EQ(filter.check(command(kResume, 10), kPayload, t0 + 3ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 11), kPayload, t0 + 4ms), DuplicateVerdict::first_copy);  // forgotten
  for (std::uint16_t s = 100; s < 1100; ++s) filter.check(command(kResume, s), kPayload, t0 + 5ms);
  EXPECT_EQ(filter.size(), 3u);
}

TEST(DuplicateFilter, TheDefaultBoundIs512) {
  DuplicateFilter filter;
  for (std::uint16_t s = 100; s < 700; ++s) filter.check(command(kResume, s), kPayload, t0);
  EXPECT_EQ(filter.size(), 512u);
  EXPECT_EQ(filter.check(command(kResume, 699), kPayload, t0), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 100), kPayload, t0), DuplicateVerdict::first_copy);
}

// An RA operator unit that keeps no state (numbering from 0 or 1 on every
// start, as Jr does in JSS) and restarts within the window: its Request
// Control, numbered like the last run's, acts at once (issue 43's rule, for
// both dialects).
TEST(DuplicateFilter, ASenderNumberingFromItsStartAgainIsANewSession) {
  DuplicateFilter filter;
  const std::vector<std::uint8_t> authority{5};
  EXPECT_EQ(filter.check(command(kRequestControl, 1), authority, t0), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.check(command(kResume, 2), kPayload, t0 + 10ms), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.check(command(kRequestControl, 1), authority, t0 + 500ms), DuplicateVerdict::new_session);
  EXPECT_EQ(filter.check(command(kResume, 2), kPayload, t0 + 510ms), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.counters().new_sessions, 1u);
  EXPECT_EQ(filter.counters().duplicates, 0u);
  // A sequence that wraps from 65535 to 0 is no restart.
  DuplicateFilter wrapping;
  EXPECT_EQ(wrapping.check(command(kResume, 65535), kPayload, t0), DuplicateVerdict::first_copy);
  EXPECT_EQ(wrapping.check(command(kResume, 0), kPayload, t0 + 1ms), DuplicateVerdict::first_copy);
  EXPECT_EQ(wrapping.check(command(kResume, 65535), kPayload, t0 + 2ms), DuplicateVerdict::duplicate);
}

// Safety before the restart rule: a copy of a Resume that its sender has since
// followed with a Standby never acts, whatever its number, restart or not.
TEST(DuplicateFilter, ACopyThatAStopFollowedNeverActs) {
  for (const std::uint16_t resume : {std::uint16_t{1}, std::uint16_t{300}}) {
    SCOPED_TRACE("Resume's sequence number " + std::to_string(resume));
    DuplicateFilter filter;
    EXPECT_EQ(filter.check(command(kResume, resume), kPayload, t0), DuplicateVerdict::first_copy);
    EXPECT_EQ(filter.check(command(kStandby, static_cast<std::uint16_t>(resume + 1)), {}, t0 + 10ms),
              DuplicateVerdict::not_filtered);
    EXPECT_EQ(filter.check(command(kResume, resume), kPayload, t0 + 20ms), DuplicateVerdict::late_copy);
    // Numbering from 0 again (a restart) does not let it act either.
    EXPECT_EQ(filter.check(command(kClearEmergency, 0, AckNak::none), kPayload, t0 + 30ms),
              DuplicateVerdict::new_session);
    EXPECT_EQ(filter.check(command(kResume, resume), kPayload, t0 + 40ms), DuplicateVerdict::late_copy);
    EXPECT_EQ(filter.counters().late_copies, 2u);
    // A Resume under a new number acts.
    EXPECT_FALSE(is_dropped(filter.check(command(kResume, 500), kPayload, t0 + 50ms)));
  }
}

// JSS retransmits a large message's packets one by one: there they can be copies.
TEST(DuplicateFilter, PacketsOfALargeMessageAreFilteredWhereTheDialectSaysSo) {
  DuplicateFilter jss({.window = 3s, .max_entries = 4096, .pieces_filtered = true});
  Header piece = command(kResume, 20);
  piece.data_flag = DataFlag::first;
  EXPECT_EQ(jss.check(piece, kPayload, t0), DuplicateVerdict::first_copy);
  EXPECT_EQ(jss.check(piece, kPayload, t0 + 1ms), DuplicateVerdict::duplicate);
  // A whole message under the same number and bytes is another message.
  EXPECT_EQ(jss.check(command(kResume, 20), kPayload, t0 + 2ms), DuplicateVerdict::new_session);
}

}  // namespace
}  // namespace jaus::node
