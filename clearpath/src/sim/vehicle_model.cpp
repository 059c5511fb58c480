#include "jaus/clearpath/sim/vehicle_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jaus::clearpath::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kJointRate = 1.0;    // rad/s
constexpr double kMountRate = 90.0;   // deg/s
constexpr double kShiftTime = 0.3;    // s a gear change takes

double wrap_angle(double a) { return std::remainder(a, 2 * kPi); }

// Moves value toward target by at most step.
double approach(double value, double target, double step) {
  if (std::abs(target - value) <= step) return target;
  return value + (target > value ? step : -step);
}

}  // namespace

VehicleModel::VehicleModel(VehicleConfig config)
    : config_(config), mounts_(config.mounts), joints_(config.joints), analog_out_(config.analog_outputs, 0) {}

void VehicleModel::touch_watchdog(MotionMode mode, double now) {
  // A command feeds the watchdog even under a stop (the link is alive), but it
  // does not move the wheels then, nor wait to move them once the stop clears.
  last_command_ = now;
  watchdog_expired_ = false;
  if (stop_engaged()) drop_motion();
  else mode_ = mode;
}

// Releasing a stop must never start motion by itself: forget the setpoint,
// so only a command that arrives after the release moves the wheels again.
void VehicleModel::drop_motion() {
  mode_ = MotionMode::none;
  diff_setpoint_ = {};
  output_setpoint_ = {};
  velocity_setpoint_ = {};
  turn_setpoint_ = {};
  ackermann_setpoint_ = {};
}

void VehicleModel::set_safety(std::uint16_t flags) {
  commanded_safety_ = flags;
  if (stop_engaged()) drop_motion();
}

void VehicleModel::set_hardware_input(HardwareInput input, bool on) {
  const auto bit = static_cast<std::uint16_t>(input);
  hardware_inputs_ = static_cast<std::uint16_t>(on ? hardware_inputs_ | bit : hardware_inputs_ & ~bit);
  if (stop_engaged()) drop_motion();
}

void VehicleModel::command_differential_speeds(double left, double right, double left_accel, double right_accel,
                                               double now) {
  diff_setpoint_ = {left, right, left_accel, right_accel};
  touch_watchdog(MotionMode::differential_speeds, now);
}

void VehicleModel::command_differential_output(double left_pct, double right_pct, double now) {
  output_setpoint_ = {left_pct, right_pct};
  touch_watchdog(MotionMode::differential_output, now);
}

void VehicleModel::command_velocity(double translational, double rotational, double accel, double now) {
  velocity_setpoint_ = {translational, rotational, accel};
  touch_watchdog(MotionMode::velocity, now);
}

void VehicleModel::command_turn(double translational, double radius, double accel, double now) {
  turn_setpoint_ = {translational, radius, accel};
  touch_watchdog(MotionMode::turn, now);
}

void VehicleModel::command_ackermann_output(double steering_pct, double throttle_pct, double brake_pct, double now) {
  ackermann_setpoint_ = {steering_pct, throttle_pct, brake_pct};
  touch_watchdog(MotionMode::ackermann_output, now);
}

void VehicleModel::set_gear(std::int8_t gear) {
  if (gear == gear_) return;
  gear_flags_ = gear > gear_ ? 0x02 : 0x01;  // upshifting / downshifting while the shift lasts
  gear_ = gear;
  shift_remaining_ = kShiftTime;
}

void VehicleModel::set_pan_tilt_zoom(std::size_t mount, double pan, double tilt, double zoom) {
  auto& m = mounts_.at(mount);
  m.target_pan = pan;
  m.target_tilt = tilt;
  m.zoom = zoom;
}

bool VehicleModel::configure_encoders(const std::vector<EncoderSetting>& encoders) {
  if (encoders.size() != encoders_.size()) return false;
  for (const auto& e : encoders)
    if (e.ppr <= 0 || e.scale == 0) return false;
  encoders_ = encoders;
  return true;
}

void VehicleModel::set_joint_absolute(std::size_t joint, double angle) {
  joints_.at(joint).target = angle;
  joints_.at(joint).homing_active = false;
}

void VehicleModel::set_joint_relative(std::size_t joint, double delta) {
  auto& j = joints_.at(joint);
  j.relative_target = delta;
  j.target = std::clamp(j.angle + delta, -kPi, kPi);
  j.homing_active = false;
}

void VehicleModel::home_joint(std::size_t joint) {
  auto& j = joints_.at(joint);
  j.homing_active = true;
  j.target = 0;
}

void VehicleModel::set_gpio_direction(std::uint32_t mask, std::uint32_t direction) {
  gpio_direction_ = (gpio_direction_ & ~mask) | (direction & mask);
}

void VehicleModel::set_gpio_output(std::uint32_t mask, std::uint32_t value) {
  gpio_out_ = (gpio_out_ & ~mask) | (value & mask);
}

std::uint16_t VehicleModel::safety_flags() const {
  return static_cast<std::uint16_t>(commanded_safety_ | hardware_inputs_ | (watchdog_expired_ ? kSafetyTimeout : 0));
}

void VehicleModel::wheel_targets(double& left, double& right, double& left_accel, double& right_accel) const {
  const double half_track = config_.track_width / 2;
  const auto from_body = [&](double v, double w, double accel) {
    left = v - w * half_track;
    right = v + w * half_track;
    left_accel = right_accel = accel > 0 ? accel : max_accel_fwd_;
  };
  left = right = 0;
  left_accel = right_accel = max_accel_fwd_;
  switch (mode_) {
    case MotionMode::none:
      break;
    case MotionMode::differential_speeds:
      left = diff_setpoint_[0];
      right = diff_setpoint_[1];
      left_accel = diff_setpoint_[2] > 0 ? diff_setpoint_[2] : max_accel_fwd_;
      right_accel = diff_setpoint_[3] > 0 ? diff_setpoint_[3] : max_accel_fwd_;
      break;
    case MotionMode::differential_output:
      left = output_setpoint_[0] / 100 * max_speed_fwd_;
      right = output_setpoint_[1] / 100 * max_speed_fwd_;
      break;
    case MotionMode::velocity:
      from_body(velocity_setpoint_[0], velocity_setpoint_[1], velocity_setpoint_[2]);
      break;
    case MotionMode::turn: {
      const double radius = turn_setpoint_[1];
      from_body(turn_setpoint_[0], radius == 0 ? 0 : turn_setpoint_[0] / radius, turn_setpoint_[2]);
      break;
    }
    case MotionMode::ackermann_output: {
      // Park and neutral give no drive; reverse gears drive backwards.
      const double direction = gear_ > 0 ? 1.0 : (gear_ < -1 ? -1.0 : 0.0);
      const double v = direction * ackermann_setpoint_[1] / 100 * max_speed_fwd_ * (1 - ackermann_setpoint_[2] / 100);
      const double curvature = std::tan(ackermann_setpoint_[0] / 100 * config_.max_steering_angle) / config_.wheelbase;
      from_body(v, v * curvature, 0);
      break;
    }
  }
}

void VehicleModel::step(double dt, double now) {
  if (dt <= 0) return;
  // Command watchdog: the platform stops by itself when commands stop.
  if (!watchdog_expired_ && now - last_command_ > config_.command_timeout) {
    watchdog_expired_ = true;
    mode_ = MotionMode::none;
  }
  double left_target = 0, right_target = 0, left_accel = max_accel_fwd_, right_accel = max_accel_fwd_;
  // A stop brakes to zero at the platform's acceleration limit (with no rate,
  // the wheels would keep their speed under a stop).
  if (!stop_engaged()) wheel_targets(left_target, right_target, left_accel, right_accel);
  left_target = std::clamp(left_target, -max_speed_rev_, max_speed_fwd_);
  right_target = std::clamp(right_target, -max_speed_rev_, max_speed_fwd_);

  const double v_before = linear_speed();
  left_.speed = approach(left_.speed, left_target, left_accel * dt);
  right_.speed = approach(right_.speed, right_target, right_accel * dt);
  left_.travel += left_.speed * dt;
  right_.travel += right_.speed * dt;

  const double v = linear_speed();
  accel_ = (v - v_before) / dt;
  yaw_rate_ = (right_.speed - left_.speed) / config_.track_width;
  x_ += v * std::cos(yaw_) * dt;
  y_ += v * std::sin(yaw_) * dt;
  yaw_ = wrap_angle(yaw_ + yaw_rate_ * dt);

  current_ = 0.8 + 6.0 * (std::abs(left_.speed) + std::abs(right_.speed));
  charge_ = std::max(0.0, charge_ - current_ * dt * 1e-4);

  if (shift_remaining_ > 0) {
    shift_remaining_ -= dt;
    if (shift_remaining_ <= 0) gear_flags_ = 0;
  }
  for (auto& m : mounts_) {
    m.pan = approach(m.pan, m.target_pan, kMountRate * dt);
    m.tilt = approach(m.tilt, m.target_tilt, kMountRate * dt);
  }
  for (auto& j : joints_) {
    const double error = j.target - j.angle;
    j.torque = std::clamp(j.constants.p * error + j.constants.feed_forward, -320.0, 320.0);
    j.angle = approach(j.angle, j.target, kJointRate * dt);
    if (j.homing_active && j.angle == 0) {
      j.homing_active = false;
      j.homing = 1;  // homed, at home
    } else if (j.homing != 0 && !j.homing_active && j.angle != 0) {
      j.homing = 2;  // homed, moved away
    }
  }
}

std::int32_t VehicleModel::ticks(std::size_t encoder) const {
  const auto& setting = encoders_.at(encoder);
  const double travel = encoder == 0 ? left_.travel : right_.travel;
  return static_cast<std::int32_t>(std::llround(travel / setting.scale * setting.ppr));
}

std::array<double, 6> VehicleModel::end_effector_pose() const {
  constexpr double kUpper = 0.4, kFore = 0.3, kBase = 0.2;
  const auto angle = [&](std::size_t i) { return i < joints_.size() ? joints_[i].angle : 0.0; };
  const double shoulder = angle(1), elbow = angle(2);
  const double reach = kUpper * std::cos(shoulder) + kFore * std::cos(shoulder + elbow);
  const double height = kBase + kUpper * std::sin(shoulder) + kFore * std::sin(shoulder + elbow);
  return {reach * std::cos(angle(0)), reach * std::sin(angle(0)), height,
          wrap_angle(angle(3)), std::clamp(shoulder + elbow + angle(4), -kPi, kPi), wrap_angle(angle(0) + angle(5))};
}

std::uint32_t VehicleModel::gpio_value() const {
  // Outputs read back what was written; inputs read a fixed pattern.
  constexpr std::uint32_t kInputPattern = 0xA5A5A5A5u;
  return (gpio_out_ & gpio_direction_) | (kInputPattern & ~gpio_direction_);
}

std::vector<std::uint16_t> VehicleModel::analog_inputs() const {
  std::vector<std::uint16_t> in(config_.analog_inputs, 0);
  // Channel 0 reads the battery against a 32 V reference; the others loop the outputs back.
  if (!in.empty()) in[0] = static_cast<std::uint16_t>(std::clamp(battery_voltage() / 32.0, 0.0, 1.0) * 0xFFFF);
  for (std::size_t i = 1; i < in.size(); ++i) in[i] = i - 1 < analog_out_.size() ? analog_out_[i - 1] : 0;
  return in;
}

std::vector<double> VehicleModel::ranges() const {
  std::vector<double> r(config_.rangefinders);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = 1.0 + 0.5 * static_cast<double>(i);
  return r;
}

}  // namespace jaus::clearpath::sim
