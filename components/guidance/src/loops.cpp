#include "jaus/components/guidance/loops.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "jaus/components/navigation_frames.hpp"

#include "argument_checks.hpp"

namespace jaus::components::guidance {

using detail::bad;
using detail::positive;

namespace {

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0; }

}  // namespace

double VehicleLimits::max_curvature_per_m() const {
  if (!(wheel_base_m > 0)) return 0;
  return std::tan(max_steering_rad) / wheel_base_m;
}

Expected<void> validate(const VehicleLimits& l) {
  if (!positive(l.max_speed_mps)) return unexpected(bad("max speed must be positive"));
  if (l.steering == Steering::differential) {
    if (!positive(l.max_yaw_rate_rps)) return unexpected(bad("max yaw rate must be positive"));
  } else {
    if (!positive(l.wheel_base_m)) return unexpected(bad("wheel base must be positive"));
    if (!positive(l.max_steering_rad) || l.max_steering_rad >= std::numbers::pi / 2) {
      return unexpected(bad("max steering must be in (0, pi/2)"));
    }
  }
  return {};
}

Expected<VehicleLimits> limits_from(const PlatformSpecifications& s) {
  VehicleLimits l;
  if (!s.max_velocity_x_mps) return unexpected(bad("the platform reports no maximum speed"));
  l.max_speed_mps = *s.max_velocity_x_mps;
  if (s.turning_radius_m && s.wheel_base_m) {
    l.steering = Steering::ackermann;
    l.wheel_base_m = *s.wheel_base_m;
    l.max_steering_rad = positive(*s.turning_radius_m) ? std::atan(l.wheel_base_m / *s.turning_radius_m) : 0;
  } else if (s.max_yaw_rate_rps) {
    l.max_yaw_rate_rps = *s.max_yaw_rate_rps;
  } else {
    return unexpected(bad("the platform reports neither a yaw rate nor a turning radius"));
  }
  if (auto ok = validate(l); !ok) return unexpected(ok.error());
  return l;
}

WrenchEffort to_effort(const MotionCommand& c, const VehicleLimits& l) {
  const double speed = finite_or_zero(c.speed_mps);
  const double curvature = finite_or_zero(c.curvature_per_m);
  WrenchEffort e;
  if (positive(l.max_speed_mps)) e.propulsive_linear.x = std::clamp(100 * speed / l.max_speed_mps, -100.0, 100.0);
  if (l.steering == Steering::differential) {
    const double rate = speed != 0 ? speed * curvature : finite_or_zero(c.yaw_rate_rps);
    if (positive(l.max_yaw_rate_rps)) {
      e.propulsive_rotational.z = std::clamp(100 * rate / l.max_yaw_rate_rps, -100.0, 100.0);
    }
  } else if (positive(l.max_steering_rad) && positive(l.wheel_base_m)) {
    const double angle = std::atan(curvature * l.wheel_base_m);
    e.propulsive_rotational.z = std::clamp(100 * angle / l.max_steering_rad, -100.0, 100.0);
  }
  return e;
}

double heading_error(double target_rad, double current_rad) {
  return wrap_angle(finite_or_zero(target_rad) - finite_or_zero(current_rad));
}

Expected<HeadingLoop> HeadingLoop::make(const PidGains& gains, const VehicleLimits& limits) {
  if (auto ok = validate(limits); !ok) return unexpected(ok.error());
  PidGains g = gains;
  // The PID's own limit is the fastest turn the vehicle has at full speed;
  // update() narrows it to the present speed for Ackermann.
  const double rate = limits.steering == Steering::differential
                          ? limits.max_yaw_rate_rps
                          : limits.max_speed_mps * limits.max_curvature_per_m();
  g.output_min = -rate;
  g.output_max = rate;
  auto pid = Pid::make(g);
  if (!pid) return unexpected(pid.error());
  return HeadingLoop(*pid, limits);
}

double HeadingLoop::update(double target_heading_rad, double heading_rad, double speed_mps, double dt_s) {
  const double rate = pid_.update(heading_error(target_heading_rad, heading_rad), dt_s);
  if (limits_.steering == Steering::differential) return rate;
  const double reachable = std::abs(finite_or_zero(speed_mps)) * limits_.max_curvature_per_m();
  return std::clamp(rate, -reachable, reachable);
}

WrenchEffort HeadingLoop::effort(double target_heading_rad, double heading_rad, double speed_mps, double dt_s) {
  const double rate = update(target_heading_rad, heading_rad, speed_mps, dt_s);
  MotionCommand c;
  c.speed_mps = speed_mps;
  c.yaw_rate_rps = rate;
  // Ackermann steers a curvature; reversing, the same curvature turns the other way.
  if (speed_mps != 0 && std::isfinite(speed_mps)) c.curvature_per_m = rate / speed_mps;
  return to_effort(c, limits_);
}

Expected<SpeedLoop> SpeedLoop::make(const PidGains& gains, const VehicleLimits& limits) {
  if (auto ok = validate(limits); !ok) return unexpected(ok.error());
  PidGains g = gains;
  g.output_min = -100;
  g.output_max = 100;
  auto pid = Pid::make(g);
  if (!pid) return unexpected(pid.error());
  return SpeedLoop(*pid, limits);
}

double SpeedLoop::update(double target_speed_mps, double speed_mps, double dt_s) {
  const double target = finite_or_zero(target_speed_mps);
  const double feedforward = 100 * target / limits_.max_speed_mps;
  // The correction's room is what the feedforward leaves of -100..100 %.
  const double error = target - finite_or_zero(speed_mps);
  const double correction = pid_.update(error, dt_s, -100 - feedforward, 100 - feedforward);
  return std::clamp(feedforward + correction, -100.0, 100.0);
}

}  // namespace jaus::components::guidance
