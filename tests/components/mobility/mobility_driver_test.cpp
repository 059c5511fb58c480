// components::MobilityDriver, the base of every driver above the primitive
// driver, on a whole vehicle node under virtual time (drive_node.hpp): a test
// driver that drives straight ahead for a few metres shows that it drives
// the vehicle only through the primitive driver over JAUS, and that every
// way a motion ends leaves the vehicle commanded to stop, with nothing
// restarting it.
#include <cmath>

#include "drive_node.hpp"
#include "jaus/components/mobility_driver.hpp"

namespace jaus::test {
namespace {

const Address kTestDriver{1, 1, 45, 1};

// Straight ahead at `effort_percent` until `distance_m` from where the motion started.
class StraightDriver final : public components::MobilityDriver {
 public:
  StraightDriver(rt::ComponentConfig config, rt::Environment env, components::PoseSource& pose)
      : MobilityDriver(std::move(config), std::move(env), pose, components::MobilityDriverOptions{}) {
    handle<msg::Resume>(Access::controller, false, [](const Header&, const msg::Resume&) {});
  }
  void go() { engage("test"); }
  void stop() { halt("test stop"); }
  double distance_m = 3;
  double effort_percent = 40;
  int started = 0;
  std::vector<std::string> halts;

 protected:
  Step step(const components::PoseSample& pose, double) override {
    const auto& p = *pose.local_position;
    if (!start_) start_ = p;
    if (std::hypot(p.x_m - start_->x_m, p.y_m - start_->y_m) >= distance_m) return Step::arrived("3 m driven");
    components::WrenchEffort e;
    e.propulsive_linear.x = effort_percent;
    return Step::drive(e);
  }
  void motion_started() override {
    ++started;
    start_.reset();
  }
  void motion_halted(std::string_view why) override { halts.emplace_back(why); }

 private:
  std::optional<components::LocalPosition> start_;
};

class MobilityDriverTest : public ::testing::TestWithParam<PlatformUnderTest> {
 protected:
  MobilityDriverTest() : node_(DriveNodeOptions{.platform = GetParam()}) {
    auto config = node_.host().component_config("test driver", kTestDriver.component);
    config.authority = 1;
    driver_ = &node_.host().emplace<StraightDriver>(config, *node_.host().backends().find<components::PoseSource>());
    driver_->start();
    EXPECT_TRUE(node_.wait_ready());
  }
  bool moving() { return node_.speed_mps() > 0.05; }
  bool stopped() { return node_.speed_mps() < 0.01; }
  double commanded_linear() { return *node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent; }

  DriveNode node_;
  StraightDriver* driver_ = nullptr;
};

TEST_P(MobilityDriverTest, WaitsInInitializeForTheSpecificationsThenKnowsTheVehicle) {
  ASSERT_TRUE(driver_->limits());
  EXPECT_EQ(driver_->limits()->steering, components::Steering::differential);
  EXPECT_NEAR(driver_->limits()->max_speed_mps, 1.0, 0.01);
}

TEST_P(MobilityDriverTest, DrivesThroughThePrimitiveDriverAndStopsOnArrival) {
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return driver_->commanding(); }, 2s));
  // Control of the primitive driver, with the driver's own authority.
  const auto& controller = node_.primitive_driver().control().controller();
  ASSERT_TRUE(controller);
  EXPECT_EQ(controller->address, kTestDriver);
  EXPECT_EQ(controller->authority, 1);
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 3s));
  ASSERT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 20s));
  EXPECT_EQ(driver_->mobility_counters().arrivals, 1u);
  EXPECT_EQ(driver_->last_halt(), "3 m driven");
  // Zero below, and control given back.
  EXPECT_EQ(commanded_linear(), 0);
  EXPECT_FALSE(node_.primitive_driver().control().controller());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
}

TEST_P(MobilityDriverTest, AnOperatorTakingThePrimitiveDriverStopsTheMotionAndNothingRestartsIt) {
  driver_->distance_m = 100;
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 3s));
  ASSERT_TRUE(node_.take_control(kPrimitiveDriver));  // authority 5 > 1
  EXPECT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 1s));
  EXPECT_EQ(driver_->mobility_counters().control_losses, 1u);
  EXPECT_NE(driver_->last_halt().find("Reject"), std::string::npos) << driver_->last_halt();
  // Its Report Component Status says so.
  const auto status = node_.ask<msg::ReportComponentStatus>(kTestDriver, msg::QueryComponentStatus{});
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->secondary_status & components::mobility_status::kLostControl);
  EXPECT_FALSE(status->secondary_status & components::mobility_status::kDriving);
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  const auto efforts = driver_->mobility_counters().efforts_sent;
  node_.run_for(3s);
  EXPECT_EQ(driver_->mobility_counters().efforts_sent, efforts);
  EXPECT_TRUE(stopped());
}

TEST_P(MobilityDriverTest, SetEmergencyOnThePrimitiveDriverStopsItAndClearEmergencyDoesNotRestart) {
  driver_->distance_m = 100;
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 3s));
  node_.send(kPrimitiveDriver, msg::SetEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 1s));
  EXPECT_NE(driver_->last_halt().find("Emergency"), std::string::npos) << driver_->last_halt();
  node_.send(kPrimitiveDriver, msg::ClearEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(kPrimitiveDriver) == rt::PrimaryStatus::ready; }, 1s));
  node_.run_for(3s);
  EXPECT_FALSE(driver_->driving());
  EXPECT_TRUE(stopped());
  EXPECT_FALSE(node_.primitive_driver().control().controller());
}

// Issue 42: Set then Clear Emergency back to back, between two of the
// driver's status queries: the primitive driver is Ready again before the
// driver's next query, yet the driver has seen the stop (reported to it at
// once, and counted in every later report) and stops for good.
TEST_P(MobilityDriverTest, AnEmergencySetAndClearedBetweenTwoStatusQueriesStopsTheDriverForGood) {
  driver_->distance_m = 100;
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 3s));
  const auto stops_before = node_.primitive_driver().counters().stops_entered;
  node_.send(kPrimitiveDriver, msg::SetEmergency{{1}});
  node_.send(kPrimitiveDriver, msg::ClearEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 1s));
  EXPECT_EQ(node_.primitive_driver().counters().stops_entered, stops_before + 1);
  EXPECT_EQ(node_.state_of(kPrimitiveDriver), rt::PrimaryStatus::ready);
  node_.run_for(3s);
  EXPECT_FALSE(driver_->driving());
  EXPECT_TRUE(stopped());
  EXPECT_FALSE(node_.primitive_driver().control().controller());
}

TEST_P(MobilityDriverTest, EveryStopPathOfTheDriverItselfCommandsZeroBelow) {
  driver_->distance_m = 100;
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 3s));
  ASSERT_TRUE(node_.take_control(kTestDriver));
  node_.send(kTestDriver, msg::Standby{});
  ASSERT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 1s));
  EXPECT_EQ(commanded_linear(), 0);
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  EXPECT_EQ(driver_->halts.size(), 1u);
}

TEST_P(MobilityDriverTest, APrimitiveDriverHeldByAnOperatorRefusesTheDriver) {
  ASSERT_TRUE(node_.take_control(kPrimitiveDriver));
  driver_->go();
  ASSERT_TRUE(node_.run_until([&] { return !driver_->driving(); }, 2s));
  EXPECT_NE(driver_->last_halt().find("refused"), std::string::npos) << driver_->last_halt();
  EXPECT_EQ(node_.primitive_driver().control().controller()->address, kOperator);
}

INSTANTIATE_TEST_SUITE_P(Platforms, MobilityDriverTest,
                         ::testing::Values(PlatformUnderTest::model, PlatformUnderTest::clearpath_sim),
                         [](const auto& test_param) { return platform_name(test_param.param); });

}  // namespace
}  // namespace jaus::test
