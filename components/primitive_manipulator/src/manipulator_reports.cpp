// Part 3's manipulator bodies <-> the arm's terms (see manipulator_reports.hpp).
#include "jaus/components/manipulator_reports.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "jaus/components/manipulator_arm.hpp"

namespace jaus::components {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kMaxThousandths = 65.535;  // an unsigned short x 0.001

struct Range {
  double revolute;   // the field's limit (+-), revolute unit
  double prismatic;  // the same field for a prismatic joint
};

Range range_of(JointQuantity q) {
  switch (q) {
    case JointQuantity::position:
      return {8 * std::numbers::pi, 10};
    case JointQuantity::velocity:
      return {10 * std::numbers::pi, 5};
    case JointQuantity::acceleration:
      return {10 * std::numbers::pi, 20};
    case JointQuantity::force_torque:
      return {1000, 500};
  }
  return {1, 1};
}

double angle_in_turn(double angle) {
  if (!std::isfinite(angle)) return 0;
  const double wrapped = angle - kTwoPi * std::floor(angle / kTwoPi);
  return wrapped >= kTwoPi ? 0.0 : wrapped;
}

double length(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, kMaxThousandths) : 0.0; }

void describe_loss(std::vector<std::string>& out, const std::string& what, double value) {
  if (std::isfinite(value) && value >= 0 && value <= kMaxThousandths) return;
  std::ostringstream line;
  line << what << " " << value << " is reported as " << length(value)
       << " (Report Manipulator Specifications carries 0 .. 65.535)";
  out.push_back(line.str());
}

}  // namespace

double joint_value_from_wire(double value, bool prismatic, JointQuantity quantity) {
  if (!prismatic) return value;
  const Range r = range_of(quantity);
  return value * (r.prismatic / r.revolute);
}

double joint_value_to_wire(double value, bool prismatic, JointQuantity quantity) {
  const Range r = range_of(quantity);
  const double wire = prismatic ? value * (r.revolute / r.prismatic) : value;
  return std::isfinite(wire) ? std::clamp(wire, -r.revolute, r.revolute) : 0.0;
}

std::vector<double> joint_values_from_wire(const ArmConfig& config, std::vector<double> values,
                                           JointQuantity quantity) {
  for (std::size_t i = 0; i < values.size() && i < config.joints.size(); ++i)
    values[i] = joint_value_from_wire(values[i], config.joints[i].prismatic, quantity);
  return values;
}

std::vector<double> joint_values_to_wire(const ArmConfig& config, std::vector<double> values, JointQuantity quantity) {
  for (std::size_t i = 0; i < values.size() && i < config.joints.size(); ++i)
    values[i] = joint_value_to_wire(values[i], config.joints[i].prismatic, quantity);
  return values;
}

msg::ManipulatorSpecificationsBody to_specifications_body(const ArmConfig& config) {
  msg::ManipulatorSpecificationsBody b;
  if (config.joints.empty()) return b;  // not a runnable arm (check_arm_config); one revolute joint of zeros
  const std::size_t n = std::min<std::size_t>(config.joints.size(), 255);
  // The fixed parameter is a length (revolute: offset d) or an angle (prismatic: joint angle theta); the
  // limits are angles (revolute) or lengths (prismatic).
  const auto fixed = [](const JointConfig& j) { return j.prismatic ? angle_in_turn(j.offset) : length(j.offset); };
  const auto limit = [](const JointConfig& j, double v) { return j.prismatic ? length(v) : angle_in_turn(v); };
  const auto type = [](const JointConfig& j) {
    return static_cast<std::uint8_t>(j.prismatic ? msg::JointType::prismatic : msg::JointType::revolute);
  };

  b.joint_count = static_cast<std::uint8_t>(n);
  const JointConfig& last = config.joints[n - 1];
  b.last_joint_type = type(last);
  b.last_joint_offset_rad_or_m = fixed(last);
  b.last_joint_min_rad_or_m = limit(last, last.min_position);
  b.last_joint_max_rad_or_m = limit(last, last.max_position);
  b.last_joint_max_velocity_rps_or_mps = length(last.max_velocity);

  const auto clamp_frame = [](double v, double r) { return std::isfinite(v) ? std::clamp(v, -r, r) : 0.0; };
  b.frame_x_m = clamp_frame(config.base_x_m, 30);
  b.frame_y_m = clamp_frame(config.base_y_m, 30);
  b.frame_z_m = clamp_frame(config.base_z_m, 30);
  const kinematics::Quaternion q = kinematics::to_quaternion(kinematics::to_rotation(
      {config.base_quaternion_d, config.base_quaternion_a, config.base_quaternion_b, config.base_quaternion_c}));
  b.frame_quaternion_d = q.d;
  b.frame_quaternion_a = q.a;
  b.frame_quaternion_b = q.b;
  b.frame_quaternion_c = q.c;

  for (std::size_t i = 0; i + 1 < n; ++i) {
    const JointConfig& j = config.joints[i];
    msg::ManipulatorJointSpec s;
    s.type = type(j);
    s.link_length_m = length(j.link_length_m);
    s.twist_angle_rad = angle_in_turn(j.twist_angle_rad);
    s.offset_rad_or_m = fixed(j);
    s.min_rad_or_m = limit(j, j.min_position);
    s.max_rad_or_m = limit(j, j.max_position);
    s.max_velocity_rps_or_mps = length(j.max_velocity);
    b.joints.push_back(s);
  }
  return b;
}

std::vector<std::string> specification_losses(const ArmConfig& config) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < config.joints.size(); ++i) {
    const JointConfig& j = config.joints[i];
    const std::string label = joint_label(config, i);
    const bool last = i + 1 == config.joints.size();
    if (last && (j.link_length_m != 0 || j.twist_angle_rad != 0))
      out.push_back(label + ": the last joint's link length and twist are not used (the tool point is the offset)");
    if (!last) describe_loss(out, label + " link length", j.link_length_m);
    if (!j.prismatic) describe_loss(out, label + " offset", j.offset);
    if (j.prismatic) {
      describe_loss(out, label + " min_position", j.min_position);
      describe_loss(out, label + " max_position", j.max_position);
    } else if (j.max_position - j.min_position >= kTwoPi) {
      out.push_back(label + ": a range of a turn or more reads as its angles modulo 2 pi");
    }
    describe_loss(out, label + " max_velocity", j.max_velocity);
  }
  return out;
}

kinematics::Pose to_pose(double x_m, double y_m, double z_m, const kinematics::Quaternion& orientation) {
  return {{x_m, y_m, z_m}, kinematics::to_rotation(orientation)};
}

kinematics::Pose to_pose(const msg::EndEffectorPoseBody& b) {
  return to_pose(b.x_m, b.y_m, b.z_m, {b.quaternion_d, b.quaternion_a, b.quaternion_b, b.quaternion_c});
}

kinematics::Pose to_pose(const msg::EndEffectorPathPose& p) {
  return to_pose(p.x_m, p.y_m, p.z_m, {p.quaternion_d, p.quaternion_a, p.quaternion_b, p.quaternion_c});
}

Expected<ToolTwist> to_tool_twist(const msg::EndEffectorVelocityStateBody& b, const kinematics::Transform& effector,
                                  const kinematics::Vec3& tool) {
  using kinematics::Vec3;
  Vec3 angular{b.angular_x_rps, b.angular_y_rps, b.angular_z_rps};
  Vec3 linear{b.linear_x_mps, b.linear_y_mps, b.linear_z_mps};
  Vec3 origin{};
  if (b.coordinate_system == 2) {
    angular = effector.rotation * angular;
    linear = effector.rotation * linear;
    origin = effector.origin;
  } else if (b.coordinate_system != 1) {
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "coordinate system " + std::to_string(b.coordinate_system) +
                                     " is neither 1 (vehicle) nor 2 (end effector)"));
  }
  return ToolTwist{linear + kinematics::cross(angular, tool - origin), angular};
}

}  // namespace jaus::components
