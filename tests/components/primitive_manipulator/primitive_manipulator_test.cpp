// The primitive manipulator on a simulated arm, under virtual time: every
// command moves the arm, every query is answered with what the arm does,
// bad commands are refused whole, and every stop path holds the arm.
#include <algorithm>
#include <set>

#include "arms.hpp"
#include "harness.hpp"
#include "jaus/components/manipulator_reports.hpp"
#include "jaus/components/primitive_manipulator.hpp"
#include "jaus/components/simulated_arm.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using components::JointQuantity;
using components::PrimitiveManipulator;
using components::SimulatedArm;
using Motion = PrimitiveManipulator::Motion;
namespace kin = components::kinematics;

const Address kManipulator{1, 1, 49, 1};
const std::vector<double> kPumaPose{0.3, -0.4, 0.5, 0.2, -0.7, 0.9};

void expect_positions(const std::vector<double>& actual, const std::vector<double>& expected, double tol) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) EXPECT_NEAR(actual[i], expected[i], tol) << "joint " << i + 1;
}

class PrimitiveManipulatorTest : public ::testing::Test {
 protected:
  PrimitiveManipulatorTest() { make(scara_arm()); }

  void make(components::ArmConfig config, components::PrimitiveManipulatorOptions options = {}) {
    manipulator.reset();
    geometry = config;
    arm = std::make_unique<SimulatedArm>(std::move(config), time);
    rt::ComponentConfig c;
    c.name = "primitive manipulator";
    c.address = kManipulator;
    c.authority = 5;
    c.controller_timeout = controller_timeout;
    outbox.clock = &time;
    manipulator = std::make_unique<PrimitiveManipulator>(
        c, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); }},
        *arm, options);
    manipulator->start();
  }

  template <class M>
  void deliver(const Address& from, const M& m) {
    deliver_to(*manipulator, time, from, m);
  }
  void take_control(const Address& ocu, std::uint8_t authority = 5) {
    deliver(ocu, msg::RequestComponentControl{{authority}});
    ASSERT_TRUE(manipulator->control().is_controller(ocu));
  }
  template <class Report, class Query>
  Report query(const Address& from, const Query& q) {
    outbox.clear();
    deliver(from, q);
    const auto reports = outbox.to<Report>(from);
    EXPECT_EQ(reports.size(), 1u) << Report::name;
    return reports.empty() ? Report{} : reports.back();
  }

  // Commands in SI units (rad or m per joint), converted as an OCU would.
  void set_positions(const Address& from, const std::vector<double>& q) {
    msg::SetJointPositions m;
    m.positions_rad = components::joint_values_to_wire(geometry, q, JointQuantity::position);
    deliver(from, m);
  }
  void set_velocities(const Address& from, const std::vector<double>& v) {
    msg::SetJointVelocities m;
    m.velocities_rps = components::joint_values_to_wire(geometry, v, JointQuantity::velocity);
    deliver(from, m);
  }
  void set_efforts(const Address& from, const std::vector<double>& e) {
    msg::SetJointEfforts m;
    m.efforts_percent = e;
    deliver(from, m);
  }
  msg::JointMotionPoint point(std::size_t joint, double position, double max_velocity = 0, double accel = 0,
                              double decel = 0) const {
    const bool p = geometry.joints[joint].prismatic;
    return {components::joint_value_to_wire(position, p, JointQuantity::position),
            components::joint_value_to_wire(max_velocity, p, JointQuantity::velocity),
            components::joint_value_to_wire(accel, p, JointQuantity::acceleration),
            components::joint_value_to_wire(decel, p, JointQuantity::acceleration)};
  }
  static msg::SetEndEffectorPose pose_message(const kin::Pose& pose) {
    const kin::Quaternion q = kin::to_quaternion(pose.orientation);
    msg::SetEndEffectorPose m;
    m.x_m = pose.position.x;
    m.y_m = pose.position.y;
    m.z_m = pose.position.z;
    m.quaternion_d = q.d;
    m.quaternion_a = q.a;
    m.quaternion_b = q.b;
    m.quaternion_c = q.c;
    return m;
  }
  void expect_pose_near(const kin::Pose& target, double tol) {
    const auto pose = manipulator->end_effector_pose();
    ASSERT_TRUE(pose);
    EXPECT_LE(kin::norm(pose->position - target.position), tol);
    EXPECT_LE(kin::norm(kin::rotation_error(pose->orientation, target.orientation)), tol);
  }

  bool logged(const std::string& text) const { return any_line_contains(logs, text); }
  const components::PrimitiveManipulatorCounters& counters() const { return manipulator->manipulator_counters(); }

  // The OCUs here send nothing between commands: control is kept for the
  // longest test unless a test is about the controller's silence.
  rt::Duration controller_timeout = std::chrono::seconds(60);
  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  components::ArmConfig geometry;
  std::unique_ptr<SimulatedArm> arm;
  std::unique_ptr<PrimitiveManipulator> manipulator;
};

// ---- Queries ----------------------------------------------------------------

TEST_F(PrimitiveManipulatorTest, SpecificationsComeFromTheArmsGeometryForAnyone) {
  EXPECT_EQ(manipulator->state(), msg::PrimaryStatus::ready);
  const auto r = query<msg::ReportManipulatorSpecifications>(kOcuB, msg::QueryManipulatorSpecifications{});
  EXPECT_EQ(r.joint_count, 3);
  EXPECT_EQ(r.last_joint_type, 2);  // the quill
  EXPECT_NEAR(r.last_joint_max_rad_or_m, 0.3, 0.0005);
  EXPECT_NEAR(r.last_joint_max_velocity_rps_or_mps, 0.2, 0.0005);
  ASSERT_EQ(r.joints.size(), 2u);
  EXPECT_NEAR(r.joints[0].link_length_m, 0.5, 0.0005);
  EXPECT_NEAR(r.joints[0].offset_rad_or_m, 0.4, 0.0005);
  EXPECT_NEAR(r.joints[1].twist_angle_rad, kPi, 0.0005);
  EXPECT_NEAR(r.joints[1].max_velocity_rps_or_mps, 0.5, 0.0005);
  EXPECT_NEAR(r.frame_quaternion_d, 1, 1e-6);
}

TEST_F(PrimitiveManipulatorTest, JointQueriesReportTheInitialState) {
  const auto positions = query<msg::ReportJointPositions>(kOcuB, msg::QueryJointPositions{});
  expect_positions(components::joint_values_from_wire(geometry, positions.positions_rad, JointQuantity::position),
                   {0, 0, 0.1}, 1e-7);
  const auto velocities = query<msg::ReportJointVelocities>(kOcuB, msg::QueryJointVelocities{});
  expect_positions(velocities.velocities_rps, {0, 0, 0}, 1e-7);
  const auto efforts = query<msg::ReportJointEfforts>(kOcuB, msg::QueryJointEfforts{});
  expect_positions(efforts.efforts_percent, {0, 0, 0}, 0.01);
  const auto forces = query<msg::ReportJointForceTorques>(kOcuB, msg::QueryJointForceTorques{});
  expect_positions(forces.force_torques_nm, {0, 0, 0}, 1e-5);
  const auto tool = query<msg::ReportToolPoint>(kOcuB, msg::QueryToolPoint{});
  EXPECT_EQ(tool, msg::ReportToolPoint{});
}

// ---- Each command changes the arm -------------------------------------------

TEST_F(PrimitiveManipulatorTest, JointPositionsMoveTheArmAndNeedNoRenewal) {
  take_control(kOcuA);
  set_positions(kOcuA, {1.0, -0.5, 0.25});
  EXPECT_EQ(manipulator->motion(), Motion::positions);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::positions);
  time.advance(500ms);
  expect_positions(arm->positions(), {0.5, -0.25, 0.2}, 1e-6);  // at the speed limits
  time.advance(5s);  // far beyond the command timeout: a position target is kept
  expect_positions(arm->positions(), {1.0, -0.5, 0.25}, 1e-6);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::positions);
  EXPECT_EQ(counters().command_timeouts, 0u);
  const auto r = query<msg::ReportJointPositions>(kOcuB, msg::QueryJointPositions{});
  expect_positions(components::joint_values_from_wire(geometry, r.positions_rad, JointQuantity::position),
                   {1.0, -0.5, 0.25}, 1e-6);
  EXPECT_EQ(counters().commands_applied, 1u);
}

TEST_F(PrimitiveManipulatorTest, JointVelocitiesMoveTheArmAndAreReported) {
  take_control(kOcuA);
  set_velocities(kOcuA, {0.5, -0.25, 0.1});
  time.advance(200ms);
  expect_positions(arm->positions(), {0.1, -0.05, 0.12}, 1e-6);
  const auto r = query<msg::ReportJointVelocities>(kOcuB, msg::QueryJointVelocities{});
  expect_positions(components::joint_values_from_wire(geometry, r.velocities_rps, JointQuantity::velocity),
                   {0.5, -0.25, 0.1}, 1e-6);
  EXPECT_EQ(manipulator->motion(), Motion::velocities);
}

TEST_F(PrimitiveManipulatorTest, EffortsMoveTheArmAndTheirForceTorquesAreReported) {
  take_control(kOcuA);
  set_efforts(kOcuA, {50, -20, 100});
  time.advance(100ms);
  // 50 % of 1 rad/s, -20 % of 0.5 rad/s, 100 % of 0.2 m/s.
  expect_positions(arm->positions(), {0.05, -0.01, 0.12}, 1e-5);
  const auto efforts = query<msg::ReportJointEfforts>(kOcuB, msg::QueryJointEfforts{});
  expect_positions(efforts.efforts_percent, {50, -20, 100}, 0.01);
  const auto forces = query<msg::ReportJointForceTorques>(kOcuB, msg::QueryJointForceTorques{});
  // 50 % of 10 N m, -20 % of 10 N m, 100 % of 100 N (the quill's, on the prismatic scale).
  expect_positions(components::joint_values_from_wire(geometry, forces.force_torques_nm, JointQuantity::force_torque),
                   {5, -2, 100}, 1e-3);  // the efforts' 16-bit steps
  EXPECT_NEAR(forces.force_torques_nm[2], 200, 1e-3);  // 100 N is 200 on the revolute scale
}

TEST_F(PrimitiveManipulatorTest, ToolPointMovesTheEndEffectorPoseNotTheArm) {
  take_control(kOcuA);
  const auto before = manipulator->end_effector_pose();
  ASSERT_TRUE(before);
  deliver(kOcuB, msg::SetToolPoint{{1, 1, 1}});  // not the controller: ignored
  deliver(kOcuA, msg::SetToolPoint{{0.1, 0, 0.05}});
  const auto tool = query<msg::ReportToolPoint>(kOcuB, msg::QueryToolPoint{});
  EXPECT_NEAR(tool.x_m, 0.1, 1e-7);
  EXPECT_NEAR(tool.y_m, 0, 1e-7);
  EXPECT_NEAR(tool.z_m, 0.05, 1e-7);
  const auto after = manipulator->end_effector_pose();
  ASSERT_TRUE(after);
  // The SCARA's end effector is flipped (pi about x): (0.1, 0, 0.05) lies at (+0.1, 0, -0.05).
  EXPECT_NEAR(after->position.x - before->position.x, 0.1, 1e-6);
  EXPECT_NEAR(after->position.z - before->position.z, -0.05, 1e-6);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
}

TEST_F(PrimitiveManipulatorTest, EndEffectorPoseIsReachedThroughInverseKinematics) {
  make(puma_arm());
  take_control(kOcuA);
  deliver(kOcuA, msg::SetToolPoint{{0, 0, 0.1}});
  const kin::Pose target = manipulator->kinematics().tool_pose(kPumaPose, {0, 0, 0.1});
  deliver(kOcuA, pose_message(target));
  EXPECT_EQ(manipulator->motion(), Motion::positions);
  time.advance(5s);
  expect_pose_near(target, 1e-3);
}

TEST_F(PrimitiveManipulatorTest, EndEffectorVelocityMovesTheToolThenTimesOut) {
  make(puma_arm());
  take_control(kOcuA);
  set_positions(kOcuA, kPumaPose);
  time.advance(3s);
  const auto start = manipulator->end_effector_pose();
  ASSERT_TRUE(start);
  msg::SetEndEffectorVelocityState m;
  m.coordinate_system = 1;
  m.linear_x_mps = 0.05;  // no rotation: the point at the vehicle origin moves like the tool
  for (int i = 0; i < 5; ++i) {
    deliver(kOcuA, m);
    EXPECT_EQ(manipulator->motion(), Motion::end_effector_velocity);
    time.advance(200ms);
  }
  kin::Pose expected = *start;
  expected.position.x += 0.05;
  expect_pose_near(expected, 3e-3);
  // Not renewed: the arm holds after the command timeout.
  time.advance(400ms);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
  EXPECT_EQ(counters().command_timeouts, 1u);
  const auto held = arm->positions();
  time.advance(2s);
  EXPECT_EQ(arm->positions(), held);
}

TEST_F(PrimitiveManipulatorTest, EndEffectorVelocityInTheEndEffectorsFrame) {
  make(puma_arm());
  take_control(kOcuA);
  set_positions(kOcuA, kPumaPose);
  time.advance(3s);
  const auto start = manipulator->end_effector_pose();
  ASSERT_TRUE(start);
  msg::SetEndEffectorVelocityState m;
  m.coordinate_system = 2;
  m.linear_z_mps = 0.04;  // along the end effector's own z (the tool point is its origin here)
  for (int i = 0; i < 4; ++i) {
    deliver(kOcuA, m);
    time.advance(100ms);
  }
  kin::Pose expected = *start;
  expected.position = expected.position + 0.016 * expected.orientation.column(2);
  expect_pose_near(expected, 2e-3);
}

TEST_F(PrimitiveManipulatorTest, JointMotionReachesEachPoseAtItsTime) {
  take_control(kOcuA);
  msg::SetJointMotion m;
  m.joint_count = 3;
  m.poses = {{2.0, {point(0, 1.0, 0, 2, 2), point(1, -0.5), point(2, 0.2, 0.1)}},
             {4.0, {point(0, 0.0), point(1, 0.0), point(2, 0.1)}}};
  deliver(kOcuA, m);
  EXPECT_EQ(manipulator->motion(), Motion::joint_motion);
  time.advance(1s);
  expect_positions(arm->positions(), {0.5, -0.25, 0.15}, 0.02);  // half way (the shoulder's trapezoid is symmetric)
  time.advance(1s);
  expect_positions(arm->positions(), {1.0, -0.5, 0.2}, 0.01);
  time.advance(2s);
  expect_positions(arm->positions(), {0.0, 0.0, 0.1}, 0.01);
  time.advance(100ms);
  expect_positions(arm->positions(), {0.0, 0.0, 0.1}, 1e-6);
  EXPECT_EQ(manipulator->motion(), Motion::positions);
  EXPECT_EQ(counters().motions_completed, 1u);
}

TEST_F(PrimitiveManipulatorTest, EndEffectorPathMotionPassesThroughEachPose) {
  make(puma_arm());
  take_control(kOcuA);
  const kin::Pose a = manipulator->kinematics().tool_pose(kPumaPose, {});
  const kin::Pose b = manipulator->kinematics().tool_pose({0.5, -0.2, 0.3, 0.4, -0.5, 0.7}, {});
  msg::SetEndEffectorPathMotion m;
  for (const auto& [t, pose] : {std::pair{8.0, a}, std::pair{16.0, b}}) {
    const auto q = kin::to_quaternion(pose.orientation);
    m.poses.push_back({t, pose.position.x, pose.position.y, pose.position.z, q.d, q.a, q.b, q.c});
  }
  deliver(kOcuA, m);
  ASSERT_EQ(manipulator->motion(), Motion::path_motion) << (logs.empty() ? "" : logs.back());
  time.advance(8s);
  expect_pose_near(a, 5e-3);
  time.advance(8100ms);
  expect_pose_near(b, 2e-3);
  EXPECT_EQ(counters().motions_completed, 1u);
}

// ---- Refusals ---------------------------------------------------------------

TEST_F(PrimitiveManipulatorTest, AWrongJointCountIsRefusedWholeAndCounted) {
  take_control(kOcuA);
  set_positions(kOcuA, {0.5, 0.5, 0.2});
  time.advance(2s);
  const auto before = arm->positions();
  set_positions(kOcuA, {0.1, 0.1});
  set_velocities(kOcuA, {0.1, 0.1, 0.1, 0.1});
  set_efforts(kOcuA, {10});
  msg::SetJointMotion motion;
  motion.joint_count = 2;
  motion.poses = {{1.0, {point(0, 0.1), point(1, 0.1)}}};
  deliver(kOcuA, motion);
  EXPECT_EQ(counters().refused_joint_count, 4u);
  EXPECT_TRUE(logged("Set Joint Positions from 2.1.40.1 refused"));
  EXPECT_TRUE(logged("2 joint values for an arm of 3 joints"));
  EXPECT_TRUE(logged("4 joint values for an arm of 3 joints"));
  time.advance(2s);
  EXPECT_EQ(arm->positions(), before);
  EXPECT_EQ(manipulator->motion(), Motion::positions);  // the last good command still holds
  EXPECT_EQ(counters().commands_applied, 1u);
}

TEST_F(PrimitiveManipulatorTest, ValuesOutOfLimitsAreRefusedWholeNamingTheJoint) {
  take_control(kOcuA);
  set_positions(kOcuA, {0.5, 3.0, 0.2});  // elbow limit 2.5 rad
  EXPECT_TRUE(logged("joint 2 (elbow): position 3"));
  set_positions(kOcuA, {0.5, 0.5, 0.35});  // quill stroke 0.3 m
  EXPECT_TRUE(logged("joint 3 (quill): position 0.35"));
  set_velocities(kOcuA, {0.1, 0.6, 0});  // elbow speed limit 0.5 rad/s
  EXPECT_TRUE(logged("joint 2 (elbow): velocity 0.6"));
  msg::SetJointMotion motion;
  motion.joint_count = 3;
  motion.poses = {{5.0, {point(0, 0.1), point(1, 0.1, 0.8), point(2, 0.1)}}};  // elbow max velocity beyond its limit
  deliver(kOcuA, motion);
  EXPECT_EQ(counters().refused_out_of_limits, 4u);
  msg::SetEndEffectorVelocityState twist;
  twist.coordinate_system = 3;
  deliver(kOcuA, twist);
  EXPECT_EQ(counters().refused_out_of_limits, 5u);

  // Unreachable: a pose 10 m away, a pose in time, a twist a SCARA cannot give.
  msg::SetEndEffectorPose far;
  far.x_m = 10;
  deliver(kOcuA, far);
  motion.poses = {{0.5, {point(0, 1.0), point(1, 0.0), point(2, 0.1)}}};  // 1 rad in 0.5 s at 1 rad/s
  deliver(kOcuA, motion);
  twist.coordinate_system = 1;
  twist.angular_x_rps = 0.5;  // tilting
  deliver(kOcuA, twist);
  EXPECT_EQ(counters().refused_unreachable, 3u);
  EXPECT_TRUE(logged("Set End-Effector Pose from 2.1.40.1 refused (nothing moved): pose unreachable"));
  EXPECT_TRUE(logged("pose 1 at 0.5 s: joint 1 (shoulder) cannot move 1"));

  time.advance(2s);
  EXPECT_EQ(arm->positions(), (std::vector<double>{0, 0, 0.1}));
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
  EXPECT_EQ(counters().commands_applied, 0u);
}

TEST_F(PrimitiveManipulatorTest, CommandsFromANonControllerOrOutsideReadyNeverReachTheArm) {
  set_positions(kOcuA, {0.5, 0.5, 0.2});  // nobody in control
  take_control(kOcuA);
  set_positions(kOcuB, {0.5, 0.5, 0.2});  // not the controller
  deliver(kOcuA, msg::Standby{});
  set_positions(kOcuA, {0.5, 0.5, 0.2});  // the controller, but in Standby
  time.advance(2s);
  EXPECT_EQ(arm->positions(), (std::vector<double>{0, 0, 0.1}));
  EXPECT_EQ(counters().commands_applied, 0u);
}

// ---- Safety: every stop holds the arm where it is ----------------------------

class StopPaths : public PrimitiveManipulatorTest {
 protected:
  // Moves the joints, then checks `trigger` holds the arm, and that nothing
  // moves it again (through `recover` and 2 s more) until a new command.
  template <class Trigger, class Recover>
  void expect_hold_and_no_resume(const std::string& what, Trigger trigger, Recover recover) {
    SCOPED_TRACE(what);
    set_velocities(kOcuA, {0.1, -0.1, 0.01});
    ASSERT_EQ(arm->mode(), SimulatedArm::Mode::velocities);
    time.advance(100ms);
    const auto holds_before = arm->holds();
    trigger();
    ASSERT_GT(arm->holds(), holds_before) << "no hold";
    EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
    EXPECT_EQ(manipulator->motion(), Motion::holding);
    const auto held = arm->positions();
    recover();
    time.advance(2s);
    EXPECT_EQ(arm->positions(), held) << "the arm moved without a new command";
    EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
  }
};

TEST_F(StopPaths, EveryStopPathHoldsTheArmAndNothingResumes) {
  take_control(kOcuA);
  expect_hold_and_no_resume(
      "standby", [&] { deliver(kOcuA, msg::Standby{}); }, [&] { deliver(kOcuA, msg::Resume{}); });
  ASSERT_EQ(manipulator->state(), msg::PrimaryStatus::ready);

  expect_hold_and_no_resume(
      "emergency", [&] { deliver(kOcuB, msg::SetEmergency{{1}}); }, [&] { deliver(kOcuB, msg::ClearEmergency{{1}}); });
  ASSERT_EQ(manipulator->state(), msg::PrimaryStatus::ready);

  expect_hold_and_no_resume(
      "reset", [&] { deliver(kOcuA, msg::Reset{}); }, [&] { take_control(kOcuA); });
  ASSERT_EQ(manipulator->state(), msg::PrimaryStatus::ready);
  take_control(kOcuA);

  expect_hold_and_no_resume(
      "control released", [&] { deliver(kOcuA, msg::ReleaseComponentControl{}); }, [&] { take_control(kOcuA); });

  expect_hold_and_no_resume(
      "control taken over", [&] { take_control(kOcuB, 9); },
      [&] {
        deliver(kOcuB, msg::ReleaseComponentControl{});
        take_control(kOcuA);
      });

  expect_hold_and_no_resume(
      "command timeout", [&] { time.advance(500ms); }, [] {});
  EXPECT_EQ(counters().command_timeouts, 1u);

  expect_hold_and_no_resume(
      "shutdown", [&] { deliver(kOcuA, msg::Shutdown{}); }, [] {});
  EXPECT_EQ(manipulator->state(), msg::PrimaryStatus::shutdown);
}

TEST_F(StopPaths, EffortsTimeOutLikeVelocities) {
  take_control(kOcuA);
  for (int i = 0; i < 5; ++i) {
    set_efforts(kOcuA, {30, 0, 0});
    time.advance(400ms);  // renewed within the 0.5 s timeout each time
  }
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::efforts);
  time.advance(150ms);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
  EXPECT_EQ(counters().command_timeouts, 1u);
  EXPECT_TRUE(manipulator->control().is_controller(kOcuA));  // control is kept
  const auto efforts = query<msg::ReportJointEfforts>(kOcuB, msg::QueryJointEfforts{});
  expect_positions(efforts.efforts_percent, {0, 0, 0}, 0.01);  // holding still: no effort
}

TEST_F(StopPaths, ControllerSilenceHoldsTheArm) {
  components::PrimitiveManipulatorOptions options;
  options.command_timeout = rt::Duration::zero();  // only the controller's liveness is at work
  controller_timeout = std::chrono::seconds(3);
  make(scara_arm(), options);
  take_control(kOcuA);
  set_velocities(kOcuA, {0.1, 0.1, 0.01});
  time.advance(2s);
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::velocities);  // no command timeout configured
  time.advance(2s);                                        // 4 s of silence > 3 s controller timeout
  EXPECT_FALSE(manipulator->control().is_controller(kOcuA));
  EXPECT_EQ(arm->mode(), SimulatedArm::Mode::holding);
  const auto held = arm->positions();
  time.advance(2s);
  EXPECT_EQ(arm->positions(), held);
}

TEST_F(StopPaths, AStopCancelsATimedMotionForGood) {
  take_control(kOcuA);
  msg::SetJointMotion m;
  m.joint_count = 3;
  m.poses = {{4.0, {point(0, 2.0), point(1, 1.0), point(2, 0.3)}}};
  deliver(kOcuA, m);
  time.advance(1s);
  deliver(kOcuA, msg::Standby{});
  const auto held = arm->positions();
  EXPECT_GT(held[0], 0.3);
  deliver(kOcuA, msg::Resume{});
  time.advance(5s);
  EXPECT_EQ(arm->positions(), held);
  EXPECT_EQ(manipulator->motion(), Motion::holding);
  EXPECT_EQ(counters().motions_completed, 0u);
}

// ---- Reset: an arm that has homing homes --------------------------------------

// A simulated arm with homing, recording what the component asks of it.
class HomingArm final : public components::ManipulatorArm {
 public:
  HomingArm(components::ArmConfig config, const rt::Clock& clock) : arm_(std::move(config), clock) {}
  const components::ArmConfig& geometry() const override { return arm_.geometry(); }
  Expected<void> move_to_positions(const std::vector<double>& p) override { return arm_.move_to_positions(p); }
  Expected<void> move_at_velocities(const std::vector<double>& v) override { return arm_.move_at_velocities(v); }
  Expected<void> apply_efforts(const std::vector<double>& e) override { return arm_.apply_efforts(e); }
  void hold() override {
    calls.push_back("hold");
    arm_.hold();
  }
  std::optional<components::JointSample> sample() const override { return arm_.sample(); }
  void home() override { calls.push_back("home"); }

  std::vector<std::string> calls;

 private:
  SimulatedArm arm_;
};

TEST_F(PrimitiveManipulatorTest, ResetHomesAnArmThatHasHomingButNotUnderAnEmergency) {
  HomingArm homing(scara_arm(), time);
  rt::ComponentConfig c;
  c.name = "primitive manipulator";
  c.address = kManipulator;
  c.authority = 5;
  c.controller_timeout = controller_timeout;
  PrimitiveManipulator m(c, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); }},
                         homing);
  m.start();
  EXPECT_EQ(std::count(homing.calls.begin(), homing.calls.end(), "home"), 0);  // starting is no Reset

  deliver_to(m, time, kOcuA, msg::RequestComponentControl{{5}});
  homing.calls.clear();
  deliver_to(m, time, kOcuA, msg::Reset{});
  EXPECT_EQ(homing.calls, (std::vector<std::string>{"hold", "home"}));  // held first, then homed
  EXPECT_EQ(m.state(), msg::PrimaryStatus::ready);

  deliver_to(m, time, kOcuB, msg::SetEmergency{{1}});
  deliver_to(m, time, kOcuA, msg::RequestComponentControl{{5}});
  homing.calls.clear();
  deliver_to(m, time, kOcuA, msg::Reset{});
  EXPECT_EQ(std::count(homing.calls.begin(), homing.calls.end(), "home"), 0);
  EXPECT_EQ(m.state(), msg::PrimaryStatus::emergency);
  EXPECT_TRUE(logged("arm not homed (emergency latched)"));
}

// ---- Service connections, services, configuration -----------------------------

TEST_F(PrimitiveManipulatorTest, ReportsStreamOnServiceConnections) {
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportJointPositions::code, 10, 0}});
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportJointForceTorques::code, 5, 0}});
  take_control(kOcuA);
  set_positions(kOcuA, {0.5, 0, 0.1});
  time.advance(1s);
  const auto positions = outbox.to<msg::ReportJointPositions>(kOcuB);
  ASSERT_GE(positions.size(), 10u);
  EXPECT_NEAR(positions.back().positions_rad[0], 0.5, 1e-6);
  EXPECT_LT(positions.front().positions_rad[0], 0.2);  // the stream followed the motion
  EXPECT_GE(outbox.to<msg::ReportJointForceTorques>(kOcuB).size(), 5u);
}

TEST_F(PrimitiveManipulatorTest, ServicesListWhatItAcceptsAndProvides) {
  const auto entry = manipulator->service_entry();
  EXPECT_EQ(entry.type, 49);
  std::set<std::uint16_t> inputs, outputs;
  for (const auto& i : entry.inputs) inputs.insert(i.command_code);
  for (const auto& o : entry.outputs) outputs.insert(o.command_code);
  for (std::uint16_t code = 0x0601; code <= 0x0608; ++code) EXPECT_TRUE(inputs.contains(code)) << code;
  for (std::uint16_t code = 0x2600; code <= 0x2605; ++code) EXPECT_TRUE(inputs.contains(code)) << code;
  for (std::uint16_t code = 0x4600; code <= 0x4605; ++code) EXPECT_TRUE(outputs.contains(code)) << code;
}

TEST_F(PrimitiveManipulatorTest, AnArmThatCannotBeRunIsAFailure) {
  auto bad = scara_arm();
  bad.joints[1].min_position = 1;
  bad.joints[1].max_position = -1;
  make(bad);
  EXPECT_EQ(manipulator->state(), msg::PrimaryStatus::failure);
  EXPECT_TRUE(logged("cannot run the arm: joint 2 (elbow): the minimum position must be below the maximum"));
}

}  // namespace
}  // namespace jaus::test
