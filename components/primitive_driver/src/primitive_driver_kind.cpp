#include "jaus/components/primitive_driver_kind.hpp"

#include "jaus/core/component_ids.hpp"

namespace jaus::components {

namespace {
constexpr double kMaxTimeoutS = 60;
}  // namespace

Expected<PrimitiveDriverOptions> primitive_driver_options(const rt::KindOptions& options) {
  PrimitiveDriverOptions o;
  const auto timeout = rt::seconds_option(options, "command_timeout_s", 0, kMaxTimeoutS, o.command_timeout);
  if (!timeout) return unexpected(timeout.error());
  o.command_timeout = *timeout;
  const auto brake = rt::number_option(options, "stop_brake_percent", 0, 100, o.stop_brake_percent);
  if (!brake) return unexpected(brake.error());
  o.stop_brake_percent = *brake;
  return o;
}

const rt::ComponentKind& primitive_driver_kind() {
  static const rt::ComponentKind kind{
      .name = "primitive_driver",
      .default_id = component_id::kPrimitiveDriver,
      .options = {"command_timeout_s", "stop_brake_percent"},
      .needs = {Drive::kInterface},
      .moves_hardware = true,
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .operator_views = {rt::operator_view::kDrive, rt::operator_view::kEmergency},
      .check = rt::check_by(primitive_driver_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto drive = k.need<Drive>();
        if (!drive) return unexpected(drive.error());
        const auto options = primitive_driver_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(std::make_unique<PrimitiveDriver>(k.config, k.env, **drive, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
