#include "jaus/components/guidance/pursuit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "argument_checks.hpp"

namespace jaus::components::guidance {

using detail::bad;
using detail::positive;

namespace {

// `p` in the body frame of `pose`: (ahead, right).
Point2 to_body(const Pose2& pose, const Point2& p) {
  const double dx = p.x_m - pose.x_m, dy = p.y_m - pose.y_m;
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  return {c * dx + s * dy, -s * dx + c * dy};
}

}  // namespace

double distance(const Point2& a, const Point2& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

double pursuit_curvature(const Pose2& pose, const Point2& target) {
  const Point2 body = to_body(pose, target);
  const double d2 = body.x_m * body.x_m + body.y_m * body.y_m;
  if (!(d2 > 1e-12)) return 0;
  if (body.x_m < 0 && std::abs(body.y_m) < 1e-9) return 2 / std::sqrt(d2);  // straight behind: turn right round
  return 2 * body.y_m / d2;
}

Expected<void> validate(const PursuitConfig& c) {
  if (!positive(c.lookahead_m)) return unexpected(bad("lookahead must be positive"));
  if (!positive(c.arrival_tolerance_m)) return unexpected(bad("arrival tolerance must be positive"));
  if (!positive(c.travel_speed_mps)) return unexpected(bad("travel speed must be positive"));
  if (!positive(c.max_deceleration_mps2)) return unexpected(bad("deceleration must be positive"));
  if (!std::isfinite(c.min_speed_mps) || c.min_speed_mps < 0) return unexpected(bad("min speed must not be negative"));
  return {};
}

MotionCommand shape_command(double curvature, double heading_error_rad, double speed_limit_mps,
                            const PursuitConfig& config, const VehicleLimits& limits) {
  MotionCommand c;
  if (!std::isfinite(curvature)) curvature = 0;
  if (!std::isfinite(heading_error_rad)) heading_error_rad = 0;
  double speed = std::clamp(std::isfinite(speed_limit_mps) ? speed_limit_mps : 0.0, 0.0, limits.max_speed_mps);
  const double alignment = std::cos(heading_error_rad);  // 1 straight at it, <= 0 beside or behind

  if (limits.steering == Steering::ackermann) {
    const double k_max = limits.max_curvature_per_m();
    // Behind, the pursuit arc is a poor guide (a point straight behind
    // gives a straight line): turn round at full lock towards its side,
    // unless it lies inside that tightest turning circle (a curvature beyond
    // the limit), which turning would only circle for ever: then drive
    // straight on until it is outside.
    if (alignment < 0) {
      curvature = std::abs(curvature) > k_max ? 0.0 : (heading_error_rad >= 0 ? k_max : -k_max);
    }
    c.curvature_per_m = std::clamp(curvature, -k_max, k_max);
    if (speed > 0) speed = std::max(speed * std::max(alignment, 0.0), std::min(config.min_speed_mps, speed));
    c.speed_mps = speed;
    c.yaw_rate_rps = speed * c.curvature_per_m;
    return c;
  }

  if (alignment <= 0) {  // beside or behind: turn in place, as fast as it may
    c.speed_mps = 0;
    c.curvature_per_m = 0;
    const double toward = heading_error_rad >= 0 ? 1.0 : -1.0;
    c.yaw_rate_rps = toward * limits.max_yaw_rate_rps * std::min(1.0, std::abs(heading_error_rad));
    return c;
  }
  speed *= alignment;
  if (std::abs(curvature) * speed > limits.max_yaw_rate_rps) speed = limits.max_yaw_rate_rps / std::abs(curvature);
  c.speed_mps = speed;
  c.curvature_per_m = curvature;
  c.yaw_rate_rps = speed * curvature;
  return c;
}

Expected<WaypointPursuit> WaypointPursuit::make(std::vector<Point2> waypoints, const PursuitConfig& config,
                                                const VehicleLimits& limits) {
  if (auto ok = validate(config); !ok) return unexpected(ok.error());
  if (auto ok = validate(limits); !ok) return unexpected(ok.error());
  if (waypoints.empty()) return unexpected(bad("no waypoints"));
  for (const auto& w : waypoints) {
    if (!std::isfinite(w.x_m) || !std::isfinite(w.y_m)) return unexpected(bad("a waypoint is not finite"));
  }
  return WaypointPursuit(std::move(waypoints), config, limits);
}

PursuitOutput WaypointPursuit::update(const Pose2& pose) {
  PursuitOutput out;
  if (!std::isfinite(pose.x_m) || !std::isfinite(pose.y_m) || !std::isfinite(pose.yaw_rad)) {
    out.target = next_;
    out.finished = finished();
    return out;  // no pose to steer by: stop, and keep the list where it is
  }
  const Point2 here = pose.position();
  if (!leg_start_) leg_start_ = here;
  // Reached waypoints, possibly several at once (two within the tolerance of each other).
  while (next_ < waypoints_.size() && distance(here, waypoints_[next_]) <= config_.arrival_tolerance_m) {
    leg_start_ = waypoints_[next_];
    ++next_;
  }
  out.target = next_;
  if (finished()) {
    out.finished = true;
    out.lookahead = waypoints_.back();
    return out;
  }

  const Point2 a = *leg_start_, b = waypoints_[next_];
  const double length = distance(a, b);
  double along = 0;
  Point2 lookahead = b;
  if (length > 1e-9) {
    const double ux = (b.x_m - a.x_m) / length, uy = (b.y_m - a.y_m) / length;
    const double dx = here.x_m - a.x_m, dy = here.y_m - a.y_m;
    along = std::clamp(dx * ux + dy * uy, 0.0, length);
    out.cross_track_m = ux * dy - uy * dx;  // right of the leg positive (x north, y east)
    const double ahead = std::min(along + config_.lookahead_m, length);
    lookahead = {a.x_m + ux * ahead, a.y_m + uy * ahead};
  }
  out.lookahead = lookahead;

  // Slow to stop at the last waypoint: v^2 = 2 a d.
  double speed = std::min(config_.travel_speed_mps, limits_.max_speed_mps);
  if (next_ + 1 == waypoints_.size()) {
    speed = std::min(speed, std::sqrt(2 * config_.max_deceleration_mps2 * distance(here, b)));
  }
  const Point2 body = to_body(pose, lookahead);
  const double bearing_error = std::atan2(body.y_m, body.x_m);
  out.command = shape_command(pursuit_curvature(pose, lookahead), bearing_error, speed, config_, limits_);
  out.effort = to_effort(out.command, limits_);
  return out;
}

}  // namespace jaus::components::guidance
