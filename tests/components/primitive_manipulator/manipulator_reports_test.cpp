// The conversions between Part 3's bodies and the arm's terms: prismatic
// scaling, the specifications report, poses and velocity states.
#include <gtest/gtest.h>

#include <cmath>

#include "arms.hpp"
#include "jaus/components/manipulator_reports.hpp"
#include "jaus/wire/describe.hpp"

namespace jaus::test {
namespace {

using namespace components;
using kinematics::Vec3;

TEST(ManipulatorReports, PrismaticValuesUseTheirOwnLimitsOnTheRevoluteScale) {
  // Part 3: a prismatic position of +10 m is the top of the field, like +8 pi rad for a revolute one.
  EXPECT_NEAR(joint_value_to_wire(10, true, JointQuantity::position), 8 * kPi, 1e-12);
  EXPECT_NEAR(joint_value_from_wire(8 * kPi, true, JointQuantity::position), 10, 1e-12);
  EXPECT_NEAR(joint_value_to_wire(5, true, JointQuantity::velocity), 10 * kPi, 1e-12);
  EXPECT_NEAR(joint_value_to_wire(20, true, JointQuantity::acceleration), 10 * kPi, 1e-12);
  EXPECT_NEAR(joint_value_to_wire(500, true, JointQuantity::force_torque), 1000, 1e-12);
  EXPECT_EQ(joint_value_to_wire(1.5, false, JointQuantity::position), 1.5);
  EXPECT_EQ(joint_value_from_wire(1.5, false, JointQuantity::velocity), 1.5);
  // Clamped to what the field carries.
  EXPECT_NEAR(joint_value_to_wire(2000, false, JointQuantity::force_torque), 1000, 1e-12);
  EXPECT_NEAR(joint_value_to_wire(-600, true, JointQuantity::force_torque), -1000, 1e-12);

  // Through the codec: the quill's 0.25 m survives a round trip of Set Joint Positions.
  const ArmConfig arm = scara_arm();
  msg::SetJointPositions m;
  m.positions_rad = joint_values_to_wire(arm, {0.5, -0.5, 0.25}, JointQuantity::position);
  std::vector<std::uint8_t> buffer(64);
  const auto size = wire::encode_payload(m, buffer);
  ASSERT_TRUE(size);
  buffer.resize(*size);
  const auto decoded = wire::decode_payload<msg::SetJointPositions>(buffer);
  ASSERT_TRUE(decoded);
  const auto back = joint_values_from_wire(arm, decoded->positions_rad, JointQuantity::position);
  EXPECT_NEAR(back[0], 0.5, 1e-7);
  EXPECT_NEAR(back[1], -0.5, 1e-7);
  EXPECT_NEAR(back[2], 0.25, 1e-7);
}

TEST(ManipulatorReports, SpecificationsInPartThreesOrderAndSize) {
  ArmConfig arm = scara_arm();
  arm.base_x_m = 0.3;
  arm.base_z_m = -0.2;
  const auto body = to_specifications_body(arm);
  EXPECT_EQ(body.joint_count, 3);
  // The last joint first: the prismatic quill (angle 0 rad; 0 .. 0.3 m; 0.2 m/s).
  EXPECT_EQ(body.last_joint_type, 2);
  EXPECT_EQ(body.last_joint_offset_rad_or_m, 0);
  EXPECT_EQ(body.last_joint_min_rad_or_m, 0);
  EXPECT_NEAR(body.last_joint_max_rad_or_m, 0.3, 1e-12);
  EXPECT_NEAR(body.last_joint_max_velocity_rps_or_mps, 0.2, 1e-12);
  EXPECT_EQ(body.frame_x_m, 0.3);
  EXPECT_EQ(body.frame_z_m, -0.2);
  EXPECT_EQ(body.frame_quaternion_d, 1);
  // Then joints 1 and 2 with their links; angles modulo 2 pi (unsigned thousandths).
  ASSERT_EQ(body.joints.size(), 2u);
  EXPECT_EQ(body.joints[0].type, 1);
  EXPECT_NEAR(body.joints[0].link_length_m, 0.5, 1e-12);
  EXPECT_NEAR(body.joints[0].offset_rad_or_m, 0.4, 1e-12);
  EXPECT_NEAR(body.joints[0].min_rad_or_m, 2 * kPi - 2.5, 1e-12);
  EXPECT_NEAR(body.joints[0].max_rad_or_m, 2.5, 1e-12);
  EXPECT_NEAR(body.joints[1].twist_angle_rad, kPi, 1e-12);

  // 38 + 13 (n - 1) bytes: every field of Part 3's table, the last joint's max value included.
  msg::ReportManipulatorSpecifications report;
  static_cast<msg::ManipulatorSpecificationsBody&>(report) = body;
  std::vector<std::uint8_t> buffer(256);
  const auto size = wire::encode_payload(report, buffer);
  ASSERT_TRUE(size);
  EXPECT_EQ(*size, 38u + 13u * 2);
  buffer.resize(*size);
  const auto decoded = wire::decode_payload<msg::ReportManipulatorSpecifications>(buffer);
  ASSERT_TRUE(decoded);
  EXPECT_NEAR(decoded->joints[0].min_rad_or_m, 2 * kPi - 2.5, 0.0005);
  EXPECT_NEAR(decoded->joints[1].link_length_m, 0.3, 0.0005);

  // A one-joint arm: no joint records.
  ArmConfig one;
  one.joints = {revolute("turret", 0, 0, 0.1)};
  EXPECT_TRUE(to_specifications_body(one).joints.empty());
}

TEST(ManipulatorReports, WhatTheSpecificationsCannotCarryIsListed) {
  EXPECT_TRUE(specification_losses(scara_arm()).empty());
  ArmConfig arm = planar_arm();
  arm.joints[0].offset = -0.1;  // a negative offset d
  arm.joints[1].link_length_m = 0.2;  // the last joint's link is not used
  const auto losses = specification_losses(arm);
  ASSERT_EQ(losses.size(), 2u);
  EXPECT_NE(losses[0].find("joint 1 (shoulder) offset"), std::string::npos) << losses[0];
  EXPECT_NE(losses[1].find("joint 2 (elbow)"), std::string::npos) << losses[1];
}

TEST(ManipulatorReports, VelocityStateAboutTheReferenceOriginBecomesTheToolsTwist) {
  kinematics::Transform effector{kinematics::rot_z(kPi / 2), {1, 0, 0}};
  const Vec3 tool{1, 0, 0.5};  // in the vehicle frame
  msg::EndEffectorVelocityStateBody b;
  // 1: vehicle-aligned; turning about z at 1 rad/s with the vehicle origin's point still.
  b.coordinate_system = 1;
  b.angular_z_rps = 1;
  auto t = to_tool_twist(b, effector, tool);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->linear.y, 1, 1e-12);  // w x (1, 0, 0.5)
  EXPECT_NEAR(t->linear.x, 0, 1e-12);
  EXPECT_NEAR(t->angular.z, 1, 1e-12);
  // 2: end-effector aligned: x of the end effector is y of the vehicle; its origin (1, 0, 0).
  b = {};
  b.coordinate_system = 2;
  b.linear_x_mps = 0.2;
  b.angular_x_rps = 1;  // about the end effector's x = vehicle y
  t = to_tool_twist(b, effector, tool);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->angular.y, 1, 1e-12);
  // v_origin (0, 0.2, 0) + (0, 1, 0) x (0, 0, 0.5) = (0.5, 0.2, 0)
  EXPECT_NEAR(t->linear.x, 0.5, 1e-12);
  EXPECT_NEAR(t->linear.y, 0.2, 1e-12);
  EXPECT_NEAR(t->linear.z, 0, 1e-12);
  b.coordinate_system = 3;
  EXPECT_FALSE(to_tool_twist(b, effector, tool));
}

}  // namespace
}  // namespace jaus::test
