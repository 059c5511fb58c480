#include "jaus/components/simulated_arm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

namespace jaus::components {

namespace {

constexpr double kMinUpdateRateHz = 0.1;
constexpr double kMaxUpdateRateHz = 10000;  // beyond this, catching up on a long gap costs too many steps

Expected<void> refused(std::string why) { return unexpected(make_error(ErrorCode::out_of_range, std::move(why))); }

// A wrong count, or the first value outside [low(i), high(i)] (with the wire's slack), refused.
template <class Low, class High>
Expected<void> check(const ArmConfig& config, const std::vector<double>& values, const char* what, Low low,
                     High high) {
  if (values.size() != config.joints.size())
    return refused(std::string(what) + " for " + std::to_string(values.size()) + " joints; the arm has " +
                   std::to_string(config.joints.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i], lo = low(i), hi = high(i);
    if (!std::isfinite(v) || v < lo - kJointLimitSlack || v > hi + kJointLimitSlack) {
      std::ostringstream why;
      why << joint_label(config, i) << ": " << what << " " << v << " outside [" << lo << ", " << hi << "]";
      return refused(why.str());
    }
  }
  return {};
}

}  // namespace

struct SimulatedArm::State {
  State(ArmConfig c, const rt::Clock& clk) : config(std::move(c)), clock(clk) {
    if (!(config.update_rate_hz >= kMinUpdateRateHz)) config.update_rate_hz = kMinUpdateRateHz;  // NaN too
    config.update_rate_hz = std::min(config.update_rate_hz, kMaxUpdateRateHz);
    step = rt::Duration{std::max<std::int64_t>(1, std::llround(1e9 / config.update_rate_hz))};
    step_s = std::chrono::duration<double>(step).count();
    last_step_at = clock.now();
    const std::size_t n = config.joints.size();
    positions.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const JointConfig& j = config.joints[i];
      positions[i] = std::isfinite(j.initial_position) ? j.initial_position : 0.0;
      if (j.min_position <= j.max_position) positions[i] = std::clamp(positions[i], j.min_position, j.max_position);
    }
    velocities.assign(n, 0.0);
    command.assign(n, 0.0);
  }

  ArmConfig config;
  const rt::Clock& clock;
  rt::Duration step{};
  double step_s = 0;

  Mode mode = Mode::holding;
  std::vector<double> command;  // targets, velocities or efforts, by mode
  std::size_t holds = 0;

  // The true state, at last_step_at.
  rt::TimePoint last_step_at{};
  std::vector<double> positions;
  std::vector<double> velocities;

  const JointConfig& joint(std::size_t i) const { return config.joints[i]; }

  bool at_rest() const {
    if (mode == Mode::holding) return true;
    if (mode != Mode::positions) return false;
    return positions == command;
  }

  // One joint moved at velocity v for one step, stopping at its limits.
  void move_at(std::size_t i, double v) {
    const double next = std::clamp(positions[i] + v * step_s, joint(i).min_position, joint(i).max_position);
    velocities[i] = (next - positions[i]) / step_s;
    positions[i] = next;
  }

  void integrate_one_step() {
    for (std::size_t i = 0; i < positions.size(); ++i) {
      switch (mode) {
        case Mode::holding:
          velocities[i] = 0;
          break;
        case Mode::positions: {
          const double delta = command[i] - positions[i];
          const double reach = joint(i).max_velocity * step_s;
          if (std::abs(delta) <= reach) {
            positions[i] = command[i];
            velocities[i] = delta / step_s;
          } else {
            positions[i] += delta > 0 ? reach : -reach;
            velocities[i] = delta > 0 ? joint(i).max_velocity : -joint(i).max_velocity;
          }
          break;
        }
        case Mode::velocities:
          move_at(i, command[i]);
          break;
        case Mode::efforts:
          move_at(i, command[i] / 100 * joint(i).max_velocity);
          break;
      }
    }
  }

  // Brings the state to the last step boundary at or before now.
  void advance() {
    const rt::TimePoint now = clock.now();
    if (now < last_step_at + step) return;
    const std::int64_t steps = (now - last_step_at) / step;
    for (std::int64_t k = 0; k < steps; ++k) {
      if (at_rest()) {  // nothing changes any more: skip the remaining steps
        std::fill(velocities.begin(), velocities.end(), 0.0);
        last_step_at += (steps - k) * step;
        return;
      }
      integrate_one_step();
      last_step_at += step;
    }
  }

  double force_torque(std::size_t i) const {
    if (mode == Mode::efforts) return command[i] / 100 * joint(i).max_effort;
    return joint(i).max_effort * speed_fraction(i);
  }
  // The velocity of joint i as a fraction of its speed limit (the effort that friction takes).
  double speed_fraction(std::size_t i) const {
    return joint(i).max_velocity > 0 ? velocities[i] / joint(i).max_velocity : 0.0;
  }
};

SimulatedArm::SimulatedArm(ArmConfig config, const rt::Clock& clock)
    : state_(std::make_unique<State>(std::move(config), clock)) {}

SimulatedArm::~SimulatedArm() = default;

const ArmConfig& SimulatedArm::geometry() const { return state_->config; }

Expected<void> SimulatedArm::move_to_positions(const std::vector<double>& positions) {
  const ArmConfig& c = state_->config;
  auto ok = check(
      c, positions, "position", [&](std::size_t i) { return c.joints[i].min_position; },
      [&](std::size_t i) { return c.joints[i].max_position; });
  if (!ok) return ok;
  state_->advance();
  state_->mode = Mode::positions;
  state_->command = positions;
  for (std::size_t i = 0; i < positions.size(); ++i)
    state_->command[i] = std::clamp(positions[i], c.joints[i].min_position, c.joints[i].max_position);
  return {};
}

Expected<void> SimulatedArm::move_at_velocities(const std::vector<double>& velocities) {
  const ArmConfig& c = state_->config;
  auto ok = check(
      c, velocities, "velocity", [&](std::size_t i) { return -c.joints[i].max_velocity; },
      [&](std::size_t i) { return c.joints[i].max_velocity; });
  if (!ok) return ok;
  state_->advance();
  state_->mode = Mode::velocities;
  state_->command = velocities;
  for (std::size_t i = 0; i < velocities.size(); ++i)
    state_->command[i] = std::clamp(velocities[i], -c.joints[i].max_velocity, c.joints[i].max_velocity);
  return {};
}

Expected<void> SimulatedArm::apply_efforts(const std::vector<double>& efforts_percent) {
  auto ok = check(
      state_->config, efforts_percent, "effort", [](std::size_t) { return -100.0; },
      [](std::size_t) { return 100.0; });
  if (!ok) return ok;
  state_->advance();
  state_->mode = Mode::efforts;
  state_->command = efforts_percent;
  for (double& e : state_->command) e = std::clamp(e, -100.0, 100.0);
  return {};
}

void SimulatedArm::hold() {
  state_->advance();
  state_->mode = Mode::holding;
  std::fill(state_->velocities.begin(), state_->velocities.end(), 0.0);
  ++state_->holds;
}

std::optional<JointSample> SimulatedArm::sample() const {
  state_->advance();
  JointSample s;
  s.positions = state_->positions;
  s.velocities = state_->velocities;
  const std::size_t n = s.positions.size();
  s.force_torques.resize(n);
  s.efforts_percent.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.force_torques[i] = state_->force_torque(i);
    s.efforts_percent[i] = state_->mode == Mode::efforts ? state_->command[i] : 100 * state_->speed_fraction(i);
  }
  s.sampled_at = state_->last_step_at;
  return s;
}

SimulatedArm::Mode SimulatedArm::mode() const { return state_->mode; }

std::vector<double> SimulatedArm::positions() const {
  state_->advance();
  return state_->positions;
}

std::size_t SimulatedArm::holds() const { return state_->holds; }

}  // namespace jaus::components
