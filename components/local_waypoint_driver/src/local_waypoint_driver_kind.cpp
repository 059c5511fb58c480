#include "jaus/components/local_waypoint_driver_kind.hpp"

#include "jaus/components/local_waypoint_driver.hpp"

namespace jaus::components {

const rt::ComponentKind& local_waypoint_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "local_waypoint_driver",
      .default_id = kLocalWaypointDriverId,
      .options = waypoint_driver_option_keys(),
      .needs = {PoseSource::kInterface},
      .moves_hardware = true,
      .one_per_node = false,
      .check = rt::check_by(waypoint_driver_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = waypoint_driver_options(k.options);
        if (!options) return unexpected(options.error());
        // Local waypoints on a source known to have no local frame could never be driven.
        if (const auto sample = (*pose)->sample(); sample && !sample->local_position)
          return unexpected(make_error(ErrorCode::invalid_argument,
                                       "local_waypoint_driver needs a pose source with a local frame "
                                       "(vehicle.local_frame: true)"));
        return std::unique_ptr<rt::Component>(
            std::make_unique<LocalWaypointDriver>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
