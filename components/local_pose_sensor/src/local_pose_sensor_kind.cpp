#include "jaus/components/local_pose_sensor_kind.hpp"

#include "jaus/components/local_pose_sensor.hpp"

namespace jaus::components {

const rt::ComponentKind& local_pose_sensor_kind() {
  static const rt::ComponentKind kind{
      .name = "local_pose_sensor",
      .default_id = kLocalPoseSensorId,
      .options = {"stale_after_s"},
      .needs = {PoseSource::kInterface},
      .moves_hardware = false,
      .one_per_node = false,
      .check = rt::check_by(sensor_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = sensor_options(k.options);
        if (!options) return unexpected(options.error());
        // A sensor of local pose on a source known to have no local frame
        // would only ever report attitude: refused, saying why.
        if (const auto sample = (*pose)->sample(); sample && !sample->local_position)
          return unexpected(make_error(ErrorCode::invalid_argument,
                                       "local_pose_sensor needs a pose source with a local frame "
                                       "(vehicle.local_frame: true)"));
        return std::unique_ptr<rt::Component>(std::make_unique<LocalPoseSensor>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
