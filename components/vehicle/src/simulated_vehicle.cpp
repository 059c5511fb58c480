#include "jaus/components/simulated_vehicle.hpp"

#include "jaus/components/local_frame.hpp"


#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace jaus::components {

namespace {

constexpr double kMinUpdateRateHz = 0.1;
constexpr double kMaxUpdateRateHz = 10000;  // beyond this, catching up on a long gap costs too many steps
constexpr double kSecondsPerHour = 3600;

constexpr std::uint8_t kGearPark = 0;
constexpr std::uint8_t kGearNeutral = 128;

// Effort as the drive takes it: finite, within [low, high].
double clamp_effort(double value, double low, double high) {
  if (!std::isfinite(value)) return 0;
  return std::clamp(value, low, high);
}

// `value` moved towards `target` by at most `step` (a negative step, from a bad configuration, moves nothing).
double move_toward(double value, double target, double step) {
  step = std::max(step, 0.0);
  if (std::abs(target - value) <= step) return target;
  return target > value ? value + step : value - step;
}

}  // namespace

struct SimulatedVehicle::State {
  State(SimulatedVehicleConfig c, const rt::Clock& clk)
      : config(std::move(c)),
        clock(clk),
        geodesy(config.start) {
    if (!(config.update_rate_hz >= kMinUpdateRateHz)) config.update_rate_hz = kMinUpdateRateHz;  // NaN too
    config.update_rate_hz = std::min(config.update_rate_hz, kMaxUpdateRateHz);
    step = rt::Duration{std::max<std::int64_t>(1, std::llround(1e9 / config.update_rate_hz))};
    step_s = std::chrono::duration<double>(step).count();
    last_step_at = clock.now();
    heading = wrap_angle(config.start_heading_rad);
  }

  SimulatedVehicleConfig config;
  const rt::Clock& clock;
  LocalFrame geodesy;
  rt::Duration step{};
  double step_s = 0;

  // Commands.
  WrenchEffort effort;
  bool main_power = true, parking_brake = false, horn = false;
  std::uint8_t gear = 1;

  // The true state, at last_step_at.
  rt::TimePoint last_step_at{};
  double speed = 0, yaw_rate = 0, heading = 0;
  double north = 0, east = 0;  // from the start, metres
  double distance = 0;
  std::int64_t powered_steps = 0;  // counted, not summed: the battery stays deterministic

  std::optional<PoseSample> frozen;
  FaultListener fault_listener;
  std::optional<std::string> fault;

  bool held() const { return parking_brake || gear == kGearPark; }
  bool engaged() const { return main_power && !held() && gear != kGearNeutral; }
  double brake_fraction() const { return held() ? 1.0 : effort.resistive_linear.x / 100; }

  double target_speed() const {
    if (!engaged()) return 0;
    return effort.propulsive_linear.x / 100 * config.max_speed_mps * (1 - effort.resistive_linear.x / 100);
  }
  double target_yaw_rate() const {  // differential only
    if (!engaged()) return 0;
    return effort.propulsive_rotational.z / 100 * config.max_yaw_rate_rps;
  }
  double steering_curvature() const {  // Ackermann only: yaw rate per metre per second
    if (!(config.wheel_base_m > 0)) return 0;
    return std::tan(effort.propulsive_rotational.z / 100 * config.max_steering_rad) / config.wheel_base_m;
  }

  bool at_rest() const {
    if (speed != 0 || yaw_rate != 0 || target_speed() != 0) return false;
    return config.steering == Steering::ackermann || target_yaw_rate() == 0;
  }

  // Speed after dt: slowing down (or towards zero before reversing) may use the brake, speeding up may not.
  double next_speed(double dt) const {
    const double target = target_speed();
    const double accel = config.max_acceleration_mps2;
    const double decel = accel + brake_fraction() * (config.max_deceleration_mps2 - accel);
    const bool slowing = (speed > 0 && target < speed) || (speed < 0 && target > speed);
    if (!slowing) return move_toward(speed, target, accel * dt);
    const double stop_at = speed > 0 ? std::max(target, 0.0) : std::min(target, 0.0);
    const double to_stop = std::abs(speed - stop_at);
    if (!(decel > 0) || to_stop > decel * dt) return move_toward(speed, stop_at, decel * dt);
    // Stopped within the step: the rest of it speeds up the other way, if the target lies there.
    return move_toward(stop_at, target, accel * (dt - to_stop / decel));
  }

  void integrate_one_step() {
    const double dt = step_s;
    const double new_speed = next_speed(dt);
    const double mean_speed = (speed + new_speed) / 2;  // exact while the acceleration is constant

    double new_yaw_rate = 0, heading_change = 0;
    if (config.steering == Steering::differential) {
      new_yaw_rate = move_toward(yaw_rate, target_yaw_rate(), config.max_yaw_acceleration_rps2 * dt);
      heading_change = (yaw_rate + new_yaw_rate) / 2 * dt;
    } else {
      new_yaw_rate = new_speed * steering_curvature();
      heading_change = mean_speed * steering_curvature() * dt;
    }

    const double mid_heading = heading + heading_change / 2;
    north += mean_speed * std::cos(mid_heading) * dt;
    east += mean_speed * std::sin(mid_heading) * dt;
    distance += std::abs(mean_speed) * dt;
    heading = wrap_angle(heading + heading_change);
    speed = new_speed;
    yaw_rate = new_yaw_rate;
    if (main_power) ++powered_steps;
  }

  // Brings the state to the last step boundary at or before now.
  void advance() {
    const rt::TimePoint now = clock.now();
    if (now < last_step_at + step) return;
    const std::int64_t steps = (now - last_step_at) / step;
    for (std::int64_t i = 0; i < steps; ++i) {
      if (at_rest()) {  // nothing moves until the next command: skip the remaining steps at once
        if (main_power) powered_steps += steps - i;
        break;
      }
      integrate_one_step();
    }
    last_step_at += steps * step;
  }

  PoseSample make_sample() const {
    PoseSample s;
    s.taken_at = last_step_at;
    s.taken_utc = clock.utc_now() - (clock.now() - last_step_at);

    const LocalPosition local{north, east, 0};
    s.position = geodesy.to_geo(local);
    if (config.local_frame) s.local_position = local;
    s.position_rms_m = config.position_rms_m + config.position_rms_per_m * distance;
    s.attitude = EulerAngles{0, 0, heading};
    s.attitude_rms_rad = config.attitude_rms_rad;
    s.velocity_mps = Axes{speed, 0, 0};
    s.velocity_rms_mps = config.velocity_rms_mps;
    s.rates_rps = Axes{0, 0, yaw_rate};
    s.rate_rms_rps = config.rate_rms_rps;
    return s;
  }

  DiscreteDevices devices() const { return {main_power, parking_brake, horn, gear}; }
};

SimulatedVehicle::SimulatedVehicle(SimulatedVehicleConfig config, const rt::Clock& clock)
    : state_(std::make_unique<State>(std::move(config), clock)) {}

SimulatedVehicle::~SimulatedVehicle() = default;

std::uint16_t SimulatedVehicle::effort_fields() const {
  return effort_field::kPropulsiveLinearX | effort_field::kPropulsiveRotationalZ | effort_field::kResistiveLinearX;
}

DeviceSet SimulatedVehicle::devices() const { return {true, true, true, true}; }

PlatformSpecifications SimulatedVehicle::specifications() const {
  const auto& c = state_->config;
  PlatformSpecifications spec = c.specifications;
  spec.max_velocity_x_mps = c.max_speed_mps;
  if (c.steering == Steering::differential) {
    spec.max_yaw_rate_rps = c.max_yaw_rate_rps;
  } else {
    const double tan_max_steering = std::tan(c.max_steering_rad);
    spec.wheel_base_m = c.wheel_base_m;  // the geometry the simulation turns with
    if (tan_max_steering > 0 && c.wheel_base_m > 0) {
      spec.turning_radius_m = c.wheel_base_m / tan_max_steering;
      if (!spec.max_yaw_rate_rps) spec.max_yaw_rate_rps = c.max_speed_mps * tan_max_steering / c.wheel_base_m;
    }
  }
  return spec;
}

WrenchEffort SimulatedVehicle::apply_effort(const WrenchEffort& effort) {
  state_->advance();
  WrenchEffort applied;
  applied.propulsive_linear.x = clamp_effort(effort.propulsive_linear.x, -100, 100);
  applied.propulsive_rotational.z = clamp_effort(effort.propulsive_rotational.z, -100, 100);
  applied.resistive_linear.x = clamp_effort(effort.resistive_linear.x, 0, 100);
  state_->effort = applied;
  return applied;
}

DiscreteDevices SimulatedVehicle::set_devices(const DiscreteDevices& devices) {
  state_->advance();
  if (devices.main_power) state_->main_power = *devices.main_power;
  if (devices.parking_brake) state_->parking_brake = *devices.parking_brake;
  if (devices.horn) state_->horn = *devices.horn;
  if (devices.gear) state_->gear = *devices.gear;
  return state_->devices();
}

void SimulatedVehicle::stop(double brake_percent) {
  state_->advance();
  state_->effort = WrenchEffort{};
  state_->effort.resistive_linear.x = clamp_effort(brake_percent, 0, 100);
}

WrenchEffort SimulatedVehicle::applied_effort() const { return state_->effort; }

DiscreteDevices SimulatedVehicle::device_state() const { return state_->devices(); }

OperationalData SimulatedVehicle::operational_data() {
  state_->advance();
  const auto& c = state_->config;
  const double powered_hours = static_cast<double>(state_->powered_steps) * state_->step_s / kSecondsPerHour;
  OperationalData data;
  data.odometer_m = state_->distance;
  data.battery_voltage_percent = std::max(0.0, c.battery_percent - c.battery_drain_percent_per_hour * powered_hours);
  return data;
}

std::optional<PoseSample> SimulatedVehicle::sample() {
  state_->advance();
  if (state_->frozen) return state_->frozen;
  return state_->make_sample();
}

double SimulatedVehicle::update_rate_hz() const { return state_->config.update_rate_hz; }

void SimulatedVehicle::freeze_samples(bool frozen) {
  state_->advance();
  if (!frozen) {
    state_->frozen.reset();
  } else if (!state_->frozen) {
    state_->frozen = state_->make_sample();
  }
}

void SimulatedVehicle::on_fault(FaultListener listener) { state_->fault_listener = std::move(listener); }

void SimulatedVehicle::inject_drive_fault(std::optional<std::string> fault) {
  if (fault == state_->fault) return;  // listeners hear changes only
  state_->fault = std::move(fault);
  if (state_->fault_listener) state_->fault_listener(state_->fault);
}

double SimulatedVehicle::speed_mps() {
  state_->advance();
  return state_->speed;
}

double SimulatedVehicle::yaw_rate_rps() {
  state_->advance();
  return state_->yaw_rate;
}

double SimulatedVehicle::heading_rad() {
  state_->advance();
  return state_->heading;
}

double SimulatedVehicle::distance_travelled_m() {
  state_->advance();
  return state_->distance;
}

const SimulatedVehicleConfig& SimulatedVehicle::config() const { return state_->config; }

}  // namespace jaus::components
