// What an arm's configuration must be for the component to run it.
#include <cmath>
#include <numbers>

#include "jaus/components/arm_config.hpp"

namespace jaus::components {

namespace {
Expected<void> invalid(std::string why) { return unexpected(make_error(ErrorCode::invalid_argument, std::move(why))); }
bool finite(double v) { return std::isfinite(v); }

// The ranges of Part 3's manipulator messages (docs/messages.md): joint
// positions and velocities as Set Joint Positions / Velocities scale them,
// link lengths as Report Manipulator Specifications does, the base frame.
constexpr double kPi = std::numbers::pi;
constexpr double kMaxRevolutePosition = 8 * kPi;
constexpr double kMaxPrismaticPosition = 10;
constexpr double kMaxRevoluteVelocity = 10 * kPi;
constexpr double kMaxPrismaticVelocity = 5;
constexpr double kMaxLinkLength = 65.535;
constexpr double kMaxBaseOffset = 30;
}  // namespace

std::string joint_label(const JointConfig& joint, std::size_t index) {
  return "joint " + std::to_string(index + 1) + (joint.name.empty() ? "" : " (" + joint.name + ")");
}

std::string joint_label(const ArmConfig& config, std::size_t index) {
  return index < config.joints.size() ? joint_label(config.joints[index], index)
                                      : "joint " + std::to_string(index + 1);
}

Expected<void> check_joint_config(const JointConfig& j, const std::string& label) {
  const std::string who = label + ": ";
  for (double v : {j.link_length_m, j.twist_angle_rad, j.offset, j.min_position, j.max_position, j.max_velocity,
                   j.max_effort, j.initial_position})
    if (!finite(v)) return invalid(who + "every value must be finite");
  // What Set Joint Positions and Set Joint Velocities can carry (their scaled ranges).
  const double reach = j.prismatic ? kMaxPrismaticPosition : kMaxRevolutePosition;
  const double speed = j.prismatic ? kMaxPrismaticVelocity : kMaxRevoluteVelocity;
  if (!(j.min_position < j.max_position)) return invalid(who + "the minimum position must be below the maximum");
  if (j.min_position < -reach || j.max_position > reach)
    return invalid(who + "positions must be within " + (j.prismatic ? "+-10 m" : "+-1440 degrees (+-8 pi rad)"));
  if (j.initial_position < j.min_position || j.initial_position > j.max_position)
    return invalid(who + "the initial position must be within its limits");
  if (!(j.max_velocity > 0 && j.max_velocity <= speed))
    return invalid(who + "the maximum speed must be > 0 and <= " + (j.prismatic ? "5 m/s" : "1800 degrees/s"));
  if (!(j.max_effort > 0)) return invalid(who + "the maximum torque or force must be > 0");
  if (j.link_length_m < 0 || j.link_length_m > kMaxLinkLength)
    return invalid(who + "the link length must be 0..65.535 m");
  return {};
}

Expected<void> check_arm_config(const ArmConfig& config) {
  if (config.joints.empty() || config.joints.size() > 255)
    return invalid("an arm has 1 to 255 joints, not " + std::to_string(config.joints.size()));
  for (std::size_t i = 0; i < config.joints.size(); ++i)
    if (auto ok = check_joint_config(config.joints[i], joint_label(config, i)); !ok) return ok;
  for (double v : {config.base_x_m, config.base_y_m, config.base_z_m})
    if (!finite(v) || std::abs(v) > kMaxBaseOffset) return invalid("the arm's base must be within 30 m of the platform's origin");
  const double q2 = config.base_quaternion_d * config.base_quaternion_d +
                    config.base_quaternion_a * config.base_quaternion_a +
                    config.base_quaternion_b * config.base_quaternion_b +
                    config.base_quaternion_c * config.base_quaternion_c;
  if (!finite(q2) || q2 < 1e-6) return invalid("the arm's base quaternion must be a non-zero rotation");
  if (!(config.update_rate_hz >= 1 && config.update_rate_hz <= 1000))
    return invalid("the arm's update rate must be 1..1000 Hz");
  return {};
}

}  // namespace jaus::components
