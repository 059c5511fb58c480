#include "jaus/components/communicator_kind.hpp"

#include "jaus/components/communicator.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& communicator_kind() {
  static const rt::ComponentKind kind{
      .name = "communicator",
      .default_id = component_id::kCommunicator,
      .options = {},
      .needs = {},
      .moves_hardware = false,
      .one_per_node = false,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .check = {},
      // One data link; heartbeats to other subsystems at the node's heartbeat
      // period, which the host offers as "heartbeat_period".
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        CommunicatorConfig config;
        if (const auto* period = k.backends.find<const rt::Duration>("heartbeat_period"))
          config.heartbeat_period = *period;
        return std::unique_ptr<rt::Component>(std::make_unique<Communicator>(k.config, k.env, config));
      },
  };
  return kind;
}

}  // namespace jaus::components
