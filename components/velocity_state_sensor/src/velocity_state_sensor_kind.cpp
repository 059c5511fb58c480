#include "jaus/components/velocity_state_sensor_kind.hpp"

#include "jaus/components/velocity_state_sensor.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& velocity_state_sensor_kind() {
  static const rt::ComponentKind kind{
      .name = "velocity_state_sensor",
      .default_id = component_id::kVelocityStateSensor,
      .options = {"stale_after_s"},
      .needs = {PoseSource::kInterface},
      .moves_hardware = false,
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .operator_views = {rt::operator_view::kVelocity},
      .check = rt::check_by(sensor_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = sensor_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(std::make_unique<VelocityStateSensor>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
