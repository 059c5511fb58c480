#include "jaus/host/component_kinds.hpp"

#include "jaus/components/communicator.hpp"

namespace jaus::host {

namespace {

const std::vector<ComponentKind>& kinds() {
  // Register a kind only once make_component() can build it.
  static const std::vector<ComponentKind> registry{
      {"node_manager", 1, {}},
      {"communicator", 35, {}},
  };
  return registry;
}

}  // namespace

std::span<const ComponentKind> component_kinds() { return kinds(); }

const ComponentKind* find_component_kind(std::string_view name) {
  for (const auto& kind : kinds())
    if (kind.name == name) return &kind;
  return nullptr;
}

Expected<std::unique_ptr<rt::Component>> make_component(const ComponentSpec& spec, const ComponentSettings& settings,
                                                        node::Node& node) {
  rt::ComponentConfig c = settings.defaults;
  c.name = spec.name.empty() ? spec.kind : spec.name;
  c.address = Address{node.config().subsystem, node.config().node, spec.id, spec.instance};
  c.authority = spec.authority;
  std::unique_ptr<rt::Component> made;
  if (spec.kind == "node_manager")
    made = std::make_unique<components::NodeManager>(c, node.environment(), node, settings.identity);
  else if (spec.kind == "communicator")
    made = std::make_unique<components::Communicator>(c, node.environment());
  if (made) return made;
  return unexpected(make_error(ErrorCode::invalid_argument,
                               "component kind '" + spec.kind + "' cannot be hosted by this build"));
}

}  // namespace jaus::host
