// Clearpath (FLU, yaw left-positive, world yaw from east) <-> JAUS (FRD, yaw
// right-positive, heading from north): physical cases first, then round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "jaus/bridge/frame_conventions.hpp"

namespace bridge = jaus::bridge;
using std::numbers::pi;

TEST(FrameConventions, APointToTheLeftAndAboveIsNegativeYAndZInJaus) {
  // One metre left of the platform and half a metre above it.
  EXPECT_EQ(bridge::flu_to_frd(bridge::Vector3{0, 1, 0.5}), (bridge::Vector3{0, -1, -0.5}));
  // Forward stays forward.
  EXPECT_EQ(bridge::flu_to_frd(bridge::Vector3{2, 0, 0}), (bridge::Vector3{2, 0, 0}));
}

TEST(FrameConventions, ALeftTurnIsANegativeJausYawRate) {
  // Clearpath 0x8601 reports a left turn as positive yaw rate; JAUS's is positive to the right.
  const auto rates = bridge::flu_to_frd(bridge::Vector3{0.1, 0.2, 0.5});
  EXPECT_DOUBLE_EQ(rates.x, 0.1);   // roll rate: the same physical sense
  EXPECT_DOUBLE_EQ(rates.y, -0.2);  // pitch rate
  EXPECT_DOUBLE_EQ(rates.z, -0.5);  // yaw rate
  EXPECT_DOUBLE_EQ(bridge::jaus_turn_to_clearpath(30.0), -30.0);  // JAUS "turn right 30 %"
  EXPECT_DOUBLE_EQ(bridge::clearpath_turn_to_jaus(-30.0), 30.0);
}

TEST(FrameConventions, NoseDownAndRightSideDownKeepTheirPhysicalMeaning) {
  // FLU: positive pitch turns z (up) toward x: nose down. FRD: positive pitch is nose up.
  // Roll (right side down) is positive in both.
  const auto jaus = bridge::flu_to_frd(bridge::EulerAngles{0.2, 0.1, 0.3});
  EXPECT_DOUBLE_EQ(jaus.roll, 0.2);
  EXPECT_DOUBLE_EQ(jaus.pitch, -0.1);
  EXPECT_DOUBLE_EQ(jaus.yaw, -0.3);
}

TEST(FrameConventions, WorldYawFromEastBecomesHeadingFromNorth) {
  EXPECT_NEAR(bridge::enu_yaw_to_ned_heading(0), pi / 2, 1e-12);        // facing east
  EXPECT_NEAR(bridge::enu_yaw_to_ned_heading(pi / 2), 0, 1e-12);        // facing north
  EXPECT_NEAR(bridge::enu_yaw_to_ned_heading(pi), -pi / 2, 1e-12);      // facing west (270 degrees)
  EXPECT_NEAR(bridge::enu_yaw_to_ned_heading(-pi / 2), pi, 1e-12);      // facing south
  EXPECT_NEAR(bridge::ned_heading_to_enu_yaw(pi / 4), pi / 4, 1e-12);   // north-east is 45 degrees either way
  EXPECT_NEAR(bridge::ned_heading_to_enu_yaw(-pi / 4), 3 * pi / 4, 1e-12);  // north-west
}

TEST(FrameConventions, AnglesWrapIntoTheHalfOpenRangeJausEncodes) {
  EXPECT_DOUBLE_EQ(bridge::wrap_angle(-pi), pi);
  EXPECT_DOUBLE_EQ(bridge::wrap_angle(pi), pi);
  EXPECT_NEAR(bridge::wrap_angle(3 * pi), pi, 1e-12);
  EXPECT_NEAR(bridge::wrap_angle(2 * pi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(bridge::wrap_angle(-2 * pi - 0.25), -0.25, 1e-12);
  EXPECT_DOUBLE_EQ(bridge::flu_to_frd(bridge::EulerAngles{0, 0, pi}).yaw, pi);  // not -pi
  EXPECT_TRUE(std::isnan(bridge::wrap_angle(std::nan(""))));  // never silently turned into a number
}

TEST(FrameConventions, EveryConversionRoundTrips) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-10, 10), angle(-pi + 1e-9, pi);
  for (int i = 0; i < 1000; ++i) {
    const bridge::Vector3 v{value(rng), value(rng), value(rng)};
    EXPECT_EQ(bridge::frd_to_flu(bridge::flu_to_frd(v)), v);
    const bridge::EulerAngles a{angle(rng), angle(rng), angle(rng)};
    const auto back = bridge::frd_to_flu(bridge::flu_to_frd(a));
    EXPECT_DOUBLE_EQ(back.roll, a.roll);
    EXPECT_DOUBLE_EQ(back.pitch, a.pitch);
    EXPECT_NEAR(back.yaw, a.yaw, 1e-12);
    const double yaw = angle(rng);
    EXPECT_NEAR(bridge::ned_heading_to_enu_yaw(bridge::enu_yaw_to_ned_heading(yaw)), yaw, 1e-12);
  }
}
