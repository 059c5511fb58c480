// The PID loop: limits, anti-windup, and steps that do not integrate.
#include <gtest/gtest.h>

#include <limits>

#include "jaus/components/guidance/pid.hpp"

namespace jaus::components::guidance {
namespace {

Pid make(double kp, double ki, double kd, double lo = -1, double hi = 1) {
  auto pid = Pid::make({kp, ki, kd, lo, hi});
  EXPECT_TRUE(pid);
  return *pid;
}

TEST(Pid, RejectsNegativeOrNonFiniteGainsAndInvertedLimits) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Pid::make({-1, 0, 0, -1, 1}));
  EXPECT_FALSE(Pid::make({1, nan, 0, -1, 1}));
  EXPECT_FALSE(Pid::make({1, 0, 0, 1, -1}));
  EXPECT_EQ(Pid::make({1, 0, 0, 1, -1}).error().code, ErrorCode::invalid_argument);
  EXPECT_TRUE(Pid::make({1, 0, 0, 0, 0}));
}

TEST(Pid, ProportionalIsClampedToTheLimits) {
  Pid pid = make(2, 0, 0);
  EXPECT_DOUBLE_EQ(pid.update(0.25, 0.1), 0.5);
  EXPECT_DOUBLE_EQ(pid.update(3, 0.1), 1);
  EXPECT_DOUBLE_EQ(pid.update(-3, 0.1), -1);
}

TEST(Pid, TheIntegralAccumulatesFromTheSecondUpdate) {
  Pid pid = make(0, 1, 0, -10, 10);
  EXPECT_DOUBLE_EQ(pid.update(1, 0.5), 0);  // the first update has no time step
  EXPECT_DOUBLE_EQ(pid.update(1, 0.5), 0.5);
  EXPECT_DOUBLE_EQ(pid.update(1, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(pid.update(1, 0), 1.0);  // no time passed: nothing integrated
  EXPECT_DOUBLE_EQ(pid.update(1, -1), 1.0);
  EXPECT_DOUBLE_EQ(pid.update(std::numeric_limits<double>::quiet_NaN(), 0.5), 1.0);  // NaN counts as 0
  pid.reset();
  EXPECT_DOUBLE_EQ(pid.update(1, 0.5), 0);
}

TEST(Pid, TheDerivativeActsOnTheChangeOfError) {
  Pid pid = make(0, 0, 1, -10, 10);
  EXPECT_DOUBLE_EQ(pid.update(1, 0.1), 0);  // no derivative on the first update
  EXPECT_NEAR(pid.update(1.5, 0.1), 5, 1e-12);
}

TEST(Pid, AntiWindupLeavesSaturationAsSoonAsTheErrorChangesSign) {
  // Held at the limit for a long time with a large error...
  Pid pid = make(0.5, 1, 0);
  for (int i = 0; i < 1000; ++i) EXPECT_LE(pid.update(5, 0.05), 1);
  EXPECT_DOUBLE_EQ(pid.last_output(), 1);
  EXPECT_LE(pid.integral_term(), 1);  // ...it stored no more than the limit
  // ...once past the target the output leaves the limit at once (a naive
  // integral of 250 would hold it there for hundreds of steps).
  const double out = pid.update(-0.5, 0.05);
  EXPECT_LT(out, 1);
  int steps = 0;
  while (pid.update(-0.5, 0.05) > 0 && steps < 1000) ++steps;
  EXPECT_LT(steps, 50);
}

TEST(Pid, TheIntegralStopsAtTheLimitAndUnwindsAtOnce) {
  Pid pid = make(0, 1, 0);
  pid.update(1, 0.1);
  for (int i = 0; i < 5; ++i) pid.update(1, 0.1);
  EXPECT_NEAR(pid.integral_term(), 0.5, 1e-12);
  for (int i = 0; i < 20; ++i) pid.update(1, 0.1);
  EXPECT_NEAR(pid.integral_term(), 1.0, 1e-12);  // at the limit, not 2.5
  EXPECT_NEAR(pid.update(-1, 0.1), 0.9, 1e-12);  // the first step back leaves the limit

  Pid strong = make(10, 1, 0);
  strong.update(-1, 0.1);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(strong.update(-1, 0.1), -1);
  EXPECT_DOUBLE_EQ(strong.integral_term(), 0);  // saturated low by the proportional term: nothing stored
}

}  // namespace
}  // namespace jaus::components::guidance
