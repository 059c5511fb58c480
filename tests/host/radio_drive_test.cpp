// The vehicle's send budget on a radio (issue 45, step 2), the short form of
// bench_radio_link: a 256 kbit/s radio that a streaming camera alone would
// fill, under virtual time. With the budget, a stop's ACK comes back within
// a round trip and a little, control holds, every effort arrives, and the
// camera still delivers a frame at least every 2 s.
#include <gtest/gtest.h>

#include <algorithm>

#include "radio_drive.hpp"

namespace jaus::test_support::radio {
namespace {

// A radio that loses nothing and does not jitter: what is measured is the
// queueing alone.
DriveOptions clean_radio(std::uint64_t budget) {
  DriveOptions options;
  options.radio.bits_per_second = 256'000;
  options.radio.least_one_way = 150ms;
  options.radio.jitter = 0ms;
  options.radio.mean_fade = 0ms;
  options.budget_bits_per_second = budget;
  options.length = 20s;
  return options;
}

TEST(RadioDriveTest, WithTheBudgetStopsControlEffortsAndFramesAllGetThrough) {
  const Outcome o = drive_over_radio(clean_radio(230'000));
  // Stops every 3 s from 3 s on: 6 in 20 s, each ACKed within the 300 ms
  // round trip plus the radios' airtime (one image packet at most ahead).
  EXPECT_EQ(o.emergencies, 6);
  ASSERT_EQ(o.emergency_ack_ms.size(), 6u);
  EXPECT_LT(*std::max_element(o.emergency_ack_ms.begin(), o.emergency_ack_ms.end()), 500.0);
  EXPECT_EQ(o.control_granted, 1);
  EXPECT_EQ(o.control_lost, 0);
  ASSERT_GT(o.efforts_sent, 150);
  EXPECT_EQ(static_cast<int>(o.effort_ms.size()), o.efforts_sent);
  EXPECT_LT(*std::max_element(o.effort_ms.begin(), o.effort_ms.end()), 300.0);
  // The camera: whole frames, the newest, at least one every 2 s once it streams.
  ASSERT_GE(o.frames.size(), 10u);
  EXPECT_LE(longest_gap_s(o.frames), 2.0);
  EXPECT_EQ(o.radio_overflowed, 0u);  // the radio's buffer never filled
}

}  // namespace
}  // namespace jaus::test_support::radio
