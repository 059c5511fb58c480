// The retransmission timeout from measured round trips (jaus/node/round_trip.hpp),
// as RFC 6298 computes it, within the bounds the options set.
#include "jaus/node/round_trip.hpp"

#include <gtest/gtest.h>

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

TEST(RoundTripEstimator, BeforeAnyMeasurementTheInitialTimeout) {
  const RoundTripEstimator estimator;
  EXPECT_EQ(estimator.timeout(), 100ms);
  EXPECT_EQ(estimator.smoothed(), std::nullopt);
  EXPECT_EQ(estimator.samples(), 0u);
}

TEST(RoundTripEstimator, TheFirstMeasurementSetsTheMeanAndHalfOfItAsTheVariation) {
  RoundTripEstimator estimator;
  estimator.sample(100ms);
  EXPECT_EQ(estimator.smoothed(), 100ms);
  EXPECT_EQ(estimator.variation(), 50ms);
  EXPECT_EQ(estimator.timeout(), 300ms);  // 100 + 4 x 50
}

TEST(RoundTripEstimator, LaterMeasurementsAreSmoothed) {
  RoundTripEstimator estimator;
  estimator.sample(100ms);
  estimator.sample(200ms);
  // Variation 3/4 x 50 + 1/4 x |100 - 200| = 62.5; mean 7/8 x 100 + 1/8 x 200 = 112.5.
  EXPECT_EQ(estimator.variation(), 62500us);
  EXPECT_EQ(estimator.smoothed(), 112500us);
  EXPECT_EQ(estimator.timeout(), 362500us);
  EXPECT_EQ(estimator.samples(), 2u);
}

TEST(RoundTripEstimator, TheTimeoutStaysWithinItsBounds) {
  RoundTripEstimator lan;
  lan.sample(200us);
  EXPECT_EQ(lan.timeout(), 50ms);  // never sooner than min_timeout
  RoundTripEstimator slow;
  slow.sample(5s);
  EXPECT_EQ(slow.timeout(), 2s);  // never later than max_timeout
  RoundTripOptions options;
  options.min_timeout = 10ms;
  options.max_timeout = 20s;
  RoundTripEstimator wide(options);
  wide.sample(1ms);
  EXPECT_EQ(wide.timeout(), 10ms);
  wide.sample(5s);
  EXPECT_GT(wide.timeout(), 2s);
}

TEST(RoundTripEstimator, ASteadyRoundTripNeedsLittleMargin) {
  RoundTripEstimator estimator;
  for (int i = 0; i < 40; ++i) estimator.sample(300ms);
  EXPECT_EQ(estimator.smoothed(), 300ms);
  EXPECT_GE(estimator.timeout(), 301ms);  // the clock's granularity at least
  EXPECT_LT(estimator.timeout(), 305ms);
}

TEST(RoundTripEstimator, AnExpiredTimeoutDoublesUntilTheNextMeasurement) {
  RoundTripEstimator estimator;
  estimator.sample(100ms);  // 300 ms
  estimator.back_off(300ms);
  EXPECT_EQ(estimator.timeout(), 600ms);
  estimator.back_off(300ms);  // another message's wait of the same length: doubled once, not twice
  EXPECT_EQ(estimator.timeout(), 600ms);
  estimator.back_off(600ms);
  EXPECT_EQ(estimator.timeout(), 1200ms);
  estimator.back_off(1200ms);
  EXPECT_EQ(estimator.timeout(), 2s);  // bounded
  EXPECT_EQ(estimator.expired(), 1200ms);
  EXPECT_EQ(estimator.measured_timeout(), 300ms);  // what the measurements alone say
  estimator.sample(100ms);
  EXPECT_LT(estimator.timeout(), 600ms);  // measured again: the doubling ends
  EXPECT_EQ(estimator.expired(), 0ms);
}

TEST(RoundTrips, EachPeerHasItsOwnAndTheLeastRecentlyUsedMakesRoom) {
  RoundTrips<int> peers({}, 2);
  const rt::TimePoint t0{};
  peers.sample(1, 40ms, t0);
  peers.sample(2, 400ms, t0 + 1s);
  EXPECT_EQ(peers.timeout(1), 120ms);
  EXPECT_EQ(peers.timeout(2), 1200ms);
  EXPECT_EQ(peers.timeout(3), 100ms);  // unknown: the initial timeout
  peers.sample(1, 40ms, t0 + 2s);     // peer 1 used last
  peers.sample(3, 60ms, t0 + 3s);     // full: peer 2 makes room
  EXPECT_EQ(peers.size(), 2u);
  EXPECT_EQ(peers.find(2), nullptr);
  EXPECT_NE(peers.find(1), nullptr);
  EXPECT_EQ(peers.find(3)->smoothed(), 60ms);
}

}  // namespace
}  // namespace jaus::node
