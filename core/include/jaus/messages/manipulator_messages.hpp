// Manipulator subgroup: 0x0600-0x07FF, 0x2600-0x27FF, 0x4600-0x47FF.
//
// Joint values whose range depends on the joint type (revolute or prismatic)
// are carried in the revolute unit; Part 3 scales a prismatic joint's value
// with the prismatic limits instead, so for such a joint multiply by the ratio
// of the limits (docs/messages.md lists them).
#pragma once

#include "jaus/messages/common.hpp"

namespace jaus::msg {

inline constexpr auto kJointEffort = manipulator_short(-100, 100);             // percent
inline constexpr auto kJointPosition = manipulator_int(-8 * kPi, 8 * kPi);     // rad (prismatic: +-10 m)
inline constexpr auto kJointVelocity = manipulator_int(-10 * kPi, 10 * kPi);   // rad/s (prismatic: +-5 m/s)
inline constexpr auto kJointAcceleration = manipulator_int(-10 * kPi, 10 * kPi);  // rad/s^2 (prismatic: +-20 m/s^2)
inline constexpr auto kJointForceTorque = manipulator_int(-1000, 1000);        // N m (prismatic: +-500 N)
inline constexpr auto kToolPoint = manipulator_int(-15, 15);                   // m
inline constexpr auto kEffectorPosition = manipulator_int(-30, 30);            // m
inline constexpr auto kQuaternion = manipulator_int(-1, 1);
inline constexpr auto kMotionTime = manipulator_int(0, 6000);                  // s
inline constexpr wire::Prefix<std::uint8_t> kJointCount{1, 255};              // "0 is reserved"

struct JointEffortsBody {
  std::vector<double> efforts_percent;
  bool operator==(const JointEffortsBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("efforts_percent", &JointEffortsBody::efforts_percent,
                                       wire::Array<wire::Prefix<std::uint8_t>, decltype(kJointEffort)>{
                                           kJointCount, kJointEffort}));
  }
};

struct JointPositionsBody {
  std::vector<double> positions_rad;
  bool operator==(const JointPositionsBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("positions_rad", &JointPositionsBody::positions_rad,
                                       wire::Array<wire::Prefix<std::uint8_t>, decltype(kJointPosition)>{
                                           kJointCount, kJointPosition}));
  }
};

struct JointVelocitiesBody {
  std::vector<double> velocities_rps;
  bool operator==(const JointVelocitiesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("velocities_rps", &JointVelocitiesBody::velocities_rps,
                                       wire::Array<wire::Prefix<std::uint8_t>, decltype(kJointVelocity)>{
                                           kJointCount, kJointVelocity}));
  }
};

struct JointForceTorquesBody {
  std::vector<double> force_torques_nm;
  bool operator==(const JointForceTorquesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("force_torques_nm", &JointForceTorquesBody::force_torques_nm,
                                       wire::Array<wire::Prefix<std::uint8_t>, decltype(kJointForceTorque)>{
                                           kJointCount, kJointForceTorque}));
  }
};

struct ToolPointBody {
  double x_m = 0;
  double y_m = 0;
  double z_m = 0;
  bool operator==(const ToolPointBody&) const = default;
  static constexpr auto describe() {
    using B = ToolPointBody;
    return std::make_tuple(wire::field("x_m", &B::x_m, kToolPoint), wire::field("y_m", &B::y_m, kToolPoint),
                           wire::field("z_m", &B::z_m, kToolPoint));
  }
};

// Tool point position (vehicle frame) and orientation as a unit quaternion (d; a, b, c).
struct EndEffectorPoseBody {
  double x_m = 0;
  double y_m = 0;
  double z_m = 0;
  double quaternion_d = 1;
  double quaternion_a = 0;
  double quaternion_b = 0;
  double quaternion_c = 0;
  bool operator==(const EndEffectorPoseBody&) const = default;
  static constexpr auto describe() {
    using B = EndEffectorPoseBody;
    return std::make_tuple(
        wire::field("x_m", &B::x_m, kEffectorPosition), wire::field("y_m", &B::y_m, kEffectorPosition),
        wire::field("z_m", &B::z_m, kEffectorPosition), wire::field("quaternion_d", &B::quaternion_d, kQuaternion),
        wire::field("quaternion_a", &B::quaternion_a, kQuaternion),
        wire::field("quaternion_b", &B::quaternion_b, kQuaternion),
        wire::field("quaternion_c", &B::quaternion_c, kQuaternion));
  }
};

inline constexpr auto kCoordinateSystem =
    wire::enum_of<std::uint8_t>({{1, "vehicle_aligned"}, {2, "end_effector_aligned"}});

struct EndEffectorVelocityStateBody {
  std::uint8_t coordinate_system = 1;  // 1 vehicle-aligned, 2 end-effector-aligned
  double angular_x_rps = 0;
  double angular_y_rps = 0;
  double angular_z_rps = 0;
  double linear_x_mps = 0;
  double linear_y_mps = 0;
  double linear_z_mps = 0;
  bool operator==(const EndEffectorVelocityStateBody&) const = default;
  static constexpr auto describe() {
    using B = EndEffectorVelocityStateBody;
    constexpr auto angular = manipulator_int(-20 * kPi, 20 * kPi);
    constexpr auto linear = manipulator_int(-10, 10);
    return std::make_tuple(
        wire::field("coordinate_system", &B::coordinate_system, kCoordinateSystem),
        wire::field("angular_x_rps", &B::angular_x_rps, angular),
        wire::field("angular_y_rps", &B::angular_y_rps, angular),
        wire::field("angular_z_rps", &B::angular_z_rps, angular), wire::field("linear_x_mps", &B::linear_x_mps, linear),
        wire::field("linear_y_mps", &B::linear_y_mps, linear), wire::field("linear_z_mps", &B::linear_z_mps, linear));
  }
};

struct JointMotionPoint {
  double position_rad = 0;
  double max_velocity_rps = 0;
  double max_acceleration_rps2 = 0;
  double max_deceleration_rps2 = 0;
  bool operator==(const JointMotionPoint&) const = default;
  static constexpr auto describe() {
    using B = JointMotionPoint;
    return std::make_tuple(wire::field("position_rad", &B::position_rad, kJointPosition),
                           wire::field("max_velocity_rps", &B::max_velocity_rps, kJointVelocity),
                           wire::field("max_acceleration_rps2", &B::max_acceleration_rps2, kJointAcceleration),
                           wire::field("max_deceleration_rps2", &B::max_deceleration_rps2, kJointAcceleration));
  }
};

struct JointMotionPose {
  double time_s = 0;
  std::vector<JointMotionPoint> joints;  // joint_count entries
  bool operator==(const JointMotionPose&) const = default;
  static constexpr auto describe() {
    using B = JointMotionPose;
    return std::make_tuple(wire::field("time_s", &B::time_s, kMotionTime),
                           wire::field("joints", &B::joints, wire::Records<wire::FromDim<0>, JointMotionPoint>{}));
  }
};

// Set Joint Motion: the joint count is sent once and applies to every pose.
struct JointMotionBody {
  std::uint8_t joint_count = 1;
  std::vector<JointMotionPose> poses;
  bool operator==(const JointMotionBody&) const = default;
  static constexpr auto describe() {
    using B = JointMotionBody;
    return std::make_tuple(
        wire::field("joint_count", &B::joint_count, wire::Dimension<0, std::uint8_t>{1}),
        wire::field("poses", &B::poses, wire::Records<wire::Prefix<std::uint8_t>, JointMotionPose>{kJointCount}));
  }
};

struct EndEffectorPathPose {
  double time_s = 0;
  double x_m = 0;
  double y_m = 0;
  double z_m = 0;
  double quaternion_d = 1;
  double quaternion_a = 0;
  double quaternion_b = 0;
  double quaternion_c = 0;
  bool operator==(const EndEffectorPathPose&) const = default;
  static constexpr auto describe() {
    using B = EndEffectorPathPose;
    return std::make_tuple(
        wire::field("time_s", &B::time_s, kMotionTime), wire::field("x_m", &B::x_m, kEffectorPosition),
        wire::field("y_m", &B::y_m, kEffectorPosition), wire::field("z_m", &B::z_m, kEffectorPosition),
        wire::field("quaternion_d", &B::quaternion_d, kQuaternion),
        wire::field("quaternion_a", &B::quaternion_a, kQuaternion),
        wire::field("quaternion_b", &B::quaternion_b, kQuaternion),
        wire::field("quaternion_c", &B::quaternion_c, kQuaternion));
  }
};

struct EndEffectorPathMotionBody {
  std::vector<EndEffectorPathPose> poses;
  bool operator==(const EndEffectorPathMotionBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("poses", &EndEffectorPathMotionBody::poses,
                    wire::Records<wire::Prefix<std::uint8_t>, EndEffectorPathPose>{kJointCount}));
  }
};

// Joint values of Report Manipulator Specifications travel in thousandths:
// milliradians for angles, millimetres for lengths. Both read as x 0.001, so
// the values are in rad or m (rad/s or m/s for velocities) by joint type.
inline constexpr wire::Linear<std::uint16_t> kMilli{0.001};

enum class JointType : std::uint8_t { revolute = 1, prismatic = 2 };
inline constexpr auto kJointType = wire::enum_of<std::uint8_t>({{1, "revolute"}, {2, "prismatic"}});

struct ManipulatorJointSpec {
  std::uint8_t type = 1;         // JointType
  double link_length_m = 0;      // link a(i)(i+1)
  double twist_angle_rad = 0;
  double offset_rad_or_m = 0;    // joint offset (revolute, m) or joint angle (prismatic, rad)
  double min_rad_or_m = 0;
  double max_rad_or_m = 0;
  double max_velocity_rps_or_mps = 0;
  bool operator==(const ManipulatorJointSpec&) const = default;
  static constexpr auto describe() {
    using B = ManipulatorJointSpec;
    return std::make_tuple(
        wire::field("type", &B::type, kJointType), wire::field("link_length_m", &B::link_length_m, kMilli),
        wire::field("twist_angle_rad", &B::twist_angle_rad, kMilli),
        wire::field("offset_rad_or_m", &B::offset_rad_or_m, kMilli),
        wire::field("min_rad_or_m", &B::min_rad_or_m, kMilli), wire::field("max_rad_or_m", &B::max_rad_or_m, kMilli),
        wire::field("max_velocity_rps_or_mps", &B::max_velocity_rps_or_mps, kMilli));
  }
};

// Report Manipulator Specifications, in Part 3's order: the joint count, the
// last joint (which has no link after it), the manipulator frame, then joints
// 1 .. n-1 with their links.
struct ManipulatorSpecificationsBody {
  std::uint8_t joint_count = 1;
  std::uint8_t last_joint_type = 1;
  double last_joint_offset_rad_or_m = 0;
  double last_joint_min_rad_or_m = 0;
  double last_joint_max_rad_or_m = 0;
  double last_joint_max_velocity_rps_or_mps = 0;
  double frame_x_m = 0;
  double frame_y_m = 0;
  double frame_z_m = 0;
  double frame_quaternion_d = 1;
  double frame_quaternion_a = 0;
  double frame_quaternion_b = 0;
  double frame_quaternion_c = 0;
  std::vector<ManipulatorJointSpec> joints;  // joint_count - 1 entries
  bool operator==(const ManipulatorSpecificationsBody&) const = default;
  static constexpr auto describe() {
    using B = ManipulatorSpecificationsBody;
    return std::make_tuple(
        wire::field("joint_count", &B::joint_count, wire::Dimension<0, std::uint8_t>{1}),
        wire::field("last_joint_type", &B::last_joint_type, kJointType),
        wire::field("last_joint_offset_rad_or_m", &B::last_joint_offset_rad_or_m, kMilli),
        wire::field("last_joint_min_rad_or_m", &B::last_joint_min_rad_or_m, kMilli),
        wire::field("last_joint_max_rad_or_m", &B::last_joint_max_rad_or_m, kMilli),
        wire::field("last_joint_max_velocity_rps_or_mps", &B::last_joint_max_velocity_rps_or_mps, kMilli),
        wire::field("frame_x_m", &B::frame_x_m, kEffectorPosition),
        wire::field("frame_y_m", &B::frame_y_m, kEffectorPosition),
        wire::field("frame_z_m", &B::frame_z_m, kEffectorPosition),
        wire::field("frame_quaternion_d", &B::frame_quaternion_d, kQuaternion),
        wire::field("frame_quaternion_a", &B::frame_quaternion_a, kQuaternion),
        wire::field("frame_quaternion_b", &B::frame_quaternion_b, kQuaternion),
        wire::field("frame_quaternion_c", &B::frame_quaternion_c, kQuaternion),
        wire::field("joints", &B::joints, wire::Records<wire::FromDim<0, 1>, ManipulatorJointSpec>{}));
  }
};

using SetJointEfforts = Message<0x0601, "Set Joint Efforts", JointEffortsBody>;
using SetJointPositions = Message<0x0602, "Set Joint Positions", JointPositionsBody>;
using SetJointVelocities = Message<0x0603, "Set Joint Velocities", JointVelocitiesBody>;
using SetToolPoint = Message<0x0604, "Set Tool Point", ToolPointBody>;
using SetEndEffectorPose = Message<0x0605, "Set End-Effector Pose", EndEffectorPoseBody>;
using SetEndEffectorVelocityState = Message<0x0606, "Set End-Effector Velocity State", EndEffectorVelocityStateBody>;
using SetJointMotion = Message<0x0607, "Set Joint Motion", JointMotionBody>;
using SetEndEffectorPathMotion = Message<0x0608, "Set End-Effector Path Motion", EndEffectorPathMotionBody>;

using QueryManipulatorSpecifications = Message<0x2600, "Query Manipulator Specifications", Empty>;
using QueryJointEfforts = Message<0x2601, "Query Joint Efforts", Empty>;
using QueryJointPositions = Message<0x2602, "Query Joint Positions", Empty>;
using QueryJointVelocities = Message<0x2603, "Query Joint Velocities", Empty>;
using QueryToolPoint = Message<0x2604, "Query Tool Point", Empty>;
using QueryJointForceTorques = Message<0x2605, "Query Joint Force/Torques", Empty>;

using ReportManipulatorSpecifications =
    Message<0x4600, "Report Manipulator Specifications", ManipulatorSpecificationsBody>;
using ReportJointEfforts = Message<0x4601, "Report Joint Efforts", JointEffortsBody>;
using ReportJointPositions = Message<0x4602, "Report Joint Positions", JointPositionsBody>;
using ReportJointVelocities = Message<0x4603, "Report Joint Velocities", JointVelocitiesBody>;
using ReportToolPoint = Message<0x4604, "Report Tool Point", ToolPointBody>;
using ReportJointForceTorques = Message<0x4605, "Report Joint Force/Torques", JointForceTorquesBody>;

using ManipulatorMessages =
    TypeList<SetJointEfforts, SetJointPositions, SetJointVelocities, SetToolPoint, SetEndEffectorPose,
             SetEndEffectorVelocityState, SetJointMotion, SetEndEffectorPathMotion, QueryManipulatorSpecifications,
             QueryJointEfforts, QueryJointPositions, QueryJointVelocities, QueryToolPoint, QueryJointForceTorques,
             ReportManipulatorSpecifications, ReportJointEfforts, ReportJointPositions, ReportJointVelocities,
             ReportToolPoint, ReportJointForceTorques>;

}  // namespace jaus::msg
