#include "id_map.hpp"

#include <algorithm>

namespace jaus::jss_face {

std::uint16_t IdMap::subsystem() const { return config_.subsystem.value_or(node_.config().subsystem); }

jss::JssId IdMap::jss_of(const Address& ra) const {
  const auto mapped = config_.component_ids.find(ra.component);
  return jss::JssId{subsystem(), ra.node, mapped != config_.component_ids.end() ? mapped->second : ra.component};
}

std::optional<jss::JssId> IdMap::jss_id_of(const Address& ra_component) const {
  if (node_.find(ra_component) == nullptr) return std::nullopt;
  return jss_of(ra_component);
}

std::vector<OurComponent> IdMap::reached_by(const jss::JssId& destination) const {
  std::vector<OurComponent> reached;
  for (const rt::Component* component : node_.local_components()) {
    const jss::JssId id = jss_of(component->address());
    if (destination.matches(id)) reached.push_back({id, component->address()});
  }
  std::sort(reached.begin(), reached.end(), [](const OurComponent& a, const OurComponent& b) { return a.ra < b.ra; });
  return reached;
}

std::optional<OurComponent> IdMap::node_manager() const {
  const auto every = all();
  if (every.empty()) return std::nullopt;
  const auto manager = std::find_if(every.begin(), every.end(), [](const OurComponent& c) { return c.ra.component == 1; });
  return manager != every.end() ? *manager : every.front();
}

}  // namespace jaus::jss_face
