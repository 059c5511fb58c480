// The hardware interface of the primitive manipulator: what the component
// asks of an arm, in joint space and SI units (radians, metres, newtons).
// Backends: a simulated arm (components/primitive_manipulator) and the
// Clearpath arm (bridge/). The component decides who may move the arm and
// when, checks every command against the arm's geometry and limits, and
// computes the kinematics; a backend only moves the joints, and says when it
// cannot.
#pragma once

#include <string_view>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/components/arm_config.hpp"

namespace jaus::components {

// A value within this of a joint's limit (the rounding of a scaled integer on
// the wire) counts as at the limit, and is clamped to it.
inline constexpr double kJointLimitSlack = 1e-6;

struct JointSample {
  std::vector<double> positions;       // one per joint, rad or m
  std::vector<double> velocities;      // rad/s or m/s; empty when the arm does not measure them
  std::vector<double> force_torques;   // N m or N; empty when not measured
  std::vector<double> efforts_percent; // effort applied now, percent of max_effort; empty when not known
  rt::TimePoint sampled_at{};
};

class ManipulatorArm {
 public:
  // Its name among the hardware a host offers a component kind (rt::Backends).
  static constexpr std::string_view kInterface = "arm";
  static constexpr std::string_view kDescription = "an arm";

  virtual ~ManipulatorArm() = default;

  // The arm's joints (Denavit-Hartenberg table, limits) and its base frame on
  // the vehicle; fixed for the arm's lifetime. The component reports it
  // (Report Manipulator Specifications) and computes kinematics from it.
  virtual const ArmConfig& geometry() const = 0;

  // Every command gives one value per joint. A wrong count or a value outside
  // a joint's limits is refused whole (nothing moves), not clamped: the
  // error says which joint. A new command replaces the previous one.
  //
  // Each joint toward its position at its speed limit, then holds it there.
  virtual Expected<void> move_to_positions(const std::vector<double>& positions) = 0;
  // Each joint at its velocity (within max_velocity) until told otherwise;
  // a joint stops at its position limits.
  virtual Expected<void> move_at_velocities(const std::vector<double>& velocities) = 0;
  // Each joint with an effort, percent of its max_effort (-100..100); what an
  // effort does is the backend's (the simulated arm documents its model).
  virtual Expected<void> apply_efforts(const std::vector<double>& efforts_percent) = 0;
  // Safety: hold every joint where it is now (for an arm, zero effort is not
  // a stop: it would fall). Called on every stop of the component (Standby,
  // Emergency, control loss, command timeout, Reset, Shutdown); never fails.
  virtual void hold() = 0;
  // On Reset, where the arm has homing (the Clearpath arm: Home Joint for
  // every joint): run the arm's homing sequence. The component calls it when
  // a Reset brings it back to Initialize and no emergency is latched, after
  // the arm has been told to hold. The default (an arm without homing, the
  // simulated one) does nothing.
  virtual void home() {}

  // The latest sample; none before the arm has reported once.
  virtual std::optional<JointSample> sample() const = 0;
};

}  // namespace jaus::components
