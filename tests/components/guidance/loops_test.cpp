// Angles, efforts and the heading and speed loops.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "jaus/components/guidance/loops.hpp"

namespace jaus::components::guidance {
namespace {

using std::numbers::pi;
constexpr double kDeg = pi / 180;

VehicleLimits differential() { return {}; }
VehicleLimits ackermann() {
  VehicleLimits l;
  l.steering = Steering::ackermann;
  l.max_speed_mps = 2.0;
  l.max_steering_rad = 0.5;
  l.wheel_base_m = 0.8;
  return l;
}

TEST(HeadingError, TakesTheShortWayRoundAcrossTheWrap) {
  EXPECT_NEAR(heading_error(-170 * kDeg, 170 * kDeg), 20 * kDeg, 1e-12);   // right across south
  EXPECT_NEAR(heading_error(170 * kDeg, -170 * kDeg), -20 * kDeg, 1e-12);  // left across south
  EXPECT_NEAR(heading_error(10 * kDeg, -10 * kDeg), 20 * kDeg, 1e-12);
  EXPECT_NEAR(heading_error(3 * pi, 0), pi, 1e-12);  // (-pi, pi]
  EXPECT_NEAR(heading_error(0, pi), pi, 1e-12);
  EXPECT_NEAR(heading_error(7 * pi / 2, 0), -pi / 2, 1e-12);
  EXPECT_EQ(heading_error(std::numeric_limits<double>::quiet_NaN(), 0), 0);
}

TEST(ToEffort, DifferentialIsSpeedAndYawRateInPercentOfTheirMaxima) {
  const auto d = differential();  // 1 m/s, 1 rad/s
  auto e = to_effort({0.5, 0.4, 0}, d);
  EXPECT_NEAR(e.propulsive_linear.x, 50, 1e-12);
  EXPECT_NEAR(e.propulsive_rotational.z, 20, 1e-12);  // 0.5 m/s * 0.4 /m = 0.2 rad/s
  e = to_effort({0, 0, -0.7}, d);                     // turning left in place
  EXPECT_NEAR(e.propulsive_linear.x, 0, 1e-12);
  EXPECT_NEAR(e.propulsive_rotational.z, -70, 1e-12);
  e = to_effort({5, 10, 0}, d);
  EXPECT_EQ(e.propulsive_linear.x, 100);
  EXPECT_EQ(e.propulsive_rotational.z, 100);
  e = to_effort({std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(), 0}, d);
  EXPECT_EQ(e, WrenchEffort{});
}

TEST(ToEffort, AckermannSteersTheCurvaturesAngleClampedToTheTightestTurn) {
  const auto a = ackermann();
  const double k = std::tan(0.25) / 0.8;  // half steering
  auto e = to_effort({1, k, 0}, a);
  EXPECT_NEAR(e.propulsive_linear.x, 50, 1e-12);
  EXPECT_NEAR(e.propulsive_rotational.z, 50, 1e-9);
  e = to_effort({0, -k, 0}, a);  // at rest it still steers
  EXPECT_NEAR(e.propulsive_rotational.z, -50, 1e-9);
  e = to_effort({1, 100, 0}, a);
  EXPECT_EQ(e.propulsive_rotational.z, 100);
  EXPECT_NEAR(a.max_curvature_per_m(), std::tan(0.5) / 0.8, 1e-12);
}

TEST(LimitsFrom, ReadsTheDrivetrainFromThePlatformSpecifications) {
  PlatformSpecifications spec;
  EXPECT_FALSE(limits_from(spec));
  spec.max_velocity_x_mps = 1.5;
  EXPECT_FALSE(limits_from(spec));  // neither a yaw rate nor a turning radius
  spec.max_yaw_rate_rps = 2;
  auto l = limits_from(spec);
  ASSERT_TRUE(l);
  EXPECT_EQ(l->steering, Steering::differential);
  EXPECT_EQ(l->max_speed_mps, 1.5);
  EXPECT_EQ(l->max_yaw_rate_rps, 2);

  spec.turning_radius_m = 2.0;
  spec.wheel_base_m = 1.0;
  l = limits_from(spec);
  ASSERT_TRUE(l);
  EXPECT_EQ(l->steering, Steering::ackermann);
  EXPECT_NEAR(l->max_steering_rad, std::atan(0.5), 1e-12);
  EXPECT_NEAR(l->max_curvature_per_m(), 0.5, 1e-12);  // 1 / turning radius
  spec.turning_radius_m = 0;
  EXPECT_FALSE(limits_from(spec));
}

TEST(HeadingLoop, TurnsTheShortWayWithinTheVehiclesYawRate) {
  auto loop = HeadingLoop::make({2, 0, 0}, differential());
  ASSERT_TRUE(loop);
  EXPECT_NEAR(loop->update(10 * kDeg, 0, 0.5, 0.05), 20 * kDeg, 1e-12);  // right: positive
  EXPECT_NEAR(loop->update(-170 * kDeg, 170 * kDeg, 0.5, 0.05), 40 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(loop->update(-pi / 2, 0, 0.5, 0.05), -1);  // limited to 1 rad/s
  const auto e = loop->effort(-pi / 2, 0, 0.5, 0.05);
  EXPECT_NEAR(e.propulsive_linear.x, 50, 1e-12);
  EXPECT_NEAR(e.propulsive_rotational.z, -100, 1e-12);
}

TEST(HeadingLoop, AckermannTurnsOnlyAsFastAsItsSpeedAllows) {
  auto loop = HeadingLoop::make({2, 0, 0}, ackermann());
  ASSERT_TRUE(loop);
  EXPECT_EQ(loop->update(pi / 2, 0, 0, 0.05), 0);  // at rest: no yaw rate to be had
  const double k_max = std::tan(0.5) / 0.8;
  EXPECT_NEAR(loop->update(pi / 2, 0, 0.5, 0.05), 0.5 * k_max, 1e-12);
  auto e = loop->effort(pi / 2, 0, 0.5, 0.05);
  EXPECT_NEAR(e.propulsive_rotational.z, 100, 1e-9);  // full right lock
  e = loop->effort(pi / 2, 0, -0.5, 0.05);            // reversing: the wheels turn the other way
  EXPECT_NEAR(e.propulsive_rotational.z, -100, 1e-9);
}

TEST(SpeedLoop, FeedforwardGivesTheTargetAndTheCorrectionMakesUpAShortfall) {
  auto loop = SpeedLoop::make({50, 100, 0}, differential());
  ASSERT_TRUE(loop);
  EXPECT_NEAR(loop->update(0.6, 0.6, 0.05), 60, 1e-12);
  // A drive that delivers 80 % of what it is told: the loop converges on the target.
  double speed = 0;
  for (int i = 0; i < 400; ++i) speed = 0.8 * loop->update(0.6, speed, 0.05) / 100;
  EXPECT_NEAR(speed, 0.6, 1e-3);
  EXPECT_EQ(loop->update(5, 0, 0.05), 100);  // and never beyond full effort
  EXPECT_FALSE(SpeedLoop::make({-1, 0, 0}, differential()));
  VehicleLimits broken;
  broken.max_speed_mps = 0;
  EXPECT_FALSE(SpeedLoop::make({1, 0, 0}, broken));
}

TEST(SpeedLoop, AskingBeyondFullEffortStoresNoIntegralForLater) {
  auto loop = SpeedLoop::make({0, 100, 0}, differential());
  ASSERT_TRUE(loop);
  // Held at 100 % by a target the vehicle cannot reach, for a long time...
  for (int i = 0; i < 400; ++i) EXPECT_EQ(loop->update(1.5, 1.0, 0.05), 100);
  // ...then asked for half speed while at full: the feedforward alone, not 100 % from a stored integral.
  EXPECT_LE(loop->update(0.5, 1.0, 0.05), 50);
}

TEST(Pid, PerStepLimitsNarrowTheGainsLimits) {
  auto pid = Pid::make({1, 0, 0, -10, 10});
  ASSERT_TRUE(pid);
  EXPECT_EQ(pid->update(5, 0.1, -2, 2), 2);
  EXPECT_EQ(pid->update(50, 0.1, -20, 20), 10);  // never wider than the gains'
  EXPECT_EQ(pid->update(-5, 0.1, -2, 2), -2);
}

}  // namespace
}  // namespace jaus::components::guidance
