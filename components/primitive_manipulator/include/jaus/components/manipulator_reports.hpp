// The conversions between Part 3's manipulator message bodies and the arm's
// terms (SI units per joint type, the kinematics' frames), one place for
// each field's meaning (manipulator_reports.cpp).
//
// Joint values that depend on the joint type (positions, velocities,
// accelerations, force/torques) are carried with the revolute limits, in the
// revolute unit (core/.../manipulator_messages.hpp, docs/messages.md): for a
// prismatic joint the same value means value x (prismatic range / revolute
// range), e.g. a position x 10 / (8 pi) m. The converters here apply that
// per joint, and clamp what they write to what the field can carry.
//
// Report Manipulator Specifications carries thousandths (rad or mm) in
// unsigned shorts, so it can carry neither negative values nor more than
// 65.535: angles (twist, a prismatic joint's angle, a revolute joint's
// limits) are sent modulo 2 pi, in [0, 2 pi) (a revolute range [-2.5, 2.5]
// reads min 3.783, max 2.5: the range runs counter-clockwise from min to
// max); lengths (link length, a revolute joint's offset, a prismatic joint's
// limits) and speed limits are clamped to [0, 65.535];
// specification_losses() lists what a configuration loses that way.
#pragma once

#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/arm_config.hpp"
#include "jaus/components/kinematics.hpp"
#include "jaus/messages/manipulator_messages.hpp"

namespace jaus::components {

enum class JointQuantity { position, velocity, acceleration, force_torque };

// A joint value as the codec decodes it (revolute scaling) -> rad, m, ... by joint type.
double joint_value_from_wire(double value, bool prismatic, JointQuantity quantity);
// The reverse, clamped to the field's range.
double joint_value_to_wire(double value, bool prismatic, JointQuantity quantity);
// Per joint of `config`; values beyond the joint count are left as they are.
std::vector<double> joint_values_from_wire(const ArmConfig& config, std::vector<double> values,
                                           JointQuantity quantity);
std::vector<double> joint_values_to_wire(const ArmConfig& config, std::vector<double> values, JointQuantity quantity);

// Report Manipulator Specifications in Part 3's order: the joint count, the
// last joint, the base frame, then joints 1 .. n-1 with their links.
msg::ManipulatorSpecificationsBody to_specifications_body(const ArmConfig& config);
// What the report cannot carry of `config` (one line each; empty: nothing lost).
std::vector<std::string> specification_losses(const ArmConfig& config);

kinematics::Pose to_pose(double x_m, double y_m, double z_m, const kinematics::Quaternion& orientation);
kinematics::Pose to_pose(const msg::EndEffectorPoseBody& body);
kinematics::Pose to_pose(const msg::EndEffectorPathPose& pose);

// Set End-Effector Velocity State as the tool point's linear velocity and
// the end effector's angular velocity, both in the vehicle frame. Part 3
// gives the angular velocity and the linear velocity of the end-effector
// point that coincides with the origin of a reference frame aligned with the
// vehicle frame (1; origin: the vehicle frame's) or with the end-effector
// frame (2; origin: the end-effector frame's, where S_n meets a_n(n+1)) at
// this instant; so v_tool = v_origin + w x (tool - origin). Other
// coordinate systems are an error.
struct ToolTwist {
  kinematics::Vec3 linear;   // m/s
  kinematics::Vec3 angular;  // rad/s
};
Expected<ToolTwist> to_tool_twist(const msg::EndEffectorVelocityStateBody& body,
                                  const kinematics::Transform& effector_frame, const kinematics::Vec3& tool_in_vehicle);

}  // namespace jaus::components
