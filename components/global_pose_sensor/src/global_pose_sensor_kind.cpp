#include "jaus/components/global_pose_sensor_kind.hpp"

#include "jaus/core/component_ids.hpp"

namespace jaus::components {

Expected<GlobalPoseSensorOptions> global_pose_sensor_options(const rt::KindOptions& options) {
  GlobalPoseSensorOptions o;
  const auto sensor = sensor_options(options);
  if (!sensor) return unexpected(sensor.error());
  o.sensor = *sensor;
  const auto local = rt::bool_option(options, "local_pose", o.local_pose);
  if (!local) return unexpected(local.error());
  o.local_pose = *local;
  return o;
}

const rt::ComponentKind& global_pose_sensor_kind() {
  static const rt::ComponentKind kind{
      .name = "global_pose_sensor",
      .default_id = component_id::kGlobalPoseSensor,
      .options = {"stale_after_s", "local_pose"},
      .needs = {PoseSource::kInterface},
      .moves_hardware = false,
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .operator_views = {rt::operator_view::kGlobalPose},
      .check = rt::check_by(global_pose_sensor_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = global_pose_sensor_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(std::make_unique<GlobalPoseSensor>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
