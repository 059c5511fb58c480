// The default backend of the primitive manipulator: an arm of ArmConfig's
// joints with no inertia, each joint driven at a speed within its limit.
//
// Time: the arm reads the injected clock and integrates lazily, in fixed
// steps of 1 / update_rate_hz up to now, whenever it is asked or told
// anything (no timers); so under VirtualTime it is deterministic. A command
// takes effect from the step in which it arrives.
//
// Motion rules (every joint, every step; never beyond its position limits):
// - positions: toward the target at the joint's max_velocity, then held there;
// - velocities: at the commanded velocity, stopping at a position limit;
// - efforts: a heavily damped joint (viscous friction, no gravity): an effort
//   of e % is a force/torque of e % x max_effort, balanced by friction at
//   e % x max_velocity; so the joint moves at e % of its speed limit;
// - hold: every joint stays where it is (velocity 0).
// The sample reports positions, velocities, and the force/torque each joint
// applies: e % x max_effort under an effort command, otherwise what the same
// friction takes at the joint's velocity (max_effort x v / max_velocity, 0
// when still); the effort reported is that force/torque in percent of max_effort.
#pragma once

#include <memory>

#include "jaus/components/manipulator_arm.hpp"

namespace jaus::components {

class SimulatedArm final : public ManipulatorArm {
 public:
  SimulatedArm(ArmConfig config, const rt::Clock& clock);
  ~SimulatedArm() override;
  SimulatedArm(const SimulatedArm&) = delete;
  SimulatedArm& operator=(const SimulatedArm&) = delete;

  const ArmConfig& geometry() const override;
  Expected<void> move_to_positions(const std::vector<double>& positions) override;
  Expected<void> move_at_velocities(const std::vector<double>& velocities) override;
  Expected<void> apply_efforts(const std::vector<double>& efforts_percent) override;
  void hold() override;
  std::optional<JointSample> sample() const override;

  // The true state, for tests.
  enum class Mode { holding, positions, velocities, efforts };
  Mode mode() const;
  std::vector<double> positions() const;
  std::size_t holds() const;  // how many times hold() was called

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace jaus::components
