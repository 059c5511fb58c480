// The shared frame conventions: angles wrapped into the range JAUS encodes,
// ENU yaw <-> NED heading, ENU <-> NED vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "jaus/components/navigation_frames.hpp"

namespace jaus::components {
namespace {

using std::numbers::pi;

TEST(NavigationFrames, AnglesWrapIntoTheHalfOpenRangeMinusPiToPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(pi), pi);
  EXPECT_DOUBLE_EQ(wrap_angle(-pi), pi);  // the closed end is +pi
  EXPECT_NEAR(wrap_angle(3 * pi), pi, 1e-12);
  EXPECT_GT(wrap_angle(3 * pi), 0);       // never the excluded -pi
  EXPECT_NEAR(wrap_angle(-3 * pi), pi, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(0), 0);
  EXPECT_NEAR(wrap_angle(2 * pi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(wrap_angle(-2 * pi - 0.25), -0.25, 1e-12);
  EXPECT_NEAR(wrap_angle(100 * pi + 1), 1, 1e-9);
  EXPECT_DOUBLE_EQ(wrap_angle(-pi + 1e-9), -pi + 1e-9);  // just inside stays
}

TEST(NavigationFrames, NonFiniteAnglesAreNeverTurnedIntoNumbers) {
  EXPECT_TRUE(std::isnan(wrap_angle(std::nan(""))));
  EXPECT_TRUE(std::isinf(wrap_angle(std::numeric_limits<double>::infinity())));
}

TEST(NavigationFrames, EnuYawFromEastBecomesHeadingFromNorthClockwise) {
  EXPECT_NEAR(enu_yaw_to_ned_heading(0), pi / 2, 1e-12);         // facing east
  EXPECT_NEAR(enu_yaw_to_ned_heading(pi / 2), 0, 1e-12);         // facing north
  EXPECT_NEAR(enu_yaw_to_ned_heading(pi), -pi / 2, 1e-12);       // facing west
  EXPECT_NEAR(enu_yaw_to_ned_heading(-pi / 2), pi, 1e-12);       // facing south
  EXPECT_NEAR(ned_heading_to_enu_yaw(0), pi / 2, 1e-12);         // north
  EXPECT_NEAR(ned_heading_to_enu_yaw(pi / 2), 0, 1e-12);         // east
  EXPECT_NEAR(ned_heading_to_enu_yaw(-pi / 4), 3 * pi / 4, 1e-12);  // north-west
}

TEST(NavigationFrames, EnuAndNedSwapTheHorizontalAxesAndFlipUp) {
  // 3 m east, 4 m north, 5 m up is 4 m north, 3 m east, 5 m above (z down: -5).
  EXPECT_EQ(enu_to_ned(Vector3{3, 4, 5}), (Vector3{4, 3, -5}));
  EXPECT_EQ(ned_to_enu(Vector3{4, 3, -5}), (Vector3{3, 4, 5}));
}

TEST(NavigationFrames, EveryConversionRoundTrips) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-1000, 1000), angle(-pi + 1e-9, pi);
  for (int i = 0; i < 1000; ++i) {
    const Vector3 v{value(rng), value(rng), value(rng)};
    EXPECT_EQ(ned_to_enu(enu_to_ned(v)), v);
    EXPECT_EQ(enu_to_ned(ned_to_enu(v)), v);
    const double yaw = angle(rng);
    EXPECT_NEAR(ned_heading_to_enu_yaw(enu_yaw_to_ned_heading(yaw)), yaw, 1e-12);
    EXPECT_NEAR(enu_yaw_to_ned_heading(ned_heading_to_enu_yaw(yaw)), yaw, 1e-12);
  }
}

}  // namespace
}  // namespace jaus::components
