#include "jaus/components/primitive_manipulator_kind.hpp"

#include "jaus/core/component_ids.hpp"

namespace jaus::components {

namespace {
constexpr double kMaxTimeoutS = 60;
}  // namespace

Expected<PrimitiveManipulatorOptions> primitive_manipulator_options(const rt::KindOptions& options) {
  PrimitiveManipulatorOptions o;
  const auto timeout = rt::seconds_option(options, "command_timeout_s", 0, kMaxTimeoutS, o.command_timeout);
  if (!timeout) return unexpected(timeout.error());
  o.command_timeout = *timeout;
  return o;
}

const rt::ComponentKind& primitive_manipulator_kind() {
  static const rt::ComponentKind kind{
      .name = "primitive_manipulator",
      .default_id = component_id::kPrimitiveManipulator,
      .options = {"command_timeout_s"},
      .needs = {ManipulatorArm::kInterface},
      .moves_hardware = true,
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .operator_views = {rt::operator_view::kArm},
      .check = rt::check_by(primitive_manipulator_options),
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto arm = k.need<ManipulatorArm>();
        if (!arm) return unexpected(arm.error());
        const auto options = primitive_manipulator_options(k.options);
        if (!options) return unexpected(options.error());
        return std::unique_ptr<rt::Component>(
            std::make_unique<PrimitiveManipulator>(k.config, k.env, **arm, *options));
      },
  };
  return kind;
}

}  // namespace jaus::components
