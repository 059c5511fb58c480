#include "jaus/host/component_options.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "jaus/base/quoted.hpp"

namespace jaus::host {

namespace {

rt::Duration seconds(double s) {
  return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(s));
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

Error option_error(const ComponentSpec& spec, const std::string& key, const std::string& what) {
  Error error = make_error(ErrorCode::invalid_argument, spec.kind + " option '" + key + "' must be " + what +
                                                            ", got " + quoted(spec.options.at(key)));
  error.field = key;
  return error;
}

// The option `key` as a number in [min, max], or `fallback` when absent.
Expected<double> number(const ComponentSpec& spec, const std::string& key, double min, double max, double fallback,
                        bool min_exclusive = false) {
  const auto it = spec.options.find(key);
  if (it == spec.options.end()) return fallback;
  const std::string& text = it->second;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  const std::string range = (min_exclusive ? "a number > " : "a number ") + number_text(min) +
                            (min_exclusive ? " and <= " : "..") + number_text(max);
  if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value) || value < min ||
      (min_exclusive && value == min) || value > max)
    return unexpected(option_error(spec, key, range));
  return value;
}

Expected<bool> boolean(const ComponentSpec& spec, const std::string& key, bool fallback) {
  const auto it = spec.options.find(key);
  if (it == spec.options.end()) return fallback;
  const std::string& text = it->second;
  if (text == "true" || text == "True" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "False" || text == "no" || text == "off") return false;
  return unexpected(option_error(spec, key, "true or false"));
}

constexpr double kMaxTimeoutS = 60;

Expected<components::SensorOptions> sensor_options(const ComponentSpec& spec) {
  components::SensorOptions o;
  const auto stale = number(spec, "stale_after_s", 0, kMaxTimeoutS,
                            std::chrono::duration<double>(o.stale_after).count(), /*min_exclusive=*/true);
  if (!stale) return unexpected(stale.error());
  o.stale_after = seconds(*stale);
  return o;
}

}  // namespace

Expected<components::PrimitiveDriverOptions> primitive_driver_options(const ComponentSpec& spec) {
  components::PrimitiveDriverOptions o;
  const auto timeout = number(spec, "command_timeout_s", 0, kMaxTimeoutS,
                              std::chrono::duration<double>(o.command_timeout).count());
  if (!timeout) return unexpected(timeout.error());
  o.command_timeout = seconds(*timeout);
  const auto brake = number(spec, "stop_brake_percent", 0, 100, o.stop_brake_percent);
  if (!brake) return unexpected(brake.error());
  o.stop_brake_percent = *brake;
  return o;
}

Expected<components::GlobalPoseSensorOptions> global_pose_sensor_options(const ComponentSpec& spec) {
  components::GlobalPoseSensorOptions o;
  const auto sensor = sensor_options(spec);
  if (!sensor) return unexpected(sensor.error());
  o.sensor = *sensor;
  const auto local = boolean(spec, "local_pose", o.local_pose);
  if (!local) return unexpected(local.error());
  o.local_pose = *local;
  return o;
}

Expected<components::SensorOptions> velocity_state_sensor_options(const ComponentSpec& spec) {
  return sensor_options(spec);
}

Expected<components::VisualSensorOptions> visual_sensor_options(const ComponentSpec& spec) {
  components::VisualSensorOptions o;
  // At most the service connection table (64 by default), at least one.
  const auto connections = number(spec, "image_connections_per_requester", 1, 64,
                                  static_cast<double>(o.image_connections_per_requester));
  if (!connections) return unexpected(connections.error());
  if (*connections != std::floor(*connections))
    return unexpected(option_error(spec, "image_connections_per_requester", "a whole number 1..64"));
  o.image_connections_per_requester = static_cast<std::size_t>(*connections);
  return o;
}

Expected<components::PrimitiveManipulatorOptions> primitive_manipulator_options(const ComponentSpec& spec) {
  components::PrimitiveManipulatorOptions o;
  const auto timeout = number(spec, "command_timeout_s", 0, kMaxTimeoutS,
                              std::chrono::duration<double>(o.command_timeout).count());
  if (!timeout) return unexpected(timeout.error());
  o.command_timeout = seconds(*timeout);
  return o;
}

std::optional<OptionProblem> check_component_options(const ComponentSpec& spec) {
  std::optional<Error> error;
  if (spec.kind == "primitive_driver") {
    if (auto o = primitive_driver_options(spec); !o) error = o.error();
  } else if (spec.kind == "global_pose_sensor") {
    if (auto o = global_pose_sensor_options(spec); !o) error = o.error();
  } else if (spec.kind == "velocity_state_sensor") {
    if (auto o = velocity_state_sensor_options(spec); !o) error = o.error();
  } else if (spec.kind == "primitive_manipulator") {
    if (auto o = primitive_manipulator_options(spec); !o) error = o.error();
  } else if (spec.kind == "visual_sensor") {
    if (auto o = visual_sensor_options(spec); !o) error = o.error();
  }
  if (!error) return std::nullopt;
  const auto line = spec.option_lines.find(error->field);
  return OptionProblem{error->message(), line != spec.option_lines.end() ? line->second : spec.line};
}

}  // namespace jaus::host
