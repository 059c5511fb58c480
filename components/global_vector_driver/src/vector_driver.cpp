#include "jaus/components/vector_driver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace jaus::components {

using namespace rt;

namespace {

// Gains are finite and not negative; these bounds only keep a typo out.
constexpr double kMaxHeadingGain = 50;  // (rad/s) per rad, per rad*s, per rad/s
constexpr double kMaxSpeedGain = 1000;  // percent per m/s, per m, per m/s^2
// Speed 0: the heading counts as reached once the vehicle has stopped
// turning too, or the stop would carry it past the tolerance (a drive with
// more turn per percent than its specifications say, or a slow one).
constexpr double kSettledYawRateRps = 0.1;

bool settled(const PoseSample& pose) { return !pose.rates_rps || std::abs(pose.rates_rps->z) <= kSettledYawRateRps; }

// The options <prefix>_kp, _ki, _kd over `gains`.
Expected<guidance::PidGains> read_gains(const KindOptions& options, std::string_view prefix, double max,
                                        guidance::PidGains gains) {
  const std::string p(prefix);
  for (auto [suffix, gain] : {std::pair{"_kp", &gains.kp}, std::pair{"_ki", &gains.ki}, std::pair{"_kd", &gains.kd}}) {
    const auto value = number_option(options, p + suffix, 0, max, *gain);
    if (!value) return unexpected(value.error());
    *gain = *value;
  }
  return gains;
}

}  // namespace

std::vector<std::string_view> vector_driver_option_keys() {
  std::vector<std::string_view> keys = kMobilityDriverOptionKeys;
  keys.insert(keys.end(), {"heading_tolerance_rad", "heading_kp", "heading_ki", "heading_kd", "speed_kp", "speed_ki",
                           "speed_kd"});
  return keys;
}

Expected<VectorDriverOptions> vector_driver_options(const KindOptions& options) {
  VectorDriverOptions o;
  auto mobility = mobility_driver_options(options);
  if (!mobility) return unexpected(mobility.error());
  o.mobility = *mobility;
  const auto tolerance = number_option(options, "heading_tolerance_rad", 0.001, 0.5, o.heading_tolerance_rad);
  if (!tolerance) return unexpected(tolerance.error());
  o.heading_tolerance_rad = *tolerance;
  const auto heading = read_gains(options, "heading", kMaxHeadingGain, o.heading_gains);
  if (!heading) return unexpected(heading.error());
  o.heading_gains = *heading;
  const auto speed = read_gains(options, "speed", kMaxSpeedGain, o.speed_gains);
  if (!speed) return unexpected(speed.error());
  o.speed_gains = *speed;
  return o;
}

VectorDriver::VectorDriver(ComponentConfig config, Environment env, PoseSource& pose, VectorDriverOptions options)
    : MobilityDriver(std::move(config), std::move(env), pose, options.mobility), options_(options) {}

std::optional<double> VectorDriver::vehicle_heading_rad() {
  const auto sample = pose_source().sample();
  if (!sample || !sample->attitude) return std::nullopt;
  return wrap_angle(sample->attitude->yaw);
}

void VectorDriver::command(std::optional<double> speed_mps, std::optional<double> heading_rad, std::string_view why) {
  ++commands_;
  // The wire allows no negative speed; a vector driver never reverses.
  if (speed_mps && std::isfinite(*speed_mps)) speed_mps_ = std::max(0.0, *speed_mps);
  if (heading_rad && std::isfinite(*heading_rad)) {
    if (heading_rad_ != wrap_angle(*heading_rad) && heading_loop_) heading_loop_->reset();  // a new target
    heading_rad_ = wrap_angle(*heading_rad);
  }
  // The first Set without a heading holds the one the vehicle has (or, with
  // no pose yet, the one it has at the first step).
  if (!heading_rad_) heading_rad_ = vehicle_heading_rad();
  engage(why);
}

void VectorDriver::motion_started() {
  heading_loop_.reset();
  speed_loop_.reset();
  if (!limits()) return;  // never: control is requested only with the limits known
  if (auto loop = guidance::HeadingLoop::make(options_.heading_gains, *limits())) heading_loop_ = *loop;
  if (auto loop = guidance::SpeedLoop::make(options_.speed_gains, *limits())) speed_loop_ = *loop;
}

MobilityDriver::Step VectorDriver::step(const PoseSample& pose, double dt_s) {
  if (!heading_loop_ || !speed_loop_ || !limits()) return Step::fault("no heading or speed loop for this vehicle");
  if (!pose.attitude) return Step::fault("the pose source gives no heading");
  const double heading = pose.attitude->yaw;
  if (!heading_rad_) heading_rad_ = wrap_angle(heading);
  const guidance::VehicleLimits& vehicle = *limits();
  const double speed = std::min(speed_mps_, vehicle.max_speed_mps);
  if (speed == 0) {
    if (vehicle.steering == Steering::ackermann) return Step::arrived("speed 0 (an Ackermann vehicle cannot turn at rest)");
    if (std::abs(guidance::heading_error(*heading_rad_, heading)) <= options_.heading_tolerance_rad && settled(pose))
      return Step::arrived("speed 0, heading reached");
  }
  WrenchEffort effort = heading_loop_->effort(*heading_rad_, heading, speed, dt_s);
  // Without a measured speed the loop gives its feedforward only.
  const double measured = pose.velocity_mps ? pose.velocity_mps->x : speed;
  effort.propulsive_linear.x = speed_loop_->update(speed, measured, dt_s);
  return Step::drive(effort);
}

// Safety: whatever ended the motion, nothing restarts the vehicle but a new
// Set (an arrival has speed 0 already; the heading is kept for the report).
void VectorDriver::motion_halted(std::string_view why) {
  if (speed_mps_ != 0) log(LogLevel::info, "commanded speed set to 0: " + std::string(why));
  speed_mps_ = 0;
  if (heading_loop_) heading_loop_->reset();
  if (speed_loop_) speed_loop_->reset();
}

void VectorDriver::state_changed(PrimaryStatus before, PrimaryStatus after) {
  MobilityDriver::state_changed(before, after);
  if (after == PrimaryStatus::initialize && before != PrimaryStatus::initialize) forget_command();
}

void VectorDriver::forget_command() {
  speed_mps_ = 0;
  heading_rad_.reset();
}

}  // namespace jaus::components
