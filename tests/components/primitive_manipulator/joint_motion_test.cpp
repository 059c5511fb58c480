// Timed joint motions: each pose at its time, trapezoids within the limits,
// and plans that cannot be met refused.
#include <gtest/gtest.h>

#include <cmath>

#include "arms.hpp"
#include "jaus/components/joint_motion.hpp"

namespace jaus::test {
namespace {

using components::JointMotionLimit;
using components::JointTrajectory;
using components::TimedJointPose;

TimedJointPose pose(double t, std::vector<double> q, JointMotionLimit limit) {
  return {t, std::move(q), std::vector<JointMotionLimit>(2, limit)};
}

TEST(JointMotion, ConstantSpeedWithoutAccelerationLimits) {
  const auto plan = JointTrajectory::plan(planar_arm(), {0, 0}, {pose(2, {1, -0.5}, {1, 0, 0})});
  ASSERT_TRUE(plan) << plan.error().message();
  EXPECT_DOUBLE_EQ(plan->duration_s(), 2);
  EXPECT_EQ(plan->at(-1), (std::vector<double>{0, 0}));
  EXPECT_NEAR(plan->at(1)[0], 0.5, 1e-12);
  EXPECT_NEAR(plan->at(1)[1], -0.25, 1e-12);
  EXPECT_EQ(plan->at(2), (std::vector<double>{1, -0.5}));
  EXPECT_EQ(plan->at(10), (std::vector<double>{1, -0.5}));
}

TEST(JointMotion, TrapezoidReachesEachPoseAtItsTimeAtRest) {
  // 1 rad in 2 s with 2 rad/s^2 each way: cruise v = 2 / (2 + sqrt 2), ramps of v / 2 s.
  const auto plan = JointTrajectory::plan(planar_arm(), {0, 0},
                                          {pose(2, {1, 0}, {1, 2, 2}), pose(3, {1, 0}, {1, 2, 2}),
                                           pose(5, {0.5, 0.2}, {1, 2, 2})});
  ASSERT_TRUE(plan) << plan.error().message();
  const double v = 2 / (2 + std::sqrt(2.0)), ramp = v / 2;
  EXPECT_NEAR(plan->at(ramp)[0], 0.5 * 2 * ramp * ramp, 1e-12);
  EXPECT_NEAR(plan->at(1)[0], 0.5, 1e-12);  // symmetric
  EXPECT_NEAR(plan->at(2)[0], 1, 1e-12);
  EXPECT_NEAR(plan->at(2.5)[0], 1, 1e-12);  // the second pose is the same: it waits
  EXPECT_NEAR(plan->at(5)[0], 0.5, 1e-12);
  EXPECT_NEAR(plan->at(5)[1], 0.2, 1e-12);
  // Never faster than the cruise speed of the segment, sampled finely.
  double last = 0;
  for (double t = 0.001; t <= 2; t += 0.001) {
    const double x = plan->at(t)[0];
    EXPECT_LE(x - last, v * 0.001 + 1e-9);
    EXPECT_GE(x - last, -1e-12);
    last = x;
  }
}

TEST(JointMotion, PosesThatCannotBeMetAreRefusedWithThePoseAndTheJoint) {
  // 1 rad in 0.5 s at 1 rad/s.
  auto plan = JointTrajectory::plan(planar_arm(), {0, 0}, {pose(0.5, {0, 1}, {1, 0, 0})});
  ASSERT_FALSE(plan);
  EXPECT_NE(plan.error().message().find("pose 1"), std::string::npos) << plan.error().message();
  EXPECT_NE(plan.error().message().find("joint 2 (elbow)"), std::string::npos) << plan.error().message();
  // Fast enough, but not with these accelerations: 1 rad in 1.2 s at 1 rad/s needs more than 1 rad/s^2.
  EXPECT_FALSE(JointTrajectory::plan(planar_arm(), {0, 0}, {pose(1.2, {1, 0}, {1, 1, 1})}));
  EXPECT_TRUE(JointTrajectory::plan(planar_arm(), {0, 0}, {pose(1.2, {1, 0}, {1, 10, 10})}));
  // Times going back.
  plan = JointTrajectory::plan(planar_arm(), {0, 0}, {pose(2, {0.1, 0}, {1, 0, 0}), pose(1, {0.2, 0}, {1, 0, 0})});
  ASSERT_FALSE(plan);
  EXPECT_NE(plan.error().message().find("pose 2"), std::string::npos) << plan.error().message();
  // A move at time 0.
  EXPECT_FALSE(JointTrajectory::plan(planar_arm(), {0, 0}, {pose(0, {0.1, 0}, {1, 0, 0})}));
  EXPECT_TRUE(JointTrajectory::plan(planar_arm(), {0, 0}, {pose(0, {0, 0}, {1, 0, 0})}));
}

}  // namespace
}  // namespace jaus::test
