#include "jaus/components/global_path_segment_driver_kind.hpp"

#include "jaus/components/global_path_segment_driver.hpp"

namespace jaus::components {

const rt::ComponentKind& global_path_segment_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "global_path_segment_driver",
      .default_id = kGlobalPathSegmentDriverId,
      .options = path_segment_driver_option_keys(),
      .needs = {PoseSource::kInterface},
      .moves_hardware = true,
      .one_per_node = false,
      .check = rt::check_by(path_segment_driver_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = path_segment_driver_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(
            std::make_unique<GlobalPathSegmentDriver>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
