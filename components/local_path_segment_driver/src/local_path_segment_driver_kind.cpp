#include "jaus/components/local_path_segment_driver_kind.hpp"

#include "jaus/components/local_path_segment_driver.hpp"

namespace jaus::components {

const rt::ComponentKind& local_path_segment_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "local_path_segment_driver",
      .default_id = kLocalPathSegmentDriverId,
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
        // Local segments on a source known to have no local frame could never be followed.
        if (const auto sample = (*pose)->sample(); sample && !sample->local_position)
          return unexpected(make_error(ErrorCode::invalid_argument,
                                       "local_path_segment_driver needs a pose source with a local frame "
                                       "(vehicle.local_frame: true)"));
        return std::unique_ptr<rt::Component>(
            std::make_unique<LocalPathSegmentDriver>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
