#include "jaus/components/visual_sensor_kind.hpp"

#include <cmath>

#include "jaus/components/frame_worker.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

Expected<VisualSensorOptions> visual_sensor_options(const rt::KindOptions& options) {
  VisualSensorOptions o;
  // At most the service connection table (64 by default), at least one.
  const auto connections = rt::number_option(options, "image_connections_per_requester", 1, 64,
                                             static_cast<double>(o.image_connections_per_requester));
  if (!connections) return unexpected(connections.error());
  if (*connections != std::floor(*connections))
    return unexpected(rt::option_error(options, "image_connections_per_requester", "a whole number 1..64"));
  o.image_connections_per_requester = static_cast<std::size_t>(*connections);
  return o;
}

const rt::ComponentKind& visual_sensor_kind() {
  static const rt::ComponentKind kind{
      .name = "visual_sensor",
      .default_id = component_id::kVisualSensor,
      .options = {"image_connections_per_requester"},
      .needs = {Cameras::kInterface},
      .moves_hardware = true,  // the cameras' mounts
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .operator_views = {rt::operator_view::kCamera},
      .check = rt::check_by(visual_sensor_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto cameras = k.need<Cameras>();
        if (!cameras) return unexpected(cameras.error());
        const auto options = visual_sensor_options(k.options);
        if (!options) return unexpected(options.error());
        auto sensor = std::make_unique<VisualSensor>(k.config, k.env, **cameras, *options);
        // Frames captured and encoded off the loop when the host offers a
        // worker; the images may come from other cameras than the mounts
        // ("camera_images": the simulated cameras, when a platform moves the mounts).
        if (auto* worker = k.backends.find<FrameWorker>())
          sensor->use_frame_worker(*worker, k.backends.find<Cameras>("camera_images"));
        return std::unique_ptr<rt::Component>(std::move(sensor));
      },
  };
  return kind;
}

}  // namespace jaus::components
