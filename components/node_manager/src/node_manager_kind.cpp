#include "jaus/components/node_manager_kind.hpp"

#include "jaus/components/node_manager.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& node_manager_kind() {
  static const rt::ComponentKind kind{
      .name = "node_manager",
      .default_id = component_id::kNodeManager,
      .options = {},
      .needs = {},
      .moves_hardware = false,
      .one_per_node = true,
      .default_node_authority = std::uint8_t{0},  // in the default node
      .check = {},
      // The node's identity is the host's (its defaults when it offers none).
      .make = [](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
        const auto* identity = k.backends.find<const NodeManagerConfig>();
        return std::unique_ptr<rt::Component>(
            std::make_unique<NodeManager>(k.config, k.env, k.directory, identity ? *identity : NodeManagerConfig{}));
      },
  };
  return kind;
}

}  // namespace jaus::components
