// The kind of a driver above the primitive driver, described once: every one
// needs the node's pose source, moves hardware (with emergency_scope vehicle
// a Set Emergency to the primitive driver holds it too), may be configured
// more than once, and is made from its options; a driver whose elements are
// in the local frame also needs a source that has one.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "jaus/components/mobility_driver.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

enum class DriverFrame : std::uint8_t { any, local };

// Driver: constructible from (ComponentConfig, Environment, PoseSource&, Options);
// read_options: Expected<Options>(const rt::KindOptions&); operator_views:
// what an operator unit shows for it (rt::operator_view).
template <class Driver, class ReadOptions>
rt::ComponentKind mobility_driver_kind(std::string_view name, std::uint8_t id,
                                       std::vector<std::string_view> option_keys, ReadOptions read_options,
                                       DriverFrame frame, std::vector<std::string_view> operator_views = {}) {
  return rt::ComponentKind{
      .name = name,
      .default_id = id,
      .options = std::move(option_keys),
      .needs = {PoseSource::kInterface},
      .moves_hardware = true,
      .one_per_node = false,
      // In the default node with authority 1: below an operator's, who takes
      // the primitive driver over at once.
      .default_node_authority = std::uint8_t{1},
      .operator_views = std::move(operator_views),
      // The options, and the authority under their ceiling: `jausd --check-config`
      // refuses what make() would (operators always win).
      .check = [read_options](const rt::KindOptions& k) -> Expected<void> {
        const auto options = read_options(k);
        if (!options) return unexpected(options.error());
        return check_driver_authority(k.kind, k.authority, options->mobility);
      },
      .make = [read_options, frame](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto pose = k.need<PoseSource>();
        if (!pose) return unexpected(pose.error());
        const auto options = read_options(k.options);
        if (!options) return unexpected(options.error());
        // Safety: never made with an authority above its ceiling (operators always win), checked
        // again here for hosts that make components without check().
        if (auto authority = check_driver_authority(k.options.kind, k.config.authority, options->mobility); !authority)
          return unexpected(authority.error());
        if (frame == DriverFrame::local)
          if (auto has_frame = require_local_frame(**pose, k.options.kind); !has_frame)
            return unexpected(has_frame.error());
        return std::unique_ptr<rt::Component>(std::make_unique<Driver>(k.config, k.env, **pose, *options));
      },
  };
}

}  // namespace jaus::components
