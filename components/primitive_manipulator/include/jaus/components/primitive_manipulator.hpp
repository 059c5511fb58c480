// The primitive manipulator (component 49, RA 3.x Part 3 manipulator
// subgroup): the controller's Set Joint Efforts / Positions / Velocities,
// Set Tool Point, Set End-Effector Pose / Velocity State, Set Joint Motion
// and Set End-Effector Path Motion reach the ManipulatorArm, in Ready only;
// anyone may query the specifications (from the arm's geometry), the joint
// efforts, positions, velocities, force/torques and the tool point, also on
// service connections. End-effector commands go through the kinematics of
// kinematics.hpp (tool point in the end-effector frame; pose in the vehicle
// frame through the arm's base frame).
//
// Every command is checked whole before anything moves: a wrong joint count,
// any value outside a joint's limits (position limits, speed limits, effort
// +-100 %), a pose the inverse kinematics cannot reach within tolerance, or
// a timed pose that a joint cannot reach in time, refuses the command (the
// arm keeps doing what it did), counted in the counters and logged with the
// joint and the reason.
//
// Safety: the arm is told to hold where it is (ManipulatorArm::hold(): for
// an arm zero effort is not a stop) in command_stop(), which the component
// base calls on Standby, Emergency, Failure, Reset, Shutdown, control
// release or takeover, controller silence and a command service
// connection's deadman (rt::Component::enforce_stop); and here, when a
// velocity, effort or end-effector velocity command has not been renewed
// within the command timeout. A position target (joint or end-effector)
// needs no renewal. A stop cancels any timed motion in progress and keeps no
// command to resume: after Resume or Clear Emergency the arm holds until the
// controller sends a new command.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/components/joint_motion.hpp"
#include "jaus/components/kinematics.hpp"
#include "jaus/components/manipulator_arm.hpp"
#include "jaus/messages/manipulator_messages.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::components {

struct PrimitiveManipulatorOptions {
  // A velocity, effort or end-effector velocity command not renewed within
  // this holds the arm (0 disables; a command service connection's deadman
  // still applies).
  rt::Duration command_timeout = std::chrono::milliseconds(500);
  // Timed motions and end-effector velocities are streamed to the arm at this rate (clamped to 1..1000).
  double control_rate_hz = 50;
  // Inverse kinematics (Set End-Effector Pose, Set End-Effector Path Motion).
  kinematics::IkOptions ik;
  // An end-effector velocity the joints miss by more than this fraction of
  // its size (plus 1 mm/s or 1 mrad/s) is refused as unreachable.
  double twist_tolerance = 0.01;
  // The tool point until Set Tool Point: in the end-effector frame, metres.
  kinematics::Vec3 tool_point;
};

struct PrimitiveManipulatorCounters {
  std::uint64_t commands_applied = 0;
  std::uint64_t refused_joint_count = 0;    // one value per joint expected
  std::uint64_t refused_out_of_limits = 0;  // a value outside a joint's limits (or a bad field)
  std::uint64_t refused_unreachable = 0;    // a pose or twist the kinematics cannot reach, or not in time
  std::uint64_t refused_by_arm = 0;         // the backend said no (the arm then holds)
  std::uint64_t command_timeouts = 0;
  std::uint64_t motions_completed = 0;      // timed motions that ran to their last pose
  std::uint64_t holds = 0;                  // every hold the component commanded
};

class PrimitiveManipulator final : public rt::Component {
 public:
  PrimitiveManipulator(rt::ComponentConfig config, rt::Environment env, ManipulatorArm& arm,
                       PrimitiveManipulatorOptions options = {});
  ~PrimitiveManipulator() override;

  // What the arm is doing by the component's last command.
  enum class Motion { holding, efforts, positions, velocities, end_effector_velocity, joint_motion, path_motion };

  const PrimitiveManipulatorOptions& options() const { return options_; }
  const PrimitiveManipulatorCounters& manipulator_counters() const { return counters_; }
  Motion motion() const { return motion_; }
  const kinematics::Vec3& tool_point() const { return tool_point_; }
  const kinematics::ArmKinematics& kinematics() const { return *kinematics_; }
  // The tool point's pose now (vehicle frame); none before the arm's first sample.
  std::optional<kinematics::Pose> end_effector_pose() const;

  // The reports (queries and service connections). Before the arm's first
  // sample, joint values are reported as 0.
  msg::ReportManipulatorSpecifications specifications_report() const;
  msg::ReportJointEfforts joint_efforts_report() const;
  msg::ReportJointPositions joint_positions_report() const;
  msg::ReportJointVelocities joint_velocities_report() const;
  msg::ReportToolPoint tool_point_report() const;
  msg::ReportJointForceTorques joint_force_torques_report() const;

 protected:
  bool initialize() override;
  void command_stop(std::string_view why) override;
  // A Reset (any state -> Initialize): the arm is already holding; where it
  // has homing, it homes (ManipulatorArm::home), unless an emergency is latched.
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override;

 private:
  enum class Refusal { joint_count, out_of_limits, unreachable, arm };
  struct Problem {
    Refusal kind;
    std::string why;
  };

  void on_set_joint_efforts(const Header& h, const msg::SetJointEfforts& m);
  void on_set_joint_positions(const Header& h, const msg::SetJointPositions& m);
  void on_set_joint_velocities(const Header& h, const msg::SetJointVelocities& m);
  void on_set_tool_point(const Header& h, const msg::SetToolPoint& m);
  void on_set_end_effector_pose(const Header& h, const msg::SetEndEffectorPose& m);
  void on_set_end_effector_velocity(const Header& h, const msg::SetEndEffectorVelocityState& m);
  void on_set_joint_motion(const Header& h, const msg::SetJointMotion& m);
  void on_set_path_motion(const Header& h, const msg::SetEndEffectorPathMotion& m);

  // Checks (nothing moves): the first problem, or none.
  std::optional<Problem> check_count(std::size_t count) const;
  std::optional<Problem> check_positions(const std::vector<double>& positions) const;
  std::optional<Problem> check_velocities(const std::vector<double>& velocities) const;
  Expected<std::vector<double>> current_positions() const;
  Expected<std::vector<double>> twist_rates(const msg::EndEffectorVelocityStateBody& body, bool strict) const;

  void refuse(const Header& h, std::string_view what, const Problem& problem);
  // Ends whatever the arm was doing by the component's commands (timed
  // motion, end-effector velocity, command timeout) before a new command.
  void end_motion();
  // Hands a command to the arm; a refusal by the backend holds the arm.
  bool command_arm(const Header& h, std::string_view what, const Expected<void>& result, Motion motion);
  void start_trajectory(JointTrajectory trajectory, Motion motion);
  void control_tick();
  void schedule_control_tick();
  void arm_command_timeout();
  void cancel_timer(rt::TimerId& timer);

  ManipulatorArm& arm_;
  PrimitiveManipulatorOptions options_;
  PrimitiveManipulatorCounters counters_;
  std::unique_ptr<kinematics::ArmKinematics> kinematics_;
  kinematics::Vec3 tool_point_;
  Motion motion_ = Motion::holding;
  // The configuration's losses are written at the first initialisation only: a
  // controller's Reset runs initialize() again, and would repeat them at will.
  bool losses_written_ = false;
  std::vector<double> commanded_efforts_;  // reported when the arm does not report its efforts
  std::optional<JointTrajectory> trajectory_;
  rt::TimePoint trajectory_started_{};
  std::optional<msg::EndEffectorVelocityStateBody> twist_;
  rt::TimerId control_timer_ = rt::kNoTimer;
  rt::TimerId command_timer_ = rt::kNoTimer;
};

}  // namespace jaus::components
