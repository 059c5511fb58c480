// The simulated Clearpath vehicle: drivetrain with acceleration limits,
// encoders, odometry, IMU, magnetometer, power, safety and command watchdog,
// gear, pan/tilt/zoom mounts, manipulator, GPIO and analog channels.
// Pure state + step(dt): no clock, no I/O, so tests drive it in virtual time.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "jaus/clearpath/message_records.hpp"

namespace jaus::clearpath::sim {

enum class Drive { differential, ackermann };

// Husky safety flags (platform specific, from the protocol notes).
inline constexpr std::uint16_t kSafetyTimeout = 0x01;
inline constexpr std::uint16_t kSafetyLockout = 0x02;
inline constexpr std::uint16_t kSafetyEmergencyStop = 0x08;
inline constexpr std::uint16_t kSafetyPause = 0x10;
// The bits that stop the wheels, wherever they come from.
inline constexpr std::uint16_t kSafetyStopBits = kSafetyEmergencyStop | kSafetyLockout | kSafetyPause;

// Physical inputs of the platform (the e-stop button, the pause/remote-stop
// input), each reported as its own safety bit. Set Safety System cannot clear them.
enum class HardwareInput : std::uint16_t { estop = kSafetyEmergencyStop, pause = kSafetyPause };

struct VehicleConfig {
  Drive drive = Drive::differential;
  double track_width = 0.55;       // m
  double wheelbase = 0.5;          // m (Ackermann)
  double max_steering_angle = 0.5; // rad at 100 % steering
  double command_timeout = 0.5;    // s without a motion command -> stop
  std::size_t joints = 6;
  std::size_t mounts = 2;
  std::size_t analog_outputs = 4;
  std::size_t analog_inputs = 4;
  std::size_t rangefinders = 4;
};

struct Wheel {
  double speed = 0;   // m/s
  double travel = 0;  // m
};

struct Mount {
  double pan = 0, tilt = 0, zoom = 1;
  double target_pan = 0, target_tilt = 0;
};

struct Joint {
  double angle = 0, target = 0, torque = 0;  // rad, rad, N-m
  double relative_target = 0;
  std::uint8_t homing = 0;  // JointHomingData status
  bool homing_active = false;
  JointControlConstants constants{5.0, 0, 0, 0, 0, 10.0};
};

// What was last commanded, in the command's own terms.
enum class MotionMode { none, differential_speeds, differential_output, velocity, turn, ackermann_output };

class VehicleModel {
 public:
  explicit VehicleModel(VehicleConfig config = {});

  const VehicleConfig& config() const { return config_; }

  // ---- commands (already range-checked by the platform) ------------------
  void command_differential_speeds(double left, double right, double left_accel, double right_accel, double now);
  void command_differential_output(double left_pct, double right_pct, double now);
  void command_velocity(double translational, double rotational, double accel, double now);
  void command_turn(double translational, double radius, double accel, double now);
  void command_ackermann_output(double steering_pct, double throttle_pct, double brake_pct, double now);
  void set_gear(std::int8_t gear);
  // The software word of Set Safety System (0x0010): replaced whole, never
  // touching the hardware inputs. Setting a stop bit drops the motion setpoint.
  void set_safety(std::uint16_t flags);
  void set_hardware_input(HardwareInput input, bool on);
  void set_max_speed(double forward, double reverse) { max_speed_fwd_ = forward; max_speed_rev_ = reverse; }
  void set_max_accel(double forward, double reverse) { max_accel_fwd_ = forward; max_accel_rev_ = reverse; }
  void set_pan_tilt_zoom(std::size_t mount, double pan, double tilt, double zoom);
  bool configure_encoders(const std::vector<EncoderSetting>& encoders);
  void set_joint_absolute(std::size_t joint, double angle);
  void set_joint_relative(std::size_t joint, double delta);
  void set_joint_constants(std::size_t joint, const JointControlConstants& c) { joints_.at(joint).constants = c; }
  void home_joint(std::size_t joint);
  void set_gpio_direction(std::uint32_t mask, std::uint32_t direction);
  void set_gpio_output(std::uint32_t mask, std::uint32_t value);
  void set_analog_output(std::size_t channel, std::uint16_t value) { analog_out_.at(channel) = value; }

  // Advance the simulation; now is seconds since start (for the watchdog).
  void step(double dt, double now);

  // ---- state ---------------------------------------------------------------
  const Wheel& left() const { return left_; }
  const Wheel& right() const { return right_; }
  double linear_speed() const { return (left_.speed + right_.speed) / 2; }
  double yaw_rate() const { return yaw_rate_; }  // rad/s, right-handed (left turn positive)
  double yaw() const { return yaw_; }            // rad, right-handed, wrapped to [-pi, pi]
  double x() const { return x_; }
  double y() const { return y_; }
  double longitudinal_accel() const { return accel_; }
  // What Safety Status (0x8010) reports: commanded | hardware inputs | watchdog timeout.
  std::uint16_t safety_flags() const;
  std::uint16_t commanded_safety() const { return commanded_safety_; }
  std::uint16_t hardware_inputs() const { return hardware_inputs_; }
  // A stop bit is set (commanded or hardware): the wheels decelerate to zero.
  bool stop_engaged() const { return ((commanded_safety_ | hardware_inputs_) & kSafetyStopBits) != 0; }
  bool watchdog_expired() const { return watchdog_expired_; }
  double battery_charge() const { return charge_; }  // %
  double battery_voltage() const { return 24.0 + 4.0 * charge_ / 100.0 - 0.1 * std::abs(current_); }
  double battery_current() const { return current_; }
  double max_speed_forward() const { return max_speed_fwd_; }
  double max_speed_reverse() const { return max_speed_rev_; }
  double max_accel_forward() const { return max_accel_fwd_; }
  double max_accel_reverse() const { return max_accel_rev_; }
  MotionMode mode() const { return mode_; }
  // Last command of each kind, for the setpoint data messages.
  std::array<double, 4> differential_speeds_setpoint() const { return diff_setpoint_; }
  std::array<double, 2> differential_output() const { return output_setpoint_; }
  std::array<double, 3> velocity_setpoint() const { return velocity_setpoint_; }
  std::array<double, 3> turn_setpoint() const { return turn_setpoint_; }
  std::array<double, 3> ackermann_output() const { return ackermann_setpoint_; }
  std::int8_t gear() const { return gear_; }
  std::uint8_t gear_flags() const { return gear_flags_; }
  const std::vector<EncoderSetting>& encoder_settings() const { return encoders_; }
  std::int32_t ticks(std::size_t encoder) const;
  const std::vector<Mount>& mounts() const { return mounts_; }
  const std::vector<Joint>& joints() const { return joints_; }
  // End effector of a 3-link arm (yaw base, shoulder, elbow) with a 3-axis wrist.
  std::array<double, 6> end_effector_pose() const;
  std::uint32_t gpio_direction() const { return gpio_direction_; }
  std::uint32_t gpio_value() const;
  const std::vector<std::uint16_t>& analog_outputs() const { return analog_out_; }
  std::vector<std::uint16_t> analog_inputs() const;
  std::vector<double> ranges() const;

 private:
  void touch_watchdog(MotionMode mode, double now);
  void drop_motion();
  void wheel_targets(double& left, double& right, double& left_accel, double& right_accel) const;

  VehicleConfig config_;
  Wheel left_, right_;
  double x_ = 0, y_ = 0, yaw_ = 0, yaw_rate_ = 0, accel_ = 0;
  double max_speed_fwd_ = 1.0, max_speed_rev_ = 1.0;
  double max_accel_fwd_ = 2.0, max_accel_rev_ = 2.0;
  MotionMode mode_ = MotionMode::none;
  double last_command_ = -1e9;
  bool watchdog_expired_ = true;
  std::uint16_t commanded_safety_ = 0;
  std::uint16_t hardware_inputs_ = 0;
  std::array<double, 4> diff_setpoint_{};
  std::array<double, 2> output_setpoint_{};
  std::array<double, 3> velocity_setpoint_{};
  std::array<double, 3> turn_setpoint_{};
  std::array<double, 3> ackermann_setpoint_{};
  std::int8_t gear_ = 1;
  std::uint8_t gear_flags_ = 0;
  double shift_remaining_ = 0;
  double charge_ = 95.0, current_ = 0;
  std::vector<EncoderSetting> encoders_{{1000, 0.1}, {1000, 0.1}};
  std::vector<Mount> mounts_;
  std::vector<Joint> joints_;
  std::uint32_t gpio_direction_ = 0, gpio_out_ = 0;
  std::vector<std::uint16_t> analog_out_;
};

}  // namespace jaus::clearpath::sim
