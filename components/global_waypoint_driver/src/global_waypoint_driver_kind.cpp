#include "jaus/components/global_waypoint_driver_kind.hpp"

#include "jaus/components/global_waypoint_driver.hpp"

namespace jaus::components {

const rt::ComponentKind& global_waypoint_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "global_waypoint_driver",
      .default_id = kGlobalWaypointDriverId,
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
        return std::unique_ptr<rt::Component>(
            std::make_unique<GlobalWaypointDriver>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
