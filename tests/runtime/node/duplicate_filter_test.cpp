#include "jaus/node/duplicate_filter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

const Address kOcu{2, 1, 40, 1};
const Address kDriver{1, 1, 33, 1};
constexpr std::uint16_t kResume = 0x0004;
constexpr std::uint16_t kClearEmergency = 0x0007;

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
  const std::vector<std::uint8_t> other{2, 0};
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), other, t0 + 10ms), DuplicateVerdict::first_copy);
  const std::vector<std::uint8_t> longer{2, 0, 0};
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), longer, t0 + 20ms), DuplicateVerdict::first_copy);
  Header from_elsewhere = command(kClearEmergency, 3);
  from_elsewhere.source = Address{3, 1, 40, 1};
  EXPECT_EQ(filter.check(from_elsewhere, longer, t0 + 30ms), DuplicateVerdict::first_copy);
  Header to_elsewhere = command(kClearEmergency, 3);
  to_elsewhere.destination = Address{1, 1, 33, 2};
  EXPECT_EQ(filter.check(to_elsewhere, longer, t0 + 40ms), DuplicateVerdict::first_copy);
  // The latest payload of the first key is what a copy must repeat now.
  EXPECT_EQ(filter.check(command(kClearEmergency, 3), longer, t0 + 50ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.counters().duplicates, 1u);
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
  for (std::uint16_t s = 0; s < 3; ++s)
    EXPECT_EQ(filter.check(command(kResume, s), kPayload, t0), DuplicateVerdict::first_copy);
  // Sequence 0 seen again: 1 is now the least recently seen.
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0 + 1ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 3), kPayload, t0 + 2ms), DuplicateVerdict::first_copy);
  EXPECT_EQ(filter.size(), 3u);
  EXPECT_EQ(filter.counters().forgotten, 1u);
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0 + 3ms), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 1), kPayload, t0 + 4ms), DuplicateVerdict::first_copy);  // forgotten
  for (std::uint16_t s = 100; s < 1100; ++s) filter.check(command(kResume, s), kPayload, t0 + 5ms);
  EXPECT_EQ(filter.size(), 3u);
}

TEST(DuplicateFilter, TheDefaultBoundIs512) {
  DuplicateFilter filter;
  for (std::uint16_t s = 0; s < 600; ++s) filter.check(command(kResume, s), kPayload, t0);
  EXPECT_EQ(filter.size(), 512u);
  EXPECT_EQ(filter.check(command(kResume, 599), kPayload, t0), DuplicateVerdict::duplicate);
  EXPECT_EQ(filter.check(command(kResume, 0), kPayload, t0), DuplicateVerdict::first_copy);
}

}  // namespace
}  // namespace jaus::node
