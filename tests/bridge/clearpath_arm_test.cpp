// The Clearpath arm under virtual time, against the simulated platform
// (LoopbackClient): JAUS joint targets reach the simulated joints through the
// mapping (ID, sign, offset), ramped at the joints' speed limits; commands
// out of the limits (JAUS or Clearpath's +-pi) are refused whole, naming the
// joint, and nothing is sent; efforts are refused; velocities integrate and
// stop at the limits; hold stops; the sample maps 0x9010/0x9014 back; homing
// sends 0x1013 and the simulated joints home.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/bridge/clearpath_arm.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace {

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
namespace bridge = jaus::bridge;
namespace components = jaus::components;
using namespace std::chrono_literals;
using jaus::ErrorCode;

components::JointConfig revolute(const char* name, double min, double max, double max_velocity) {
  components::JointConfig j;
  j.name = name;
  j.link_length_m = 0.3;
  j.min_position = min;
  j.max_position = max;
  j.max_velocity = max_velocity;
  return j;
}

components::ArmConfig three_joints() {
  components::ArmConfig arm;
  arm.joints = {revolute("waist", -2.0, 2.0, 1.0), revolute("shoulder", -1.5, 1.5, 0.5),
                revolute("elbow", -2.5, 2.5, 1.0)};
  return arm;
}

// waist -> Clearpath joint 2, reversed; shoulder -> 0, +0.5 rad; elbow -> 5, -1 rad.
bridge::ClearpathArmConfig mapping() {
  bridge::ClearpathArmConfig c;
  c.joints = {{2, -1, 0}, {0, 1, 0.5}, {5, 1, -1.0}};
  return c;
}

class ClearpathArmTest : public ::testing::Test {
 protected:
  ClearpathArmTest()
      : loopback(time, time),
        platform(loopback, time, [this](rt::LogLevel, const std::string& line) { logs.push_back(line); }),
        made_arm(bridge::ClearpathArm::make(platform, time, three_joints(), mapping()).value()),
        arm(*made_arm) {
    loopback.on_written([this](std::span<const std::uint8_t> frame) {
      const auto f = cp::decode_frame(frame);
      if (!f) return;
      const auto e = cp::decode(*f, cp::Direction::to_platform);
      if (!e) return;
      if (const auto* m = e->message.get_if<cp::SetAbsoluteJoints>()) joint_commands.push_back(*m);
      if (const auto* m = e->message.get_if<cp::HomeJoint>()) homes.push_back(m->joint);
    });
  }

  void run(rt::Duration d) { time.advance(d); }
  const sim::Joint& joint(std::size_t id) const { return loopback.platform().vehicle().joints().at(id); }
  bool logged(const std::string& text) const {
    return std::any_of(logs.begin(), logs.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  }
  std::vector<double> positions() const {
    const auto s = arm.sample();
    return s ? s->positions : std::vector<double>{};
  }

  rt::VirtualTime time;
  sim::LoopbackClient loopback;
  std::vector<std::string> logs;
  bridge::PlatformConnection platform;
  std::unique_ptr<bridge::ClearpathArm> made_arm;
  bridge::ClearpathArm& arm;
  std::vector<cp::SetAbsoluteJoints> joint_commands;
  std::vector<std::uint8_t> homes;
};

TEST_F(ClearpathArmTest, TheSampleMapsTheSetpointsBack) {
  EXPECT_FALSE(arm.sample());  // nothing heard yet
  run(200ms);
  const auto s = arm.sample();
  ASSERT_TRUE(s);
  ASSERT_EQ(s->positions.size(), 3u);
  // Every simulated joint at 0 rad: waist -(0 - 0), shoulder 0 - 0.5, elbow 0 + 1.
  EXPECT_NEAR(s->positions[0], 0, 1e-9);
  EXPECT_NEAR(s->positions[1], -0.5, 1e-4);
  EXPECT_NEAR(s->positions[2], 1.0, 1e-4);
  EXPECT_TRUE(s->velocities.empty());  // Clearpath does not report them
  EXPECT_TRUE(s->efforts_percent.empty());
  ASSERT_EQ(s->force_torques.size(), 3u);
  EXPECT_EQ(arm.geometry().joints.size(), 3u);
}

TEST_F(ClearpathArmTest, JointTargetsArriveMappedAndRampedAtTheSpeedLimits) {
  run(200ms);
  ASSERT_TRUE(arm.move_to_positions({0.4, 0.2, 1.5}));
  EXPECT_EQ(arm.motion(), bridge::ClearpathArm::Motion::positions);
  run(500ms);
  // The shoulder's setpoint moves at its 0.5 rad/s: 0 -> 0.25 rad after 0.5 s (one 50 ms step late at most).
  EXPECT_NEAR(joint(0).target, 0.25, 0.03);
  EXPECT_TRUE(arm.ramping());
  run(3s);
  EXPECT_FALSE(arm.ramping());
  EXPECT_NEAR(joint(2).target, -0.4, 1e-4);  // waist, reversed
  EXPECT_NEAR(joint(0).target, 0.7, 1e-4);   // shoulder, 0.2 + 0.5
  EXPECT_NEAR(joint(5).target, 0.5, 1e-4);   // elbow, 1.5 - 1
  EXPECT_NEAR(joint(2).angle, -0.4, 1e-4);
  EXPECT_NEAR(joint(0).angle, 0.7, 1e-4);
  EXPECT_NEAR(joint(5).angle, 0.5, 1e-4);
  for (std::size_t unmapped : {1u, 3u, 4u}) EXPECT_EQ(joint(unmapped).target, 0) << unmapped;
  ASSERT_FALSE(joint_commands.empty());
  const auto& last = joint_commands.back().joints;
  ASSERT_EQ(last.size(), 3u);
  EXPECT_EQ(last[0].joint, 2);
  EXPECT_EQ(last[1].joint, 0);
  EXPECT_EQ(last[2].joint, 5);
  const auto q = positions();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_NEAR(q[0], 0.4, 1e-4);
  EXPECT_NEAR(q[1], 0.2, 1e-4);
  EXPECT_NEAR(q[2], 1.5, 1e-4);

  arm.hold();  // there already: it stays exactly there
  run(500ms);
  EXPECT_NEAR(joint(2).target, -0.4, 1e-4);
  EXPECT_NEAR(joint(0).target, 0.7, 1e-4);
  EXPECT_NEAR(joint(5).target, 0.5, 1e-4);
}

TEST_F(ClearpathArmTest, OutOfLimitsIsRefusedWholeNamingTheJointAndNothingIsSent) {
  run(200ms);
  // The shoulder beyond its JAUS limit.
  auto r = arm.move_to_positions({0.1, 1.6, 0.0});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::out_of_range);
  EXPECT_NE(r.error().message().find("joint 2 (shoulder)"), std::string::npos) << r.error().message();
  // The elbow within its JAUS limits but at -3.3 rad on Clearpath joint 5.
  r = arm.move_to_positions({0.1, 0.1, -2.3});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message().find("joint 3 (elbow)"), std::string::npos) << r.error().message();
  EXPECT_NE(r.error().message().find("Clearpath joint 5"), std::string::npos) << r.error().message();
  // A wrong count.
  r = arm.move_to_positions({0.1, 0.1});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message().find("2 joints"), std::string::npos) << r.error().message();
  r = arm.move_at_velocities({0, 0.6, 0});  // the shoulder's limit is 0.5 rad/s
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message().find("joint 2 (shoulder)"), std::string::npos) << r.error().message();
  run(1s);
  EXPECT_TRUE(joint_commands.empty());
  EXPECT_FALSE(arm.ramping());
  for (const auto& j : loopback.platform().vehicle().joints()) EXPECT_EQ(j.target, 0);
  EXPECT_EQ(arm.counters().refused, 4u);
}

TEST_F(ClearpathArmTest, EffortsAreRefused) {
  run(200ms);
  const auto r = arm.apply_efforts({10, 0, 0});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::refused);
  EXPECT_NE(r.error().message().find("no joint effort command"), std::string::npos) << r.error().message();
  run(500ms);
  EXPECT_TRUE(joint_commands.empty());
  EXPECT_TRUE(logged("joint efforts"));
}

TEST_F(ClearpathArmTest, CommandsWaitForThePlatform) {
  const auto r = arm.move_to_positions({0.1, 0.1, 0.1});  // nothing heard yet
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::io);
  run(500ms);
  EXPECT_TRUE(joint_commands.empty());
}

TEST_F(ClearpathArmTest, VelocitiesAreIntegratedAndStopAtTheLimits) {
  run(200ms);
  ASSERT_TRUE(arm.move_at_velocities({0.5, 0, -1.0}));
  EXPECT_EQ(arm.motion(), bridge::ClearpathArm::Motion::velocities);
  run(1s);
  EXPECT_NEAR(joint(2).target, -0.5, 0.06);  // waist at 0.5 rad/s, reversed
  EXPECT_NEAR(joint(0).target, 0, 1e-4);     // shoulder still
  // The elbow from 1 rad at -1 rad/s: its reachable limit is Clearpath's -pi, i.e. 1 - pi rad.
  run(5s);
  EXPECT_FALSE(arm.ramping());
  EXPECT_NEAR(joint(2).target, -2.0, 1e-4);  // the waist's limit, 2 rad
  EXPECT_NEAR(joint(5).target, -std::numbers::pi, 1e-3);
  const auto q = positions();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_NEAR(q[0], 2.0, 1e-4);
  EXPECT_NEAR(q[2], 1 - std::numbers::pi, 1e-3);
  const std::size_t count = joint_commands.size();
  run(1s);
  EXPECT_EQ(joint_commands.size(), count);  // nothing more at the limits
}

TEST_F(ClearpathArmTest, HoldStopsWhereThePlatformIs) {
  run(200ms);
  ASSERT_TRUE(arm.move_at_velocities({0.8, 0, 0}));
  run(1s);
  const double before = joint(2).target;  // the platform's setpoint when told to hold
  arm.hold();
  EXPECT_EQ(arm.motion(), bridge::ClearpathArm::Motion::holding);
  EXPECT_FALSE(arm.ramping());
  run(100ms);
  const double held = joint(2).target;
  EXPECT_LT(held, -0.6);  // it did move
  // Where the ramp was: never back (toward 0), at most one 50 ms step further.
  EXPECT_LE(held, before + 1e-9);
  EXPECT_GE(held, before - 0.8 * 0.05 - 1e-3);
  run(2s);
  EXPECT_NEAR(joint(2).target, held, 1e-9);
  EXPECT_NEAR(joint(2).angle, held, 1e-9);
  ASSERT_FALSE(joint_commands.empty());
  EXPECT_NEAR(joint_commands.back().joints[0].angle, held, 1e-4);
}

TEST_F(ClearpathArmTest, HoldStopsAPositionRamp) {
  run(200ms);
  ASSERT_TRUE(arm.move_to_positions({-1.8, 0, 0}));  // waist 1.8 rad at 1 rad/s
  run(500ms);
  arm.hold();
  run(2s);
  EXPECT_LT(joint(2).target, 0.7);  // Clearpath 1.8 if it had gone on
  EXPECT_GT(joint(2).target, 0.3);
  EXPECT_NEAR(joint(2).angle, joint(2).target, 1e-9);
}

TEST_F(ClearpathArmTest, ForceTorquesAreMappedWithTheJointsSign) {
  run(200ms);
  // Move Clearpath joint 2 (the reversed waist) from outside the bridge: its
  // torque is the controller's p x error while it moves.
  loopback.send(cp::SetAbsoluteJoints{{{2, 1.0}}});
  run(200ms);
  const auto s = arm.sample();
  ASSERT_TRUE(s);
  ASSERT_EQ(s->force_torques.size(), 3u);
  EXPECT_GT(joint(2).torque, 2.0);
  EXPECT_NEAR(s->force_torques[0], -joint(2).torque, 0.6);
  EXPECT_NEAR(s->force_torques[1], joint(0).torque, 1e-9);
}

TEST_F(ClearpathArmTest, HomingSendsHomeJointAndTheJointsHome) {
  run(200ms);
  ASSERT_TRUE(arm.move_to_positions({0.5, 0, 0}));  // Clearpath joints 2: -0.5, 0: 0.5, 5: -1
  run(3s);
  ASSERT_NEAR(joint(5).angle, -1.0, 1e-4);
  arm.home();
  EXPECT_EQ(arm.motion(), bridge::ClearpathArm::Motion::homing);
  run(2s);
  EXPECT_EQ(homes, (std::vector<std::uint8_t>{2, 0, 5}));
  for (std::size_t id : {0u, 2u, 5u}) {
    EXPECT_EQ(joint(id).homing, cp::JointHomingData::kHomedAtHome) << id;
    EXPECT_NEAR(joint(id).angle, 0, 1e-9) << id;
  }
  for (std::size_t id : {1u, 3u, 4u}) EXPECT_EQ(joint(id).homing, cp::JointHomingData::kUnhomed) << id;
  EXPECT_EQ(arm.counters().homings, 1u);
}

TEST_F(ClearpathArmTest, LosingThePlatformEndsTheRamp) {
  run(200ms);
  ASSERT_TRUE(arm.move_at_velocities({0.5, 0, 0}));
  run(300ms);
  loopback.set_plugged(false);
  run(2s);
  EXPECT_FALSE(platform.alive());
  EXPECT_FALSE(arm.ramping());
  EXPECT_TRUE(logged("motion ended"));
  EXPECT_FALSE(arm.move_at_velocities({0.5, 0, 0}));  // refused while it is gone
  const auto last = arm.sample();                     // the last data, with its time
  ASSERT_TRUE(last);
  EXPECT_GT(last->positions[0], 0.1);
  EXPECT_LT(last->sampled_at, time.now() - 1s);
  loopback.set_plugged(true);
  run(3s);
  ASSERT_TRUE(platform.alive());
  const double target = joint(2).target;
  run(1s);
  EXPECT_NEAR(joint(2).target, target, 1e-9);  // nothing resumes by itself
}

TEST(ClearpathArmConfig, BadMappingsAreRefusedNamingTheJoint) {
  const auto arm = three_joints();
  EXPECT_TRUE(bridge::check_clearpath_arm_config(arm, mapping()));

  auto c = mapping();
  c.joints.pop_back();
  EXPECT_FALSE(bridge::check_clearpath_arm_config(arm, c));

  c = mapping();
  c.joints[2].clearpath_joint = 2;  // the waist's
  auto ok = bridge::check_clearpath_arm_config(arm, c);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("joint 3 (elbow)"), std::string::npos) << ok.error().message();

  c = mapping();
  c.joints[1].sign = 2;
  ok = bridge::check_clearpath_arm_config(arm, c);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("joint 2 (shoulder)"), std::string::npos) << ok.error().message();

  c = mapping();
  c.joints[0].offset_rad = 6;  // the waist's [-2, 2] would be [4, 8] rad
  ok = bridge::check_clearpath_arm_config(arm, c);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("joint 1 (waist)"), std::string::npos) << ok.error().message();

  auto prismatic = three_joints();
  prismatic.joints[2].prismatic = true;
  prismatic.joints[2].min_position = 0;
  prismatic.joints[2].max_position = 0.3;
  prismatic.joints[2].initial_position = 0;
  ok = bridge::check_clearpath_arm_config(prismatic, mapping());
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("prismatic"), std::string::npos) << ok.error().message();
}

// No arm exists in an invalid state: the factory says why and makes none,
// and nothing reaches the platform (no subscription, no joint moved).
TEST(ClearpathArmConfig, AnInvalidMappingMakesNoArm) {
  rt::VirtualTime time;
  sim::LoopbackClient loopback(time, time);
  bridge::PlatformConnection platform(loopback, time);
  auto bad = mapping();
  bad.joints[0].sign = 0;
  const auto arm = bridge::ClearpathArm::make(platform, time, three_joints(), bad);
  ASSERT_FALSE(arm);
  EXPECT_EQ(arm.error().message(), bridge::check_clearpath_arm_config(three_joints(), bad).error().message());
  time.advance(1s);
  EXPECT_EQ(loopback.platform().subscription_count(), 0u);
  for (const auto& j : loopback.platform().vehicle().joints()) EXPECT_EQ(j.target, 0);
}

}  // namespace
