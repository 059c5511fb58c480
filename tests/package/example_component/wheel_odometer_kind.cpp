// The wheel odometer as a component kind jausd can host, and the plugin
// that brings it: `plugins: [.../libwheel_odometer.so]` in jausd's YAML, then
// a component `kind: wheel_odometer`. Its options say what the wheels
// measure (a real odometer would read its encoders).
#include "jaus/runtime/component_plugin.hpp"
#include "wheel_odometer.hpp"

namespace example {

namespace {

struct OdometerOptions {
  double speed_mps;
  double yaw_rate_rps;
};

// Each option's range is what Report Velocity State can carry.
jaus::Expected<OdometerOptions> read_options(const jaus::rt::KindOptions& options) {
  const auto speed = jaus::rt::number_option(options, "speed_mps", -65.534, 65.534, 0);
  if (!speed) return jaus::unexpected(speed.error());
  const auto yaw_rate = jaus::rt::number_option(options, "yaw_rate_rps", -32.767, 32.767, 0);
  if (!yaw_rate) return jaus::unexpected(yaw_rate.error());
  return OdometerOptions{*speed, *yaw_rate};
}

jaus::rt::ComponentKind wheel_odometer_kind() {
  return jaus::rt::ComponentKind{
      .name = "wheel_odometer",
      .default_id = 42,  // RA 3.x Velocity State Sensor
      .options = {"speed_mps", "yaw_rate_rps"},
      .needs = {},
      .moves_hardware = false,
      .one_per_node = false,
      .check = jaus::rt::check_by(read_options),
      .make = [](const jaus::rt::KindContext& k) -> jaus::Expected<std::unique_ptr<jaus::rt::Component>> {
        const auto options = read_options(k.options);
        if (!options) return jaus::unexpected(options.error());
        auto odometer = std::make_unique<WheelOdometer>(k.config, k.env);
        odometer->measured(options->speed_mps, options->yaw_rate_rps);
        return std::unique_ptr<jaus::rt::Component>(std::move(odometer));
      }};
}

std::vector<jaus::rt::ComponentKind> plugin_kinds() { return {wheel_odometer_kind()}; }

}  // namespace

}  // namespace example

JAUS_COMPONENT_PLUGIN("example_wheel_odometer", example::plugin_kinds)
