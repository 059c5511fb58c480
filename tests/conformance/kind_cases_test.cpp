// The per-kind cases (primitive driver, global and local pose and velocity
// sensors, visual sensor, manipulator) against nodes in this process: on
// each component of a node of ours every case applies to, every case of its
// kind passes and the component is left as found (nobody in control, the
// vehicle not driven, the arm where it was); each case is seen failing,
// with its reason, against a component broken the way it looks for; and
// each says why it does not apply to a component of another kind. On a
// memory network under virtual time.
#include <gtest/gtest.h>

#include <cmath>

#include "broken_components.hpp"
#include "case_results.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/conform/runner.hpp"
#include "kind_node.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using namespace test;

class KindConformance : public ::testing::Test {
 protected:
  void SetUp() override {
    ours = std::make_unique<KindNode>(net.time, net.network);
    broken = std::make_unique<BrokenNode>(net.time, net.network);
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  std::vector<CaseResult> run(const Address& address, std::string only = {}) {
    RunOptions options;
    options.only = std::move(only);
    // The silent-requester case runs on three components in
    // multi_requester_cases_test.cpp, not again here.
    options.skip = "control.silent_requester";
    return net.run_on(*session, address, options);
  }

  // Nobody controls `component` once the runner's last Release Component
  // Control, maybe still on its way, has arrived.
  bool released(const rt::Component& component) {
    return session->run_until([&] { return !component.control().controller().has_value(); }, 3s);
  }

  rt::Component& component_at(const Address& address) {
    auto* found = ours->host().node().find(address);
    if (found == nullptr) throw std::runtime_error("no component at " + address.to_string());
    return *found;
  }

  VirtualNetwork net;
  std::unique_ptr<KindNode> ours;
  std::unique_ptr<BrokenNode> broken;
  std::unique_ptr<ocu::OcuSession> session;
};

struct OurComponent {
  Address address;
  std::vector<std::string_view> passing;  // the case id prefixes that must pass on it (not skip)
};

void PrintTo(const OurComponent& c, std::ostream* out) { *out << c.address.to_string(); }

class OurKindsConform : public KindConformance, public ::testing::WithParamInterface<OurComponent> {};

// Every case that applies passes (core, control and service connection
// cases too: the kinds are components like any other), and those of its
// kind pass rather than skip.
TEST_P(OurKindsConform, EveryApplicableCasePassesAndThoseOfItsKindRun) {
  const OurComponent& tested = GetParam();
  std::vector<double> arm_before;
  if (tested.address == kManipulator) arm_before = ours->host().platform_as<host::ModelPlatform>()->arm()->positions();
  const auto results = run(tested.address);
  ASSERT_EQ(results.size(), all_cases().size() - 1);  // all but the silent-requester case
  for (const auto& r : results) {
    EXPECT_NE(r.outcome.verdict, Verdict::fail) << describe(results);
    for (const auto prefix : tested.passing) {
      if (std::string_view(r.test_case->id).starts_with(prefix)) {
        EXPECT_EQ(r.outcome.verdict, Verdict::pass) << r.test_case->id << "\n" << describe(results);
      }
    }
  }
  // Left as found: nobody in control (once the last Release arrives), the
  // vehicle not driven, the arm back.
  EXPECT_TRUE(released(component_at(tested.address)));
  const components::WrenchEffort effort = ours->host().platform_as<host::ModelPlatform>()->vehicle()->applied_effort();
  EXPECT_EQ(effort.propulsive_linear, components::Axes{});
  EXPECT_EQ(effort.propulsive_rotational, components::Axes{});
  if (!arm_before.empty()) {
    session->run_for(300ms);  // the last restoring Set Joint Positions reaches its target
    const auto arm_after = ours->host().platform_as<host::ModelPlatform>()->arm()->positions();
    ASSERT_EQ(arm_after.size(), arm_before.size());
    for (std::size_t j = 0; j < arm_before.size(); ++j) EXPECT_NEAR(arm_after[j], arm_before[j], 0.01) << j;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Components, OurKindsConform,
    ::testing::Values(OurComponent{kDriver, {"driver."}},
                      OurComponent{kGlobalPoseSensor, {"sensor.global_pose.", "sensor.local_pose."}},
                      OurComponent{kLocalPoseSensor, {"sensor.local_pose."}},
                      OurComponent{kVelocityStateSensor, {"sensor.velocity_state."}},
                      OurComponent{kVisualSensor, {"visual."}}, OurComponent{kManipulator, {"manipulator."}}),
    [](const ::testing::TestParamInfo<OurComponent>& p) {
      return "component_" + std::to_string(p.param.address.component);
    });

// One component broken one way, the case that must catch it, and what its
// failure must say.
struct Broken {
  const char* name;
  Address address;
  std::string_view case_id;
  std::string_view says;
};

void PrintTo(const Broken& b, std::ostream* out) { *out << b.name; }

class BrokenKindsFail : public KindConformance, public ::testing::WithParamInterface<Broken> {};

TEST_P(BrokenKindsFail, TheCaseThatLooksForTheFlawFailsSayingWhy) {
  const Broken& b = GetParam();
  const auto results = run(b.address, std::string(b.case_id));
  ASSERT_EQ(results.size(), 1u) << describe(results);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find(b.says), std::string::npos) << results[0].outcome.detail;
  EXPECT_FALSE(results[0].exchange.empty());
  // Whatever it did, it is left with nobody in control.
  auto* component = broken->node().find(b.address);
  ASSERT_NE(component, nullptr);
  EXPECT_TRUE(released(*component));
}

INSTANTIATE_TEST_SUITE_P(
    Flaws, BrokenKindsFail,
    ::testing::Values(
        Broken{"DriverObeysAnyone", kDriverObeysAnyone, "driver.non_controller_ignored",
               "from a non-controller (controller 0.0.0.0) executed: reported 5.00 %; stopped again"},
        Broken{"DriverForgetsEffort", kDriverForgetsEffort, "driver.effort_reported",
               "Set Wrench Effort 5.00 % from its controller, reported as 0.00 %"},
        Broken{"DriverKeepsEffortOnStop", kDriverKeepsEffortOnStop, "driver.stop_zeroes_effort",
               "Standby while driving at 5.00 % left propulsive linear X at 5.00 %"},
        Broken{"DriverResumesLatchedEffort", kDriverResumesLatchedEffort, "driver.no_resume_after_stop",
               "Standby then Resume resumed the latched effort: 5.00 %"},
        Broken{"SensorFrozenTime", kSensorFrozenTime, "sensor.global_pose.time_advances", " 0.3 s later"},
        Broken{"SensorEchoesQueryPresence", kSensorEchoesQueryPresence, "sensor.global_pose.presence_and",
               "presence vector 0x1FF for 0x1FF asked; Report Services says 0x17F available"},
        Broken{"SensorScElsewhere", kSensorScElsewhere, "sensor.global_pose.query_matches_sc",
               "latitude 45.5 by query, 45.51 .. 45.51 on the service connection"},
        Broken{"CamerasIgnoreSelection", kCamerasIgnoreSelection, "visual.count_and_selection",
               "Select Camera 2 from its controller, then camera 1 reported selected"},
        Broken{"CamerasObeyAnyone", kCamerasObeyAnyone, "visual.non_controller_ignored",
               "Select Camera 2 from a non-controller (controller 0.0.0.0) executed: camera 2 selected; selected back"},
        Broken{"CamerasMislabelFormat", kCamerasMislabelFormat, "visual.image_format",
               "Report Image in JPEG (7), which Report Camera Format Options does not advertise"},
        Broken{"ArmExecutesPartly", kArmExecutesPartly, "manipulator.out_of_range_refused_whole",
               "was executed in part: joint 1 moved"},
        Broken{"ArmObeysAnyone", kArmObeysAnyone, "manipulator.non_controller_ignored",
               "executed: joint 1 moved from 0.0000 to "},
        Broken{"ArmKeepsMovingOnStop", kArmKeepsMovingOnStop, "manipulator.hold_on_stop",
               "after Standby, joint 1 moved from"},
        Broken{"ArmKeepsMovingOnRelease", kArmKeepsMovingOnRelease, "manipulator.hold_on_stop",
               "after Release Component Control, joint 1 moved from"},
        Broken{"DriverKeepsEffortOnReset", kDriverKeepsEffortOnReset, "driver.stop_zeroes_effort",
               "Reset while driving at 5.00 % left propulsive linear X at 5.00 %"},
        Broken{"DriverKeepsEffortOnTakeover", kDriverKeepsEffortOnTakeover, "driver.stop_zeroes_effort",
               "a takeover by a higher authority while driving at 5.00 % left propulsive linear X at 5.00 %"},
        Broken{"ArmMiscountsJoints", kArmMiscountsJoints, "manipulator.joint_count",
               "Report Joint Velocities lists 4 joints, its specifications 3"}),
    [](const ::testing::TestParamInfo<Broken>& p) { return std::string(p.param.name); });

// Every per-kind case says why it does not apply to a component of another
// kind (the node manager), and sends it nothing.
TEST_F(KindConformance, PerKindCasesSayWhyTheyDoNotApplyToOtherComponents) {
  auto manager = learn_component(*session, kKindManager, nullptr, 1s);
  ASSERT_TRUE(manager) << manager.error().message();
  for (auto suite : {primitive_driver_cases(), sensor_cases(), visual_sensor_cases(), manipulator_cases()}) {
    for (const auto& c : suite) {
      ASSERT_TRUE(c.not_applicable) << c.id;
      const std::string why = c.not_applicable(*manager);
      EXPECT_TRUE(std::string_view(why).starts_with("it does not accept ")) << c.id << ": " << why;
    }
  }
  // A driver that reports no propulsive linear X effort is not one these cases can drive.
  ComponentUnderTest steering_only = *manager;
  steering_only.services_known = true;
  steering_only.inputs = {msg::SetWrenchEffort::code, msg::QueryWrenchEffort::code};
  steering_only.outputs[msg::ReportWrenchEffort::code] = 1u << 5;
  EXPECT_EQ(primitive_driver_cases()[0].not_applicable(steering_only), "it reports no propulsive linear X effort");
}

}  // namespace
}  // namespace jaus::conform
