#include "jaus/components/local_vector_driver_kind.hpp"

#include "jaus/components/local_vector_driver.hpp"

namespace jaus::components {

const rt::ComponentKind& local_vector_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "local_vector_driver",
      .default_id = kLocalVectorDriverId,
      .options = vector_driver_option_keys(),
      .needs = {PoseSource::kInterface},
      // With emergency_scope vehicle a Set Emergency to the primitive driver holds it too.
      .moves_hardware = true,
      .one_per_node = false,
      .check = rt::check_by(vector_driver_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = vector_driver_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(
            std::make_unique<LocalVectorDriver>(k.config, k.env, **pose, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
