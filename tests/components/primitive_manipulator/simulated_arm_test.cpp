// The simulated arm under virtual time: each mode, the limits, hold, and
// what it reports.
#include <gtest/gtest.h>

#include "arms.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/components/simulated_arm.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using components::SimulatedArm;

class SimulatedArmTest : public ::testing::Test {
 protected:
  rt::VirtualTime time;
  SimulatedArm arm{scara_arm(), time};  // 100 Hz; shoulder 1 rad/s, elbow 0.5 rad/s, quill 0.2 m/s
};

TEST_F(SimulatedArmTest, StartsHoldingItsInitialPositions) {
  EXPECT_EQ(arm.mode(), SimulatedArm::Mode::holding);
  EXPECT_EQ(arm.positions(), (std::vector<double>{0, 0, 0.1}));
  time.advance(1s);
  const auto s = arm.sample();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->positions, (std::vector<double>{0, 0, 0.1}));
  EXPECT_EQ(s->velocities, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(s->force_torques, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(s->sampled_at, time.now());
}

TEST_F(SimulatedArmTest, PositionsAreReachedAtTheSpeedLimitsThenHeld) {
  ASSERT_TRUE(arm.move_to_positions({1, -0.25, 0.3}));
  time.advance(500ms);
  auto s = arm.sample();
  EXPECT_NEAR(s->positions[0], 0.5, 1e-9);    // 1 rad/s
  EXPECT_NEAR(s->positions[1], -0.25, 1e-9);  // 0.5 rad/s: reached
  EXPECT_NEAR(s->positions[2], 0.2, 1e-9);    // 0.2 m/s
  EXPECT_NEAR(s->velocities[0], 1, 1e-9);
  EXPECT_NEAR(s->force_torques[0], 10, 1e-9);  // friction at full speed: max_effort
  EXPECT_NEAR(s->efforts_percent[0], 100, 1e-9);
  time.advance(2s);
  s = arm.sample();
  EXPECT_EQ(s->positions, (std::vector<double>{1, -0.25, 0.3}));
  EXPECT_EQ(s->velocities, (std::vector<double>{0, 0, 0}));
}

TEST_F(SimulatedArmTest, VelocitiesStopAtThePositionLimits) {
  ASSERT_TRUE(arm.move_at_velocities({-1, 0.5, 0.2}));
  time.advance(1s);
  auto s = arm.sample();
  EXPECT_NEAR(s->positions[0], -1, 1e-9);
  EXPECT_NEAR(s->positions[1], 0.5, 1e-9);
  EXPECT_NEAR(s->positions[2], 0.3, 1e-9);  // the quill's end, just reached
  time.advance(100ms);
  s = arm.sample();
  EXPECT_EQ(s->positions[2], 0.3);
  EXPECT_EQ(s->velocities[2], 0);
  time.advance(10s);
  s = arm.sample();
  EXPECT_NEAR(s->positions[0], -2.5, 1e-9);
  EXPECT_NEAR(s->positions[1], 2.5, 1e-9);
}

TEST_F(SimulatedArmTest, EffortIsThatShareOfTheSpeedLimitAndOfMaxEffort) {
  ASSERT_TRUE(arm.apply_efforts({50, -20, -100}));
  time.advance(200ms);
  const auto s = arm.sample();
  EXPECT_NEAR(s->positions[0], 0.1, 1e-9);     // 50 % of 1 rad/s
  EXPECT_NEAR(s->positions[1], -0.02, 1e-9);   // -20 % of 0.5 rad/s
  EXPECT_NEAR(s->positions[2], 0.06, 1e-9);    // -100 % of 0.2 m/s
  EXPECT_NEAR(s->force_torques[0], 5, 1e-9);   // 50 % of 10 N m
  EXPECT_NEAR(s->force_torques[2], -100, 1e-9);  // -100 % of 100 N
  EXPECT_EQ(s->efforts_percent, (std::vector<double>{50, -20, -100}));
}

TEST_F(SimulatedArmTest, HoldKeepsEveryJointWhereItIs) {
  ASSERT_TRUE(arm.move_at_velocities({0.5, 0.5, 0.1}));
  time.advance(300ms);
  arm.hold();
  const auto held = arm.positions();
  time.advance(5s);
  EXPECT_EQ(arm.positions(), held);
  EXPECT_EQ(arm.mode(), SimulatedArm::Mode::holding);
  EXPECT_EQ(arm.sample()->force_torques, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(arm.holds(), 1u);
}

TEST_F(SimulatedArmTest, BadCommandsAreRefusedWholeAndNameTheJoint) {
  ASSERT_TRUE(arm.move_at_velocities({0.1, 0, 0}));
  auto r = arm.move_to_positions({1, 3, 0.1});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message().find("joint 2 (elbow)"), std::string::npos) << r.error().message();
  EXPECT_FALSE(arm.move_to_positions({1, 0}));
  EXPECT_FALSE(arm.move_at_velocities({0, 0, 0.3}));  // quill faster than 0.2 m/s
  EXPECT_FALSE(arm.apply_efforts({0, 101, 0}));
  EXPECT_EQ(arm.mode(), SimulatedArm::Mode::velocities);  // still the last good command
  time.advance(1s);
  EXPECT_NEAR(arm.positions()[0], 0.1, 1e-9);
}

TEST_F(SimulatedArmTest, TwoArmsGivenTheSameCommandsAgreeExactly) {
  SimulatedArm other{scara_arm(), time};
  for (auto* a : {&arm, &other}) ASSERT_TRUE(a->move_to_positions({2, -1, 0.25}));
  for (int i = 0; i < 37; ++i) {
    time.advance(13ms);
    if (i % 3 == 0) {
      EXPECT_EQ(arm.sample()->positions[0], arm.positions()[0]);  // extra reads change nothing
    }
  }
  EXPECT_EQ(arm.positions(), other.positions());
}

}  // namespace
}  // namespace jaus::test
