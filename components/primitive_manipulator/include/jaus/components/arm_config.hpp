// What a node's configuration says of the arm of the primitive manipulator
// (jausd.yaml `manipulator:`; docs/configuration.md): its joints, in the
// Denavit-Hartenberg terms of Report Manipulator Specifications, and where
// its base is on the platform. The simulated arm is built from it; the
// component reports it and checks commands against its limits.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::components {

struct JointConfig {
  std::string name;        // for logs and errors ("joint 3 (elbow)")
  bool prismatic = false;  // revolute otherwise
  // The link after this joint and the joint's fixed parameter, as Part 3's
  // Report Manipulator Specifications carries them: link length a (m), twist
  // angle alpha (rad), and the joint offset d (m) of a revolute joint or the
  // joint angle theta (rad) of a prismatic one.
  double link_length_m = 0;
  double twist_angle_rad = 0;
  double offset = 0;
  // Position limits (rad, or m for a prismatic joint), speed limit (rad/s or
  // m/s), and the force/torque of 100 % effort (N m, or N).
  double min_position = -3.14159;
  double max_position = 3.14159;
  double max_velocity = 1.0;
  double max_effort = 10.0;
  double initial_position = 0;  // within the limits
};

struct ArmConfig {
  std::vector<JointConfig> joints;  // 1..255
  // The manipulator's base frame in the vehicle frame (x forward, y right,
  // z down; metres) and its orientation as a unit quaternion (d; a, b, c).
  double base_x_m = 0, base_y_m = 0, base_z_m = 0;
  double base_quaternion_d = 1, base_quaternion_a = 0, base_quaternion_b = 0, base_quaternion_c = 0;
  double update_rate_hz = 100;  // the simulated arm's integration step and sample rate
};

// Whether `config` describes an arm the component can run and Part 3's
// messages can carry: 1..255 joints, finite values, min_position <
// max_position within +-8 pi rad (revolute) or +-10 m (prismatic), initial
// positions within the limits, 0 < max_velocity <= 10 pi rad/s or 5 m/s,
// max_effort > 0, link lengths 0..65.535 m, the base within 30 m and a
// non-zero quaternion, an update rate of 1..1000 Hz. The one source of these
// rules: jausd's configuration reader reports the same error at its line.
// The error names the first offending joint ("joint 2 (elbow): ...").
Expected<void> check_arm_config(const ArmConfig& config);

// One joint's part of those rules; `label` names it in the error.
Expected<void> check_joint_config(const JointConfig& joint, const std::string& label);

// "joint 3 (elbow)" (1-based, as Part 3 counts joints); "joint 3" without a name.
std::string joint_label(const JointConfig& joint, std::size_t index);
std::string joint_label(const ArmConfig& config, std::size_t index);

}  // namespace jaus::components
