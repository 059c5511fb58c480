// The hardware interface of the primitive manipulator: what the component
// asks of an arm, in joint space and SI units (radians, metres, newtons).
// Backends: a simulated arm (components/primitive_manipulator) and the
// Clearpath arm (bridge/). The component decides who may move the arm and
// when; a backend only moves it, and says when it cannot.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"

namespace jaus::components {

struct JointLimits {
  double min_position = 0;  // rad (revolute) or m (prismatic)
  double max_position = 0;
  double max_velocity = 0;  // rad/s or m/s
  bool prismatic = false;
};

struct JointSample {
  std::vector<double> positions;       // one per joint
  std::vector<double> velocities;      // empty when the arm does not measure them
  std::vector<double> force_torques;   // N or N·m; empty when not measured
  rt::TimePoint sampled_at{};
};

class ManipulatorArm {
 public:
  virtual ~ManipulatorArm() = default;

  virtual std::vector<JointLimits> joints() const = 0;
  // Targets outside a joint's limits are refused, not clamped: the error says which joint.
  virtual Expected<bool> move_to_positions(const std::vector<double>& positions) = 0;
  virtual Expected<bool> move_at_velocities(const std::vector<double>& velocities) = 0;
  // Safety: hold every joint where it is now. Called on every stop of the
  // component (Standby, Emergency, control loss, Reset, Shutdown); never fails.
  virtual void hold() = 0;
  // The latest sample; none before the arm has reported once.
  virtual std::optional<JointSample> sample() const = 0;
};

}  // namespace jaus::components
