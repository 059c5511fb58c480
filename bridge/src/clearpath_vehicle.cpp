#include "jaus/bridge/clearpath_vehicle.hpp"

#include "command_stream.hpp"
#include "safety_word.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "jaus/bridge/frame_conventions.hpp"
#include "jaus/clearpath/messages.hpp"
#include "jaus/components/local_frame.hpp"

namespace jaus::bridge {

namespace cp = clearpath;
using components::DiscreteDevices;
using components::OperationalData;
using components::PoseSample;
using components::WrenchEffort;
namespace field = components::effort_field;

std::int8_t clearpath_gear(std::uint8_t g) {
  if (g == 0) return -1;                                // park
  if (g <= 127) return static_cast<std::int8_t>(g);     // forward
  if (g == 128) return 0;                               // neutral
  return static_cast<std::int8_t>(127 - static_cast<int>(g));  // 129 -> -2 ... 255 -> -128
}

std::uint8_t jaus_gear(std::int8_t g) {
  if (g == -1) return 0;
  if (g == 0) return 128;
  if (g > 0) return static_cast<std::uint8_t>(g);
  return static_cast<std::uint8_t>(127 - static_cast<int>(g));  // -2 -> 129 ... -128 -> 255
}

namespace {

// NaN and infinities count as 0, like every effort the drives accept.
double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }
double clamp_percent(double v, double lo = -100, double hi = 100) { return std::clamp(finite_or_zero(v), lo, hi); }

template <class Request>
cp::AnyMessage request_at(std::uint16_t rate_hz) {
  Request r;
  r.subscription = rate_hz;
  return r;
}

}  // namespace

std::uint16_t owned_safety_bits(const ClearpathVehicleConfig& c) {
  std::uint32_t bits = c.emergency_flags;
  for (const auto* out : {&c.main_power, &c.parking_brake, &c.horn})
    if (out->kind == DeviceOutput::Kind::safety_flag) bits |= out->bits;
  return static_cast<std::uint16_t>(bits);
}

struct ClearpathVehicle::State {
  State(PlatformConnection& p, ClearpathVehicleConfig c)
      : platform(p),
        config(std::move(c)),
        frame(config.datum),
        safety({owned_safety_bits(config), config.platform_stop_flags, config.platform_status_flags}) {}

  PlatformConnection& platform;
  ClearpathVehicleConfig config;
  components::LocalFrame frame;
  ClearpathVehicleCounters counters;
  FaultListener fault_listener;

  // What the platform was last told and when (stop(): the zero, stopped = true).
  WrenchEffort applied;
  rt::TimePoint applied_at{};
  bool stopped = true;
  double steering_percent = 0;  // Ackermann: the last steering commanded, held through stops

  // Devices as commanded (Clearpath reports neither of them back, except the gear).
  DiscreteDevices devices;
  std::uint32_t safety_flags = 0;   // the discrete devices' bits of the safety word
  bool emergency_commanded = false;
  detail::SafetyWord safety;        // the word 0x0010 carries, owned bit by bit
  EmergencyListener emergency_listener;
  std::optional<std::string> platform_emergency;  // the platform's own stop, while on
  std::uint32_t gpio_outputs = 0;   // the pins 0x0302 drives
  bool gpio_configured = false;
  std::optional<std::int8_t> reported_gear;

  // What the platform reports.
  std::optional<std::string> platform_name;
  std::optional<double> max_forward_mps, max_reverse_mps;
  std::optional<double> temperature_c, battery_v, charge_percent;
  std::optional<cp::OrientationData> orientation;
  std::optional<cp::RotationalRateData> rates;
  rt::TimePoint rates_at{};

  // Dead reckoning.
  bool baseline = false;
  double left_travel = 0, right_travel = 0;
  double north = 0, east = 0, heading = 0;
  double distance = 0;  // travelled, for the RMS and the odometer
  std::optional<PoseSample> latest;

  rt::TimePoint now() const { return platform.clock().now(); }

  void fault(std::optional<std::string> what) {
    if (fault_listener) fault_listener(what);
  }

  void send(cp::AnyMessage message, const char* what) {
    platform.client().send(std::move(message), [this, what](const cp::CommandOutcome& outcome) {
      // A newer command of its kind replaced it: nothing failed.
      if (outcome.ok() || outcome.error == cp::CommandError::superseded) return;
      ++counters.command_failures;
      platform.log(rt::LogLevel::warn,
                   std::string("Clearpath platform: ") + what + " not applied (" + detail::outcome_text(outcome) + ")");
    });
  }

  // ---- drive --------------------------------------------------------------

  double speed_limit(double v) const {
    double hi = config.max_speed_mps, lo = -config.max_speed_mps;
    if (max_forward_mps) hi = std::min(hi, *max_forward_mps);
    if (max_reverse_mps) lo = std::max(lo, -*max_reverse_mps);
    return std::clamp(v, lo, hi);
  }

  // The command for `effort` and the effort it really asks for, after clamping.
  std::pair<cp::AnyMessage, WrenchEffort> command_for(const WrenchEffort& e) const {
    const double x = clamp_percent(e.propulsive_linear.x);
    const double z = clamp_percent(e.propulsive_rotational.z);  // positive turning right
    const double brake = clamp_percent(e.resistive_linear.x, 0, 100);
    WrenchEffort told;
    switch (config.drive) {
      case DriveMode::differential_output: {
        const double scale = config.brake == BrakeMode::scale ? 1.0 - brake / 100.0 : 1.0;
        cp::SetDifferentialOutput m;
        m.left = std::clamp((x + z) * scale, -100.0, 100.0);
        m.right = std::clamp((x - z) * scale, -100.0, 100.0);
        // What the two outputs amount to, in JAUS's terms (the brake is already in them).
        told.propulsive_linear.x = (m.left + m.right) / 2;
        told.propulsive_rotational.z = (m.left - m.right) / 2;
        if (config.brake == BrakeMode::scale && scale > 0) {
          told.propulsive_linear.x /= scale;
          told.propulsive_rotational.z /= scale;
          told.resistive_linear.x = brake;
        } else if (config.brake == BrakeMode::scale) {
          told.propulsive_linear.x = x;
          told.propulsive_rotational.z = z;
          told.resistive_linear.x = brake;
        }
        return {m, told};
      }
      case DriveMode::differential_speeds: {
        const double w = z / 100 * config.max_yaw_rate_rps;
        const double v = speed_limit(x / 100 * config.max_speed_mps);
        cp::SetDifferentialSpeeds m;
        m.left_speed = speed_limit(v + w * config.track_width_m / 2);
        m.right_speed = speed_limit(v - w * config.track_width_m / 2);
        m.left_accel = m.right_accel = config.max_acceleration_mps2;
        told.propulsive_linear.x = (m.left_speed + m.right_speed) / 2 / config.max_speed_mps * 100;
        told.propulsive_rotational.z =
            (m.left_speed - m.right_speed) / config.track_width_m / config.max_yaw_rate_rps * 100;
        return {m, told};
      }
      case DriveMode::velocity: {
        cp::SetVelocity m;
        m.translational = speed_limit(x / 100 * config.max_speed_mps);
        m.rotational = jaus_turn_to_clearpath(z / 100 * config.max_yaw_rate_rps);
        m.acceleration = config.max_acceleration_mps2;
        told.propulsive_linear.x = m.translational / config.max_speed_mps * 100;
        told.propulsive_rotational.z = clearpath_turn_to_jaus(m.rotational) / config.max_yaw_rate_rps * 100;
        return {m, told};
      }
      case DriveMode::ackermann: {
        cp::SetAckermannOutput m;
        m.steering = jaus_turn_to_clearpath(z);
        m.throttle = x;
        m.brake = brake;
        told.propulsive_linear.x = x;
        told.propulsive_rotational.z = z;
        told.resistive_linear.x = brake;
        return {m, told};
      }
    }
    return {cp::SetDifferentialOutput{}, told};
  }

  bool uses_safety_flags() const {
    return config.main_power.kind == DeviceOutput::Kind::safety_flag ||
           config.parking_brake.kind == DeviceOutput::Kind::safety_flag ||
           config.horn.kind == DeviceOutput::Kind::safety_flag || config.emergency_flags != 0;
  }

  // ---- the safety word (safety_word.hpp has the rule) ----------------------

  std::uint16_t wanted_safety_bits() const {
    std::uint32_t word = safety_flags;
    if (emergency_commanded) word |= config.emergency_flags;
    return static_cast<std::uint16_t>(word);
  }

  // After anything that changes what is wanted or known: write what is due,
  // and tell the host when the platform's own stop appears or clears.
  void update_safety() {
    if (uses_safety_flags()) {
      safety.want(wanted_safety_bits());
      if (const auto word = safety.take_write()) {
        cp::SetSafetySystem m;
        m.flags = *word;
        platform.client().send(m, [this](const cp::CommandOutcome& outcome) {
          safety.write_done(outcome.ok());
          if (!outcome.ok() && outcome.error != cp::CommandError::superseded) {
            ++counters.command_failures;
            platform.log(rt::LogLevel::warn,
                         "Clearpath platform: safety flags not applied (" + detail::outcome_text(outcome) + ")");
          }
          update_safety();
        });
      }
    }
    const auto now_on = safety.platform_stop();
    if (now_on == platform_emergency) return;
    const bool edge = now_on.has_value() != platform_emergency.has_value();
    platform_emergency = now_on;
    if (!edge) return;  // the same stop, described anew (the e-stop took over from an unconfirmed clear)
    platform.log(now_on ? rt::LogLevel::warn : rt::LogLevel::info,
                 now_on ? *now_on : std::string("Clearpath platform stop cleared"));
    if (emergency_listener) emergency_listener(now_on);
  }

  void write_devices() {
    update_safety();
    std::uint32_t gpio_mask = 0;
    for (const auto* out : {&config.main_power, &config.parking_brake, &config.horn})
      if (out->kind == DeviceOutput::Kind::gpio) gpio_mask |= out->bits;
    if (gpio_mask == 0) return;
    if (!gpio_configured) {
      send(cp::SetGpioDirection{gpio_mask, gpio_mask}, "GPIO direction (discrete devices)");
      gpio_configured = true;
    }
    send(cp::SetGpioOutput{gpio_mask, gpio_outputs & gpio_mask}, "GPIO outputs (discrete devices)");
  }

  void set_output(const DeviceOutput& out, bool on) {
    const bool high = on == out.active_high;
    std::uint32_t* word = out.kind == DeviceOutput::Kind::safety_flag ? &safety_flags
                          : out.kind == DeviceOutput::Kind::gpio      ? &gpio_outputs
                                                                      : nullptr;
    if (word == nullptr) return;
    *word = high ? (*word | out.bits) : (*word & ~out.bits);
  }

  // ---- pose ---------------------------------------------------------------

  void on_encoders(const cp::EncoderData& data) {
    if (data.encoders.size() < 2) return;  // a platform without both sides' encoders cannot dead-reckon
    ++counters.encoder_readings;
    const auto& left = data.encoders[0];
    const auto& right = data.encoders[1];
    if (!baseline) {
      // Encoders keep their counts across host restarts: integrate from the first reading.
      baseline = true;
      left_travel = left.travel;
      right_travel = right.travel;
      heading = current_heading(heading_or_datum());
      publish(left, right);
      return;
    }
    const double dl = left.travel - left_travel, dr = right.travel - right_travel;
    left_travel = left.travel;
    right_travel = right.travel;
    if (std::abs(dl) > config.max_encoder_step_m || std::abs(dr) > config.max_encoder_step_m) {
      // A roll-over or a platform reset, not motion: start again from here.
      ++counters.encoder_resets;
      platform.log(rt::LogLevel::warn, "Clearpath platform: implausible encoder jump (" + std::to_string(dl) + " m, " +
                                           std::to_string(dr) + " m) ignored");
      return;
    }
    const double before = heading;
    // Without orientation: a left wheel travelling further turns the platform right.
    const double after = current_heading(wrap_angle(before + (dl - dr) / config.track_width_m));
    const double mid = before + wrap_angle(after - before) / 2;
    const double d = (dl + dr) / 2;
    north += d * std::cos(mid);
    east += d * std::sin(mid);
    distance += std::abs(d);
    heading = after;
    publish(left, right);
  }

  double heading_or_datum() const { return wrap_angle(config.datum_heading_rad); }

  // The heading now: 0x8600's yaw (already clockwise) from the datum's heading, or `integrated`.
  double current_heading(double integrated) const {
    if (config.heading_from_orientation && orientation) return wrap_angle(config.datum_heading_rad + orientation->yaw);
    return integrated;
  }

  void publish(const cp::EncoderReading& left, const cp::EncoderReading& right) {
    PoseSample s;
    s.taken_at = now();
    s.taken_utc = platform.clock().utc_now();
    const components::LocalPosition local{north, east, 0};
    s.position = frame.to_geo(local);
    if (config.local_frame) s.local_position = local;
    s.position_rms_m = config.position_rms_m + config.position_rms_per_m * distance;
    components::EulerAngles attitude{0, 0, heading};
    if (orientation) {
      attitude.roll = orientation->roll;
      attitude.pitch = orientation->pitch;
    }
    s.attitude = attitude;
    s.attitude_rms_rad = config.attitude_rms_rad;
    s.velocity_mps = components::Axes{(left.speed + right.speed) / 2, 0, 0};
    s.velocity_rms_mps = config.velocity_rms_mps;
    // Rates from 0x8601 when fresh (two data periods), else the encoders' yaw rate.
    const auto period = std::chrono::duration<double>(1.0 / std::max<std::uint16_t>(config.data_rate_hz, 1));
    if (rates && s.taken_at - rates_at <= 2 * std::chrono::duration_cast<rt::Duration>(period))
      s.rates_rps = components::Axes{rates->roll_rate, rates->pitch_rate, rates->yaw_rate};
    else
      s.rates_rps = components::Axes{0, 0, (left.speed - right.speed) / config.track_width_m};
    s.rate_rms_rps = config.rate_rms_rps;
    latest = s;
  }

  void subscribe() {
    auto& client = platform.client();
    const std::uint16_t rate = std::max<std::uint16_t>(config.data_rate_hz, 1);
    client.subscribe(request_at<cp::RequestEncoders>(rate));
    client.subscribe(request_at<cp::RequestOrientation>(rate));
    client.subscribe(request_at<cp::RequestRotationalRates>(rate));
    client.subscribe(request_at<cp::RequestSystemStatus>(1));
    client.subscribe(request_at<cp::RequestPowerStatus>(1));
    client.subscribe(request_at<cp::RequestMaxSpeed>(1));
    if (config.gear) client.subscribe(request_at<cp::RequestGear>(2));
    // The platform's stops, and the foreign bits of the safety word jausd keeps.
    if (config.platform_stop_flags != 0 || uses_safety_flags())
      client.subscribe(request_at<cp::RequestSafetyStatus>(config.safety_status_rate_hz), [this](const cp::CommandOutcome& o) {
        if (o.error != cp::CommandError::refused) return;
        platform.log(rt::LogLevel::warn, "Clearpath platform: no safety status (0x8010, " + detail::outcome_text(o) +
                                             "): its own e-stop is not watched, and jausd writes only its own safety bits");
        safety.status_unavailable();
        update_safety();
      });
  }

  void listen() {
    platform.on_data(cp::EncoderData::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::EncoderData>()) on_encoders(*m);
    });
    platform.on_data(cp::OrientationData::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::OrientationData>()) orientation = *m;
    });
    platform.on_data(cp::RotationalRateData::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::RotationalRateData>()) {
        rates = *m;
        rates_at = now();
      }
    });
    platform.on_data(cp::SystemStatus::kType, [this](const cp::Envelope& e) {
      const auto* m = e.message.get_if<cp::SystemStatus>();
      if (m == nullptr) return;
      if (!m->voltages.empty()) battery_v = m->voltages.front();
      if (!m->temperatures.empty()) temperature_c = *std::max_element(m->temperatures.begin(), m->temperatures.end());
    });
    platform.on_data(cp::PowerStatus::kType, [this](const cp::Envelope& e) {
      const auto* m = e.message.get_if<cp::PowerStatus>();
      if (m != nullptr && !m->batteries.empty()) charge_percent = m->batteries.front().charge;
    });
    platform.on_data(cp::MaxSpeedData::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::MaxSpeedData>()) {
        max_forward_mps = m->forward;
        max_reverse_mps = m->reverse;
      }
    });
    platform.on_data(cp::PlatformName::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::PlatformName>()) platform_name = m->name;
    });
    platform.on_data(cp::GearData::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::GearData>()) reported_gear = m->gear;
    });
    platform.on_data(cp::SafetyStatus::kType, [this](const cp::Envelope& e) {
      if (const auto* m = e.message.get_if<cp::SafetyStatus>()) {
        safety.status(m->flags);
        update_safety();
      }
    });
    platform.on_alive([this](bool alive) {
      if (alive) {
        platform.client().send(cp::RequestPlatformName{});  // once per connection: a name rarely changes
        fault(std::nullopt);
      } else {
        // Safety: the platform's watchdog stops it (the client dropped every
        // setpoint); the driver goes to Failure and moves nothing until it is back.
        stopped = true;
        applied = WrenchEffort{};
        // The platform's word is unknown until it speaks again (it may have
        // restarted without our bits); a stop it reported stays held meanwhile.
        safety.link_lost();
        fault("link to the Clearpath platform lost");
      }
    });
  }
};

ClearpathVehicle::ClearpathVehicle(PlatformConnection& platform, ClearpathVehicleConfig config)
    : state_(std::make_unique<State>(platform, std::move(config))) {
  state_->heading = wrap_angle(state_->config.datum_heading_rad);
  state_->listen();
  state_->subscribe();
  if (state_->config.main_power.kind != DeviceOutput::Kind::none) state_->devices.main_power = true;
  if (state_->config.parking_brake.kind != DeviceOutput::Kind::none) state_->devices.parking_brake = false;
  if (state_->config.horn.kind != DeviceOutput::Kind::none) state_->devices.horn = false;
  if (state_->config.gear) state_->devices.gear = 1;
  for (const auto* out : {&state_->config.main_power})
    if (out->kind != DeviceOutput::Kind::none) state_->set_output(*out, true);
}

ClearpathVehicle::~ClearpathVehicle() = default;

void ClearpathVehicle::on_fault(FaultListener listener) {
  state_->fault_listener = std::move(listener);
  // A platform not heard from yet is a fault now; the first data clears it.
  if (state_->fault_listener && !state_->platform.alive()) state_->fault("no data from the Clearpath platform yet");
}

std::uint16_t ClearpathVehicle::effort_fields() const {
  std::uint16_t fields = field::kPropulsiveLinearX | field::kPropulsiveRotationalZ;
  const auto& c = state_->config;
  if (c.drive == DriveMode::ackermann || (c.drive == DriveMode::differential_output && c.brake == BrakeMode::scale))
    fields |= field::kResistiveLinearX;
  return fields;
}

components::DeviceSet ClearpathVehicle::devices() const {
  const auto& c = state_->config;
  using K = DeviceOutput::Kind;
  return {c.main_power.kind != K::none, c.parking_brake.kind != K::none, c.horn.kind != K::none, c.gear};
}

components::PlatformSpecifications ClearpathVehicle::specifications() const {
  const auto& s = *state_;
  auto spec = s.config.specifications;
  if (spec.name.empty()) spec.name = s.platform_name.value_or("clearpath");
  if (spec.name.size() > 15) spec.name.resize(15);
  double max_speed = s.config.max_speed_mps;
  if (s.max_forward_mps) max_speed = std::min(max_speed, *s.max_forward_mps);
  if (!spec.max_velocity_x_mps) spec.max_velocity_x_mps = max_speed;
  if (!spec.track_width_m) spec.track_width_m = s.config.track_width_m;
  // What 100 % propulsive rotational z really does, for those who steer by
  // these figures (the drivers above the primitive driver; guidance::limits_from):
  switch (s.config.drive) {
    case DriveMode::differential_output:
      // Open loop: L = X + Z, R = X - Z, so 100 % Z turns the wheels at the
      // full speed either way: 2 max_speed / track width (3.6 rad/s for 1 m/s
      // on 0.55 m), not the closed-loop modes' max_yaw_rate_rps.
      if (!spec.max_yaw_rate_rps && s.config.track_width_m > 0)
        spec.max_yaw_rate_rps = 2 * max_speed / s.config.track_width_m;
      break;
    case DriveMode::differential_speeds:
    case DriveMode::velocity:
      if (!spec.max_yaw_rate_rps) spec.max_yaw_rate_rps = s.config.max_yaw_rate_rps;
      break;
    case DriveMode::ackermann:
      if (!spec.wheel_base_m) spec.wheel_base_m = s.config.wheel_base_m;
      if (!spec.turning_radius_m && std::tan(s.config.max_steering_rad) > 0)
        spec.turning_radius_m = *spec.wheel_base_m / std::tan(s.config.max_steering_rad);
      break;
  }
  return spec;
}

WrenchEffort ClearpathVehicle::apply_effort(const WrenchEffort& effort) {
  auto& s = *state_;
  if (!s.platform.alive()) {
    // Safety: nothing is sent to a platform we cannot hear; the driver is in Failure.
    ++s.counters.refused_offline;
    return WrenchEffort{};
  }
  auto [command, told] = s.command_for(effort);
  s.platform.client().set_setpoint(std::move(command));
  ++s.counters.setpoints;
  s.steering_percent = told.propulsive_rotational.z;
  s.applied = told;
  s.applied_at = s.now();
  s.stopped = false;
  return told;
}

DiscreteDevices ClearpathVehicle::set_devices(const DiscreteDevices& d) {
  auto& s = *state_;
  const auto has = devices();
  bool outputs_changed = false;
  if (d.main_power && has.main_power) {
    s.devices.main_power = *d.main_power;
    s.set_output(s.config.main_power, *d.main_power);
    outputs_changed = true;
  }
  if (d.parking_brake && has.parking_brake) {
    s.devices.parking_brake = *d.parking_brake;
    s.set_output(s.config.parking_brake, *d.parking_brake);
    outputs_changed = true;
  }
  if (d.horn && has.horn) {
    s.devices.horn = *d.horn;
    s.set_output(s.config.horn, *d.horn);
    outputs_changed = true;
  }
  if (outputs_changed) s.write_devices();
  if (d.gear && has.gear) {
    s.devices.gear = *d.gear;
    cp::ChangeGear m;
    m.gear = clearpath_gear(*d.gear);
    s.send(m, "gear change");
  }
  return device_state();
}

void ClearpathVehicle::stop(double brake_percent) {
  auto& s = *state_;
  // Safety (the Drive contract): one zero setpoint of the drive's command, at
  // once, first in the link's queue; then the stream ends, so nothing older
  // can reach the platform. If it is lost, the platform's watchdog stops the
  // platform as the stream has ended.
  // An Ackermann platform keeps its steering angle: a stop is no reason to
  // swing the actuator to centre (during an e-stop least of all).
  const bool ackermann = s.config.drive == DriveMode::ackermann;
  WrenchEffort zero;
  zero.resistive_linear.x = clamp_percent(brake_percent, 0, 100);
  if (ackermann) zero.propulsive_rotational.z = s.steering_percent;
  auto [command, told] = s.command_for(zero);
  told.propulsive_linear = {};
  if (!ackermann) told.propulsive_rotational = {};
  s.platform.client().stop_setpoint(std::move(command));
  ++s.counters.stops;
  s.applied = told;
  s.applied_at = s.now();
  s.stopped = true;
}

WrenchEffort ClearpathVehicle::applied_effort() const {
  const auto& s = *state_;
  // A setpoint the driver stopped renewing is no longer sent: the platform is told nothing.
  if (!s.stopped && s.now() - s.applied_at > s.config.setpoint_max_age) return WrenchEffort{};
  WrenchEffort reported = s.applied;
  if ((effort_fields() & field::kResistiveLinearX) == 0) reported.resistive_linear.x = 0;
  return reported;
}

DiscreteDevices ClearpathVehicle::device_state() const {
  DiscreteDevices d = state_->devices;
  if (d.gear && state_->reported_gear) d.gear = jaus_gear(*state_->reported_gear);
  return d;
}

OperationalData ClearpathVehicle::operational_data() {
  const auto& s = *state_;
  OperationalData d;
  d.engine_temperature_c = s.temperature_c;
  if (s.baseline) d.odometer_m = s.distance;
  if (s.battery_v && s.config.nominal_battery_v > 0) d.battery_voltage_percent = *s.battery_v / s.config.nominal_battery_v * 100;
  d.fuel_level_percent = s.charge_percent;  // the energy left: the battery's charge
  return d;
}

std::optional<PoseSample> ClearpathVehicle::sample() { return state_->latest; }

double ClearpathVehicle::update_rate_hz() const { return std::max<std::uint16_t>(state_->config.data_rate_hz, 1); }

void ClearpathVehicle::on_platform_emergency(EmergencyListener listener) {
  state_->emergency_listener = std::move(listener);
  if (state_->emergency_listener && state_->platform_emergency) state_->emergency_listener(state_->platform_emergency);
}

void ClearpathVehicle::command_emergency(bool active) {
  auto& s = *state_;
  if (s.config.emergency_flags == 0 || s.emergency_commanded == active) return;
  s.emergency_commanded = active;
  s.platform.log(rt::LogLevel::info, active ? "Clearpath platform: setting its emergency flag"
                                            : "Clearpath platform: clearing its emergency flag");
  s.update_safety();
}

void ClearpathVehicle::reclaim_safety_bits() {
  auto& s = *state_;
  s.safety.adopt_owned_bits_seen();
  s.update_safety();
}

const ClearpathVehicleConfig& ClearpathVehicle::config() const { return state_->config; }
const ClearpathVehicleCounters& ClearpathVehicle::counters() const { return state_->counters; }

}  // namespace jaus::bridge
