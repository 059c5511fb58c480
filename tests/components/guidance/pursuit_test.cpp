// Pure pursuit: the arc's curvature and sign, command shaping per drivetrain,
// and the waypoint list's legs, cross-track sign and arrival.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jaus/components/guidance/pursuit.hpp"

namespace jaus::components::guidance {
namespace {

using std::numbers::pi;

VehicleLimits ackermann() {
  VehicleLimits l;
  l.steering = Steering::ackermann;
  return l;  // 1 m/s, 0.5 rad steering, 0.5 m wheel base
}

TEST(PursuitCurvature, IsTwoTimesTheLateralOffsetOverTheDistanceSquared) {
  const Pose2 north{0, 0, 0};
  EXPECT_EQ(pursuit_curvature(north, {5, 0}), 0);  // straight ahead
  EXPECT_NEAR(pursuit_curvature(north, {1, 1}), 1.0, 1e-12);  // ahead right: 2 * 1 / 2, turning right
  EXPECT_NEAR(pursuit_curvature(north, {1, -1}), -1.0, 1e-12);
  EXPECT_EQ(pursuit_curvature(north, {0, 0}), 0);
  // The arc through a point one radius to the side ahead is the quarter circle of that radius.
  const Pose2 east{3, 4, pi / 2};
  EXPECT_NEAR(pursuit_curvature(east, {3 - 2, 4 + 2}), 0.5, 1e-12);  // heading east, the point south-east: right
  EXPECT_NEAR(pursuit_curvature(east, {3 + 2, 4 + 2}), -0.5, 1e-12);  // north-east: left
  EXPECT_GT(pursuit_curvature(north, {-1, 0}), 0);  // straight behind: it turns round
}

TEST(ShapeCommand, DifferentialKeepsTheArcWithinItsYawRateAndTurnsInPlaceWhenFacingAway) {
  const VehicleLimits d;  // 1 m/s, 1 rad/s
  const PursuitConfig config;
  auto c = shape_command(0.5, 0, 0.8, config, d);
  EXPECT_NEAR(c.speed_mps, 0.8, 1e-12);
  EXPECT_NEAR(c.yaw_rate_rps, 0.4, 1e-12);
  c = shape_command(4, 0, 0.8, config, d);  // 3.2 rad/s wanted: slower on the same arc
  EXPECT_NEAR(c.speed_mps, 0.25, 1e-12);
  EXPECT_NEAR(c.yaw_rate_rps, 1, 1e-12);
  c = shape_command(1, 2.0, 0.8, config, d);  // the target behind on the right
  EXPECT_EQ(c.speed_mps, 0);
  EXPECT_NEAR(c.yaw_rate_rps, 1, 1e-12);
  c = shape_command(-1, -0.5 - pi / 2, 0.8, config, d);
  EXPECT_NEAR(c.yaw_rate_rps, -1, 1e-12);
}

TEST(ShapeCommand, AckermannClampsTheCurvatureAndKeepsMovingThroughSharpTurns) {
  const auto a = ackermann();
  PursuitConfig config;
  config.min_speed_mps = 0.2;
  auto c = shape_command(10, pi / 2, 0.8, config, a);
  EXPECT_NEAR(c.curvature_per_m, a.max_curvature_per_m(), 1e-12);
  EXPECT_NEAR(c.speed_mps, 0.2, 1e-12);  // slowed, not stopped: it cannot turn at rest
  c = shape_command(-0.1, 0, 0.8, config, a);
  EXPECT_NEAR(c.curvature_per_m, -0.1, 1e-12);
  EXPECT_NEAR(c.speed_mps, 0.8, 1e-12);
  c = shape_command(0, 0, 0, config, a);  // told to stop, it stops
  EXPECT_EQ(c.speed_mps, 0);
}

TEST(WaypointPursuit, RejectsAnEmptyListAndABadConfiguration) {
  EXPECT_FALSE(WaypointPursuit::make({}, {}, {}));
  PursuitConfig bad;
  bad.arrival_tolerance_m = 0;
  EXPECT_FALSE(WaypointPursuit::make({{1, 0}}, bad, {}));
  VehicleLimits broken;
  broken.max_yaw_rate_rps = -1;
  EXPECT_FALSE(WaypointPursuit::make({{1, 0}}, {}, broken));
  EXPECT_EQ(WaypointPursuit::make({{std::nan(""), 0}}, {}, {}).error().code, ErrorCode::invalid_argument);
}

TEST(WaypointPursuit, TheLookaheadIsOnTheLegAndTheCrossTrackIsPositiveToItsRight) {
  auto p = WaypointPursuit::make({{10, 0}, {10, 10}}, {}, {});
  ASSERT_TRUE(p);
  auto out = p->update({0, 0, 0});  // the first leg starts here, heading north
  EXPECT_EQ(out.target, 0u);
  EXPECT_EQ(out.lookahead, (Point2{1, 0}));
  EXPECT_EQ(out.cross_track_m, 0);
  EXPECT_EQ(out.command.curvature_per_m, 0);
  EXPECT_NEAR(out.effort.propulsive_linear.x, 50, 1e-12);  // travel speed 0.5 of 1 m/s

  out = p->update({3, 0.5, 0});  // east of a northbound leg: right of it
  EXPECT_NEAR(out.cross_track_m, 0.5, 1e-12);
  EXPECT_EQ(out.lookahead, (Point2{4, 0}));
  EXPECT_LT(out.command.curvature_per_m, 0);  // steers left, back onto it
  out = p->update({3, -0.5, 0});
  EXPECT_NEAR(out.cross_track_m, -0.5, 1e-12);
  EXPECT_GT(out.command.curvature_per_m, 0);

  out = p->update({9.4, 0, 0});  // near the end of the leg: never past the waypoint
  EXPECT_EQ(out.lookahead, (Point2{10, 0}));
}

TEST(WaypointPursuit, ArrivingWithinTheToleranceMovesOnAndTheLastFinishes) {
  auto p = WaypointPursuit::make({{10, 0}, {10, 10}}, {}, {});
  ASSERT_TRUE(p);
  p->update({0, 0, 0});
  auto out = p->update({9.6, 0.2, 0});  // 0.45 m from (10, 0): within 0.5
  EXPECT_EQ(out.target, 1u);
  EXPECT_EQ(p->next_waypoint(), 1u);
  EXPECT_GT(out.command.curvature_per_m, 0);  // the next leg goes east: turn right
  EXPECT_FALSE(out.finished);
  out = p->update({10.1, 9.7, pi / 2});
  EXPECT_TRUE(out.finished);
  EXPECT_TRUE(p->finished());
  EXPECT_EQ(out.command.speed_mps, 0);
  EXPECT_EQ(out.effort, WrenchEffort{});
  EXPECT_TRUE(p->update({0, 0, 0}).finished);  // and stays finished
}

TEST(WaypointPursuit, APoseThatIsNotFiniteStopsAndChangesNothing) {
  auto p = WaypointPursuit::make({{10, 0}}, {}, {});
  ASSERT_TRUE(p);
  const auto out = p->update({std::nan(""), 0, 0});
  EXPECT_EQ(out.effort, WrenchEffort{});
  EXPECT_FALSE(out.finished);
  EXPECT_EQ(p->update({0, 0, 0}).lookahead, (Point2{1, 0}));  // the first leg still starts at the first real pose
}

TEST(WaypointPursuit, SlowsToStopAtTheLastWaypoint) {
  PursuitConfig config;
  config.travel_speed_mps = 1.0;
  config.max_deceleration_mps2 = 0.5;
  auto p = WaypointPursuit::make({{10, 0}}, config, {});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->update({0, 0, 0}).command.speed_mps, 1.0, 1e-12);
  EXPECT_NEAR(p->update({9, 0, 0}).command.speed_mps, 1.0, 1e-12);  // sqrt(2 * 0.5 * 1)
  EXPECT_NEAR(p->update({9.36, 0, 0}).command.speed_mps, 0.8, 1e-12);
}

}  // namespace
}  // namespace jaus::components::guidance
