// Part 3's platform bodies <-> the Drive's terms. Values are clamped to what
// each field can encode, so a report never fails to encode because a backend
// measured something out of range.
#include <algorithm>
#include <cmath>
#include <limits>

#include "jaus/components/primitive_driver.hpp"

namespace jaus::components {

namespace {

namespace pv = effort_field;

// Part 3, Set Discrete Devices: main propulsion bit 0 "on"; brake/horn bit 0
// parking brake set, bit 1 horn on.
constexpr std::uint8_t kMainPropulsionOn = 0x01;
constexpr std::uint8_t kParkingBrakeSet = 0x01;
constexpr std::uint8_t kHornOn = 0x02;

double or_zero(const std::optional<double>& v) { return v && std::isfinite(*v) ? *v : 0.0; }

std::optional<double> clamped(std::optional<double> v, double low, double high) {
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return std::clamp(*v, low, high);
}

}  // namespace

WrenchEffort to_wrench_effort(const msg::WrenchEffortBody& b) {
  WrenchEffort e;
  e.propulsive_linear = {or_zero(b.propulsive_linear_effort_x_percent), or_zero(b.propulsive_linear_effort_y_percent),
                         or_zero(b.propulsive_linear_effort_z_percent)};
  e.propulsive_rotational = {or_zero(b.propulsive_rotational_effort_x_percent),
                             or_zero(b.propulsive_rotational_effort_y_percent),
                             or_zero(b.propulsive_rotational_effort_z_percent)};
  e.resistive_linear = {or_zero(b.resistive_linear_effort_x_percent), or_zero(b.resistive_linear_effort_y_percent),
                        or_zero(b.resistive_linear_effort_z_percent)};
  e.resistive_rotational = {or_zero(b.resistive_rotational_effort_x_percent),
                            or_zero(b.resistive_rotational_effort_y_percent),
                            or_zero(b.resistive_rotational_effort_z_percent)};
  return e;
}

msg::WrenchEffortBody to_wrench_effort_body(const WrenchEffort& e, std::uint16_t fields) {
  msg::WrenchEffortBody b;
  const auto put = [fields](std::uint16_t bit, std::optional<double>& field, double value, double low) {
    if (fields & bit) field = clamped(value, low, 100.0);
  };
  put(pv::kPropulsiveLinearX, b.propulsive_linear_effort_x_percent, e.propulsive_linear.x, -100);
  put(pv::kPropulsiveLinearY, b.propulsive_linear_effort_y_percent, e.propulsive_linear.y, -100);
  put(pv::kPropulsiveLinearZ, b.propulsive_linear_effort_z_percent, e.propulsive_linear.z, -100);
  put(pv::kPropulsiveRotationalX, b.propulsive_rotational_effort_x_percent, e.propulsive_rotational.x, -100);
  put(pv::kPropulsiveRotationalY, b.propulsive_rotational_effort_y_percent, e.propulsive_rotational.y, -100);
  put(pv::kPropulsiveRotationalZ, b.propulsive_rotational_effort_z_percent, e.propulsive_rotational.z, -100);
  put(pv::kResistiveLinearX, b.resistive_linear_effort_x_percent, e.resistive_linear.x, 0);
  put(pv::kResistiveLinearY, b.resistive_linear_effort_y_percent, e.resistive_linear.y, 0);
  put(pv::kResistiveLinearZ, b.resistive_linear_effort_z_percent, e.resistive_linear.z, 0);
  put(pv::kResistiveRotationalX, b.resistive_rotational_effort_x_percent, e.resistive_rotational.x, 0);
  put(pv::kResistiveRotationalY, b.resistive_rotational_effort_y_percent, e.resistive_rotational.y, 0);
  put(pv::kResistiveRotationalZ, b.resistive_rotational_effort_z_percent, e.resistive_rotational.z, 0);
  return b;
}

DiscreteDevices to_discrete_devices(const msg::DiscreteDevicesBody& b, const DeviceSet& has) {
  DiscreteDevices d;
  if (b.main_propulsion && has.main_power) d.main_power = (*b.main_propulsion & kMainPropulsionOn) != 0;
  if (b.parking_brake_and_horn) {
    if (has.parking_brake) d.parking_brake = (*b.parking_brake_and_horn & kParkingBrakeSet) != 0;
    if (has.horn) d.horn = (*b.parking_brake_and_horn & kHornOn) != 0;
  }
  if (b.gear && has.gear) d.gear = *b.gear;
  return d;
}

msg::DiscreteDevicesBody to_discrete_devices_body(const DiscreteDevices& d, const DeviceSet& has) {
  msg::DiscreteDevicesBody b;
  if (has.main_power && d.main_power) b.main_propulsion = *d.main_power ? kMainPropulsionOn : 0;
  if ((has.parking_brake && d.parking_brake) || (has.horn && d.horn)) {
    std::uint8_t bits = 0;
    if (has.parking_brake && d.parking_brake.value_or(false)) bits |= kParkingBrakeSet;
    if (has.horn && d.horn.value_or(false)) bits |= kHornOn;
    b.parking_brake_and_horn = bits;
  }
  if (has.gear && d.gear) b.gear = *d.gear;
  return b;
}

msg::PlatformSpecificationsBody to_specifications_body(const PlatformSpecifications& s) {
  msg::PlatformSpecificationsBody b;
  if (!s.name.empty()) b.mobility_platform_name = s.name.substr(0, 15);  // the field holds 15 characters
  b.front_m = clamped(s.front_m, 0, 32.767);
  b.back_m = clamped(s.back_m, 0, 32.767);
  b.right_m = clamped(s.right_m, 0, 32.767);
  b.left_m = clamped(s.left_m, 0, 32.767);
  b.bottom_m = clamped(s.bottom_m, 0, 32.767);
  b.top_m = clamped(s.top_m, 0, 32.767);
  b.wheel_base_m = clamped(s.wheel_base_m, 0, 65.535);
  b.track_width_m = clamped(s.track_width_m, 0, 65.535);
  b.turning_radius_m = clamped(s.turning_radius_m, 0, 65.535);
  b.max_velocity_x_mps = clamped(s.max_velocity_x_mps, 0, 65.534);
  b.max_yaw_rate_rps = clamped(s.max_yaw_rate_rps, 0, 32.767);
  return b;
}

PlatformSpecifications from_specifications_body(const msg::PlatformSpecificationsBody& b) {
  PlatformSpecifications s;
  s.name = b.mobility_platform_name.value_or("");
  s.front_m = b.front_m;
  s.back_m = b.back_m;
  s.right_m = b.right_m;
  s.left_m = b.left_m;
  s.bottom_m = b.bottom_m;
  s.top_m = b.top_m;
  s.wheel_base_m = b.wheel_base_m;
  s.track_width_m = b.track_width_m;
  s.turning_radius_m = b.turning_radius_m;
  s.max_velocity_x_mps = b.max_velocity_x_mps;
  s.max_yaw_rate_rps = b.max_yaw_rate_rps;
  return s;
}

msg::PlatformOperationalDataBody to_operational_data_body(const OperationalData& d) {
  msg::PlatformOperationalDataBody b;
  b.engine_temperature_c = clamped(d.engine_temperature_c, -75, 180);
  if (d.odometer_m && std::isfinite(*d.odometer_m) && *d.odometer_m >= 0)
    b.odometer_m = static_cast<std::uint32_t>(
        std::min(std::floor(*d.odometer_m), static_cast<double>(std::numeric_limits<std::uint32_t>::max())));
  b.battery_voltage_percent = clamped(d.battery_voltage_percent, 0, 127);
  b.fuel_level_percent = clamped(d.fuel_level_percent, 0, 100);
  return b;
}

}  // namespace jaus::components
