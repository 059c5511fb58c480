// From what guidance wants (a speed, a turn) to what the primitive driver
// takes (Set Wrench Effort, percent), and the heading and speed loops of the
// vector drivers.
//
// The effort model is the one the simulated vehicle implements
// (components/vehicle/src/simulated_vehicle.cpp) and the primitive driver
// reports in Report Platform Specifications:
// - propulsive linear x: percent of max_speed_mps, either way;
// - propulsive rotational z, positive turning right (heading increasing):
//   differential, percent of max_yaw_rate_rps; Ackermann, percent of
//   max_steering_rad, the front wheels' angle, so the path's curvature is
//   tan(angle) / wheel_base_m whatever the speed (and no turn at rest).
// A driver above the primitive driver sees only the specifications, so
// limits_from() builds these limits from them.
#pragma once

#include "jaus/base/expected.hpp"
#include "jaus/components/drive.hpp"
#include "jaus/components/guidance/pid.hpp"
#include "jaus/components/simulated_vehicle.hpp"  // Steering: the drivetrains

namespace jaus::components::guidance {

struct VehicleLimits {
  Steering steering = Steering::differential;
  double max_speed_mps = 1.0;     // at 100 % linear x
  double max_yaw_rate_rps = 1.0;  // differential: at 100 % rotational z
  double max_steering_rad = 0.5;  // Ackermann: at 100 % rotational z
  double wheel_base_m = 0.5;      // Ackermann

  // Ackermann: the tightest curvature, 1 / minimum turning radius.
  double max_curvature_per_m() const;
};

// All positive and finite (the Ackermann fields only for Ackermann; the
// steering below pi / 2).
Expected<void> validate(const VehicleLimits& limits);

// From Report Platform Specifications: a turning radius with a wheel base
// means Ackermann (max steering = atan(wheel_base / radius)), otherwise
// differential with max_yaw_rate_rps. Needs max_velocity_x_mps, and the yaw
// rate or the radius and wheel base.
Expected<VehicleLimits> limits_from(const PlatformSpecifications& specifications);

// What guidance asks of the vehicle: a speed along body x (negative: reverse)
// and a curvature of its path (1/m, positive turning right). The yaw rate is
// speed * curvature; a differential vehicle may also turn in place, with
// yaw_rate_rps set and speed 0 (then the curvature is not used).
struct MotionCommand {
  double speed_mps = 0;
  double curvature_per_m = 0;
  double yaw_rate_rps = 0;  // differential only; used when the speed is 0
};

// The wrench effort for `command` within the limits: linear x and rotational
// z in -100..100, no brake. Differential: rotational z from speed *
// curvature (or yaw_rate_rps at speed 0); Ackermann: from the curvature's
// steering angle, clamped to the tightest turn. Non-finite values count as 0.
WrenchEffort to_effort(const MotionCommand& command, const VehicleLimits& limits);

// target - current, wrapped to (-pi, pi]: the shortest turn, positive turning
// right (headings from north, clockwise).
double heading_error(double target_rad, double current_rad);

// The heading loop of the vector drivers: a PID on the wrapped heading error
// giving a yaw rate (rad/s), limited to the vehicle's (differential:
// max_yaw_rate_rps; Ackermann: |speed| / minimum turning radius).
class HeadingLoop {
 public:
  // gains.output_min/max are ignored: the limit is the vehicle's yaw rate.
  static Expected<HeadingLoop> make(const PidGains& gains, const VehicleLimits& limits);
  // The yaw rate to command now, for a vehicle at `speed_mps`.
  double update(double target_heading_rad, double heading_rad, double speed_mps, double dt_s);
  // The whole command: the effort that holds `speed_mps` and turns towards the target.
  WrenchEffort effort(double target_heading_rad, double heading_rad, double speed_mps, double dt_s);
  void reset() { pid_.reset(); }

 private:
  HeadingLoop(Pid pid, const VehicleLimits& limits) : pid_(pid), limits_(limits) {}
  Pid pid_;
  VehicleLimits limits_;
};

// The speed loop: feedforward (the effort that gives target speed on an
// ideal drive: target / max_speed) plus a PI correction, in percent, so a
// drive that under-delivers (load, a slope, a real motor) still reaches the
// target; the simulated vehicle needs only the feedforward.
class SpeedLoop {
 public:
  // gains are in percent per m/s of error; output limits are ignored (the
  // correction is limited to -100..100 % and so is the sum).
  static Expected<SpeedLoop> make(const PidGains& gains, const VehicleLimits& limits);
  // Linear x effort, percent.
  double update(double target_speed_mps, double speed_mps, double dt_s);
  void reset() { pid_.reset(); }

 private:
  SpeedLoop(Pid pid, const VehicleLimits& limits) : pid_(pid), limits_(limits) {}
  Pid pid_;
  VehicleLimits limits_;
};

}  // namespace jaus::components::guidance
