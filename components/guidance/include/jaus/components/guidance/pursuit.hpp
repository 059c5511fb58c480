// Pure pursuit: steer along the arc that reaches a point on the route a
// lookahead distance ahead. The waypoint drivers use WaypointPursuit; the
// path segment drivers use the same law on a curve (path_segment.hpp).
//
// Frames: the local frame of components/vehicle (local_frame.hpp): x north,
// y east, metres; yaw is the heading from north, clockwise (JAUS's). In the
// body frame (x forward, y right) a point at (ahead, right) at distance d
// lies on the arc of curvature 2 * right / d^2, positive turning right, the
// sign of the primitive driver's rotational z.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/guidance/loops.hpp"

namespace jaus::components::guidance {

struct Point2 {
  double x_m = 0, y_m = 0;  // north, east
  bool operator==(const Point2&) const = default;
};

struct Pose2 {
  double x_m = 0, y_m = 0;  // north, east
  double yaw_rad = 0;       // heading from north, clockwise
  Point2 position() const { return {x_m, y_m}; }
};

double distance(const Point2& a, const Point2& b);

// The curvature of the arc from `pose` (tangent to its heading) through
// `target`; 0 when the target is the vehicle's position. A target behind
// gives the tightest arc there is through it (the vehicle turns round).
double pursuit_curvature(const Pose2& pose, const Point2& target);

struct PursuitConfig {
  double lookahead_m = 1.0;          // the pursuit distance along the route
  double arrival_tolerance_m = 0.5;  // a waypoint (or the path's end) within this is reached
  double travel_speed_mps = 0.5;     // Set Travel Speed; limited by the vehicle's max speed
  double max_deceleration_mps2 = 0.5;  // slowing to stop at the last waypoint
  double min_speed_mps = 0.1;          // Ackermann: the slowest it drives while turning (it cannot turn at rest)
};

// Positive and finite (min_speed_mps may be 0 for a differential vehicle).
Expected<void> validate(const PursuitConfig& config);

// The command that follows `curvature` within the vehicle's limits at up to
// `speed_limit_mps`:
// - Ackermann: the curvature is clamped to the tightest turn; the speed is
//   slowed with the heading error to the target (cos of it, not below
//   min_speed_mps) so a sharp corner is taken slowly but always moving. A
//   target behind it is turned to at full lock, or, inside its tightest
//   turning circle (a curvature beyond the limit), driven away from in a
//   straight line until it is outside: turning would only circle it.
// - Differential: the speed is slowed so speed * curvature stays within the
//   maximum yaw rate (the arc is kept, only slower), and with the heading
//   error; past 90 degrees it turns in place towards the target.
MotionCommand shape_command(double curvature, double heading_error_rad, double speed_limit_mps,
                            const PursuitConfig& config, const VehicleLimits& limits);

struct PursuitOutput {
  MotionCommand command;        // all zero once finished
  WrenchEffort effort;          // the command as Set Wrench Effort
  Point2 lookahead;             // where it steers to
  std::size_t target = 0;       // the waypoint (or segment) being driven to
  double cross_track_m = 0;     // from the route, positive to the right of it
  bool finished = false;        // the last waypoint (or the end) is reached
};

// Drives through a list of waypoints in order. Each leg runs from the
// previous waypoint (for the first, from where the vehicle was at its first
// update) to the next; the lookahead point is the vehicle's projection on the
// leg moved lookahead_m along it, never past the waypoint, so every waypoint
// is driven at and reached within arrival_tolerance_m (corners are not cut).
// Reaching the last one finishes: the command is zero from then on.
class WaypointPursuit {
 public:
  // Errors: an invalid config or limits, or no waypoints.
  static Expected<WaypointPursuit> make(std::vector<Point2> waypoints, const PursuitConfig& config,
                                        const VehicleLimits& limits);

  // The command for the vehicle at `pose` now. Stateless in time: the pursuit
  // law has no memory but which waypoint is next. A pose that is not finite
  // (a failed sensor) gives the zero command and changes nothing.
  PursuitOutput update(const Pose2& pose);

  std::size_t next_waypoint() const { return next_; }
  bool finished() const { return next_ >= waypoints_.size(); }
  const std::vector<Point2>& waypoints() const { return waypoints_; }
  // A new travel speed (Set Travel Speed) from the next update on.
  void set_travel_speed(double mps) { config_.travel_speed_mps = mps; }

 private:
  WaypointPursuit(std::vector<Point2> waypoints, const PursuitConfig& config, const VehicleLimits& limits)
      : waypoints_(std::move(waypoints)), config_(config), limits_(limits) {}
  std::vector<Point2> waypoints_;
  PursuitConfig config_;
  VehicleLimits limits_;
  std::optional<Point2> leg_start_;
  std::size_t next_ = 0;
};

}  // namespace jaus::components::guidance
