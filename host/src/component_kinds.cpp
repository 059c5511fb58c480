#include "jaus/host/component_kinds.hpp"

#include "jaus/host/component_options.hpp"

namespace jaus::host {

namespace {

std::vector<ComponentKind>& kinds() {
  static std::vector<ComponentKind> registry = [] {
    std::vector<ComponentKind> r;
    for (const ComponentKind* kind : builtin_component_kinds()) r.push_back(*kind);
    return r;
  }();
  return registry;
}

}  // namespace

const std::vector<ComponentKind>& component_kinds() { return kinds(); }

const ComponentKind* find_component_kind(std::string_view name) {
  for (const auto& kind : kinds())
    if (kind.name == name) return &kind;
  return nullptr;
}

Expected<void> add_component_kind(ComponentKind kind) {
  if (kind.name.empty()) return unexpected(make_error(ErrorCode::invalid_argument, "a component kind needs a name"));
  if (find_component_kind(kind.name))
    return unexpected(
        make_error(ErrorCode::invalid_argument, "component kind '" + std::string(kind.name) + "' already exists"));
  if (!kind.make)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "component kind '" + std::string(kind.name) + "' cannot make components"));
  kinds().push_back(std::move(kind));
  return {};
}

bool remove_component_kind(std::string_view name) {
  auto& all = kinds();
  for (auto it = all.begin(); it != all.end(); ++it)
    if (it->name == name) {
      all.erase(it);
      return true;
    }
  return false;
}

bool has_hardware(std::string_view kind) {
  const ComponentKind* k = find_component_kind(kind);
  return k && !k->needs.empty();
}

bool moves_hardware(std::string_view kind) {
  const ComponentKind* k = find_component_kind(kind);
  return k && k->moves_hardware;
}

Expected<std::unique_ptr<rt::Component>> make_component(const ComponentSpec& spec, const ComponentSettings& settings,
                                                        node::Node& node, const rt::Backends& backends) {
  const ComponentKind* kind = find_component_kind(spec.kind);
  if (!kind || !kind->make)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "component kind '" + spec.kind + "' cannot be hosted by this build"));
  rt::ComponentConfig c = settings.defaults;
  c.name = spec.name.empty() ? spec.kind : spec.name;
  c.address = Address{node.config().subsystem, node.config().node, spec.id, spec.instance};
  c.authority = spec.authority;
  // What every kind may look up besides the hardware: the node's identity
  // and its heartbeat period.
  rt::Backends offered = backends;
  offered.offer<const components::NodeManagerConfig>(&settings.identity);
  offered.offer<const rt::Duration>("heartbeat_period", &settings.identity.heartbeat_period);
  const rt::KindContext context{c, node.environment(), node, rt::KindOptions{kind->name, spec.options, spec.authority},
                                offered};
  auto made = kind->make(context);
  if (made && !*made)
    return unexpected(make_error(ErrorCode::invalid_argument, spec.kind + " made no component"));
  return made;
}

Expected<void, OptionProblem> check_component_options(const ComponentSpec& spec) {
  const ComponentKind* kind = find_component_kind(spec.kind);
  if (!kind || !kind->check) return {};
  const Expected<void> checked = kind->check(rt::KindOptions{kind->name, spec.options, spec.authority});
  if (checked) return {};
  const auto line = spec.option_lines.find(checked.error().field);
  return unexpected(
      OptionProblem{checked.error().message(), line != spec.option_lines.end() ? line->second : spec.line});
}

}  // namespace jaus::host
