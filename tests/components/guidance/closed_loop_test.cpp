// Guidance closing the loop on the simulated vehicle under virtual time, as
// the waypoint and path segment drivers will: read the pose, update, apply
// the effort, let 50 ms pass. Both drivetrains; the limits come from the
// vehicle's Report Platform Specifications, as a driver would get them.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/components/guidance/path_segment.hpp"
#include "jaus/components/guidance/pursuit.hpp"
#include "jaus/components/simulated_vehicle.hpp"

namespace jaus::components::guidance {
namespace {

using namespace std::chrono_literals;

constexpr auto kControlPeriod = 50ms;
constexpr int kMaxSteps = 3000;  // 150 s of virtual time: a bound, not the expected duration

SimulatedVehicleConfig vehicle_config(Steering steering) {
  SimulatedVehicleConfig c;
  c.steering = steering;  // defaults: 1 m/s, 1 rad/s; Ackermann 0.5 rad on 0.5 m (turning radius 0.92 m)
  return c;
}

Pose2 pose_of(SimulatedVehicle& vehicle) {
  const auto s = *vehicle.sample();
  return {s.local_position->x_m, s.local_position->y_m, s.attitude->yaw};
}

PursuitConfig pursuit_config() {
  PursuitConfig c;
  c.lookahead_m = 1.5;
  c.arrival_tolerance_m = 0.5;
  c.travel_speed_mps = 0.8;
  c.max_deceleration_mps2 = 0.5;
  c.min_speed_mps = 0.2;
  return c;
}

class ClosedLoop : public ::testing::TestWithParam<Steering> {
 protected:
  rt::VirtualTime time;
  SimulatedVehicle vehicle{vehicle_config(GetParam()), time};

  VehicleLimits limits() {
    auto l = limits_from(vehicle.specifications());
    EXPECT_TRUE(l);
    EXPECT_EQ(l->steering, GetParam());
    return *l;
  }
};

TEST_P(ClosedLoop, ASquareOfFourWaypointsIsDrivenInOrderEachWithinTheTolerance) {
  const std::vector<Point2> square{{10, 0}, {10, 10}, {0, 10}, {0, 0}};
  const PursuitConfig config = pursuit_config();
  auto pursuit = WaypointPursuit::make(square, config, limits());
  ASSERT_TRUE(pursuit);

  std::vector<double> closest(square.size(), 1e9);  // the true nearest approach to each
  std::vector<std::size_t> order;                   // the waypoints, as reached
  int steps = 0;
  for (; steps < kMaxSteps && !pursuit->finished(); ++steps) {
    const Pose2 pose = pose_of(vehicle);
    for (std::size_t i = 0; i < square.size(); ++i) {
      closest[i] = std::min(closest[i], distance(pose.position(), square[i]));
    }
    const std::size_t before = pursuit->next_waypoint();
    const auto out = pursuit->update(pose);
    for (std::size_t i = before; i < pursuit->next_waypoint(); ++i) {
      order.push_back(i);
      EXPECT_LE(distance(pose.position(), square[i]), config.arrival_tolerance_m) << "waypoint " << i;
    }
    vehicle.apply_effort(out.effort);
    time.advance(kControlPeriod);
  }
  ASSERT_TRUE(pursuit->finished()) << "after " << steps << " steps";
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3}));
  for (std::size_t i = 0; i < square.size(); ++i) EXPECT_LE(closest[i], config.arrival_tolerance_m) << "waypoint " << i;

  // Finished, the command is zero: the vehicle comes to rest near the last waypoint.
  vehicle.apply_effort(pursuit->update(pose_of(vehicle)).effort);
  time.advance(3s);
  EXPECT_EQ(vehicle.speed_mps(), 0);
  EXPECT_LT(distance(pose_of(vehicle).position(), square.back()), 1.0);
  EXPECT_LT(steps * kControlPeriod, 90s);  // 40 m at 0.8 m/s with four turns
}

TEST_P(ClosedLoop, AThreeSegmentPathIsFollowedWithinTheStatedCrossTrackError) {
  // North 10 m; a right-hand curve (quadratic Bezier, w = 1) to heading east;
  // a second right-hand curve (w = 0.7) round to heading south. Each joint is
  // smooth: each P1 continues the previous arrival direction.
  const std::vector<SegmentSpec> segments{
      {{5, 0}, {10, 0}, 0}, {{13, 0}, {13, 3}, 1.0}, {{13, 6}, {9, 6}, 0.7}};
  auto path = Path::make(pose_of(vehicle).position(), segments);
  ASSERT_TRUE(path);
  const PursuitConfig config = pursuit_config();
  auto pursuit = PathPursuit::make(*path, config, limits());
  ASSERT_TRUE(pursuit);

  constexpr double kMaxCrossTrack_m = 0.2;  // the stated bound, both drivetrains (measured: 0.08 m)
  double max_cross_track = 0, sum = 0;
  int steps = 0;
  for (; steps < kMaxSteps && !pursuit->finished(); ++steps) {
    const Pose2 pose = pose_of(vehicle);
    const double cross = std::abs(path->project(pose.position()).cross_track_m);  // independent of the pursuit's window
    max_cross_track = std::max(max_cross_track, cross);
    sum += cross;
    vehicle.apply_effort(pursuit->update(pose).effort);
    time.advance(kControlPeriod);
  }
  ASSERT_TRUE(pursuit->finished()) << "after " << steps << " steps";
  EXPECT_LE(distance(pose_of(vehicle).position(), path->end()), config.arrival_tolerance_m + 0.1);
  EXPECT_LT(max_cross_track, kMaxCrossTrack_m);
  RecordProperty("max_cross_track_mm", static_cast<int>(max_cross_track * 1000));
  RecordProperty("mean_cross_track_mm", static_cast<int>(sum / steps * 1000));
  std::printf("cross-track: max %.3f m, mean %.3f m over %d steps\n", max_cross_track, sum / steps, steps);
}

TEST_P(ClosedLoop, AWaypointBehindTheVehicleIsStillReached) {
  auto pursuit = WaypointPursuit::make({{-4, 0}}, pursuit_config(), limits());
  ASSERT_TRUE(pursuit);
  int steps = 0;
  for (; steps < kMaxSteps && !pursuit->finished(); ++steps) {
    vehicle.apply_effort(pursuit->update(pose_of(vehicle)).effort);
    time.advance(kControlPeriod);
  }
  EXPECT_TRUE(pursuit->finished());
  EXPECT_LT(steps * kControlPeriod, 40s);
}

TEST_P(ClosedLoop, TheHeadingAndSpeedLoopsTurnRoundAndHoldTheNewHeading) {
  // A vector driver's command: heading 135 degrees (south-east, a right turn) at 0.6 m/s.
  constexpr double kTarget = 3 * std::numbers::pi / 4;
  auto heading = HeadingLoop::make({1.5, 0.2, 0}, limits());
  auto speed = SpeedLoop::make({20, 10, 0}, limits());
  ASSERT_TRUE(heading && speed);
  double worst_overshoot = 0;
  for (int step = 0; step < 400; ++step) {  // 20 s
    const auto s = *vehicle.sample();
    const double yaw = s.attitude->yaw, v = s.velocity_mps->x;
    worst_overshoot = std::max(worst_overshoot, heading_error(yaw, kTarget));  // past the target: positive
    WrenchEffort e = heading->effort(kTarget, yaw, v, 0.05);
    e.propulsive_linear.x = speed->update(0.6, v, 0.05);
    if (GetParam() == Steering::ackermann) {
      // Steering needs speed: the rotational effort is for the present speed, the linear one sets the next.
      e.propulsive_rotational.z = heading->effort(kTarget, yaw, std::max(v, 0.1), 0).propulsive_rotational.z;
    }
    vehicle.apply_effort(e);
    time.advance(kControlPeriod);
  }
  EXPECT_NEAR(heading_error(kTarget, vehicle.heading_rad()), 0, 0.02);
  EXPECT_NEAR(vehicle.speed_mps(), 0.6, 0.01);
  EXPECT_LT(worst_overshoot, 0.1);  // rad
}

TEST(ClosedLoopAckermann, ACurveTighterThanTheTurningRadiusIsFollowedAsCloselyAsTheTurnAllows) {
  rt::VirtualTime time;
  SimulatedVehicleConfig config = vehicle_config(Steering::ackermann);
  config.wheel_base_m = 0.8;
  config.max_steering_rad = 0.3;  // turning radius 2.58 m; the path's curves bend at 2.1 m
  SimulatedVehicle vehicle(config, time);
  auto limits = limits_from(vehicle.specifications());
  ASSERT_TRUE(limits);
  EXPECT_NEAR(1 / limits->max_curvature_per_m(), 0.8 / std::tan(0.3), 1e-9);
  auto path = Path::make({0, 0}, {{{5, 0}, {10, 0}, 0}, {{13, 0}, {13, 3}, 1.0}, {{13, 6}, {9, 6}, 0.7}});
  ASSERT_TRUE(path);
  auto pursuit = PathPursuit::make(*path, pursuit_config(), *limits);
  ASSERT_TRUE(pursuit);
  double max_cross_track = 0;
  int steps = 0;
  for (; steps < kMaxSteps && !pursuit->finished(); ++steps) {
    const Pose2 pose = pose_of(vehicle);
    max_cross_track = std::max(max_cross_track, std::abs(path->project(pose.position()).cross_track_m));
    vehicle.apply_effort(pursuit->update(pose).effort);
    time.advance(kControlPeriod);
  }
  ASSERT_TRUE(pursuit->finished());
  std::printf("wide Ackermann cross-track: max %.3f m over %d steps\n", max_cross_track, steps);
  EXPECT_LT(max_cross_track, 0.3);  // measured: 0.08 m; the pursuit cuts inside the bends, which eases them
}

INSTANTIATE_TEST_SUITE_P(BothDrivetrains, ClosedLoop, ::testing::Values(Steering::differential, Steering::ackermann),
                         [](const ::testing::TestParamInfo<Steering>& tested) {
                           return tested.param == Steering::differential ? std::string("Differential")
                                                                       : std::string("Ackermann");
                         });

}  // namespace
}  // namespace jaus::components::guidance
