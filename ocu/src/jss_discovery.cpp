#include "jaus/ocu/jss_discovery.hpp"

#include <algorithm>
#include <map>

#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

namespace {

namespace jss_msg = jss::msg;

bool uri_matches(const std::string& uri, std::string_view wanted) {
  if (uri == wanted) return true;
  // "PrimitiveDriver" names urn:jaus:jss:mobility:PrimitiveDriver.
  return wanted.find(':') == std::string_view::npos && uri.size() > wanted.size() &&
         uri.compare(uri.size() - wanted.size(), wanted.size(), wanted) == 0 &&
         uri[uri.size() - wanted.size() - 1] == ':';
}

// A subsystem as it is being learnt: components by (node, component).
struct Gathering {
  JssSubsystem subsystem;
  std::map<std::pair<std::uint8_t, std::uint8_t>, JssComponent> components;
};

// Adds a component unless the subsystem is full; the component either way (or null).
JssComponent* component_of(Gathering& g, std::uint8_t node, std::uint8_t component, const JssDiscoveryOptions& options,
                           std::size_t& left_out) {
  const auto key = std::make_pair(node, component);
  if (const auto it = g.components.find(key); it != g.components.end()) return &it->second;
  if (node == 0 || component == 0 || node == jss::JssId::kAll || component == jss::JssId::kAll) return nullptr;
  if (g.components.size() >= options.max_components_per_subsystem) {
    ++left_out;
    return nullptr;
  }
  JssComponent& c = g.components[key];
  c.id = jss::JssId{g.subsystem.id, node, component};
  return &c;
}

void add_services(Gathering& g, const std::vector<jss_msg::ServicesNode>& nodes, const JssDiscoveryOptions& options,
                  std::size_t& left_out) {
  for (const auto& node : nodes)
    for (const auto& entry : node.components) {
      JssComponent* c = component_of(g, node.node_id, entry.component_id, options, left_out);
      if (!c) continue;
      c->instance = entry.instance_id;
      c->services.clear();
      for (const auto& s : entry.services) c->services.push_back(JssService{s.uri, s.major_version, s.minor_version});
    }
}

// Query Configuration, then the service list (v1.1, else Query Services v1.0), then names.
void learn_subsystem(JssSession& session, Gathering& g, const JssDiscoveryOptions& options, std::size_t& left_out) {
  const jss::JssId discovery = g.subsystem.discovery;
  jss_msg::QueryConfiguration query_configuration;
  query_configuration.query_field = jss_msg::identification::kSubsystem;
  if (auto configuration =
          session.query<jss_msg::ReportConfiguration>(discovery, query_configuration, options.query_timeout)) {
    for (const auto& node : configuration->nodes)
      for (const auto& entry : node.components)
        if (JssComponent* c = component_of(g, node.node_id, entry.component_id, options, left_out))
          c->instance = entry.instance_id;
  }
  if (session.interrupted()) return;
  jss_msg::QueryServiceList query_list;
  jss_msg::ServiceListQuerySubsystem wanted;
  wanted.subsystem_id = g.subsystem.id;
  wanted.nodes.push_back(jss_msg::ServiceListQueryNode{jss::JssId::kAll, {jss_msg::ServiceListQueryComponent{}}});
  query_list.subsystems.push_back(wanted);
  if (auto list = session.query<jss_msg::ReportServiceList>(discovery, query_list, options.query_timeout)) {
    g.subsystem.services_listed = true;
    for (const auto& s : list->subsystems)
      if (s.subsystem_id == g.subsystem.id) add_services(g, s.nodes, options, left_out);
  } else if (!session.interrupted()) {
    // A core v1.0 node: Query Services with no node listed asks for all (as IOP's fallback).
    if (auto services = session.query<jss_msg::ReportServices>(discovery, jss_msg::QueryServices{}, options.query_timeout)) {
      g.subsystem.services_listed = true;
      add_services(g, services->nodes, options, left_out);
    }
  }
  if (!options.component_names) return;
  jss_msg::QueryIdentification query_name;
  query_name.query_type = jss_msg::identification::kComponent;
  for (auto& [key, c] : g.components) {
    if (session.interrupted()) return;
    if (auto name = session.query<jss_msg::ReportIdentification>(c.id, query_name, options.query_timeout))
      c.name = name->identification;
  }
}

// A node's name: Query Identification (node) to its discovery component, else its first component.
void name_node(JssSession& session, const jss::JssId& discovery, JssNode& node, const JssDiscoveryOptions& options) {
  if (node.components.empty()) return;
  const jss::JssId asked = discovery.node == node.id ? discovery : node.components.front().id;
  jss_msg::QueryIdentification query;
  query.query_type = jss_msg::identification::kNode;
  if (auto report = session.query<jss_msg::ReportIdentification>(asked, query, options.query_timeout))
    node.name = report->identification;
}

}  // namespace

bool JssComponent::has(std::string_view uri) const {
  return std::any_of(services.begin(), services.end(), [&](const JssService& s) { return uri_matches(s.uri, uri); });
}

std::vector<const JssComponent*> JssSubsystem::with(std::string_view uri) const {
  std::vector<const JssComponent*> out;
  for (const auto& node : nodes)
    for (const auto& c : node.components)
      if (c.has(uri)) out.push_back(&c);
  return out;
}

const JssSubsystem* JssSystem::find(std::uint16_t subsystem) const {
  for (const auto& s : subsystems)
    if (s.id == subsystem) return &s;
  return nullptr;
}

const JssComponent* JssSystem::find(const jss::JssId& component) const {
  const JssSubsystem* s = find(component.subsystem);
  if (!s) return nullptr;
  for (const auto& node : s->nodes)
    if (node.id == component.node)
      for (const auto& c : node.components)
        if (c.id == component) return &c;
  return nullptr;
}

Expected<JssSystem> discover_jss(JssSession& session, const JssDiscoveryOptions& options) {
  std::map<std::uint16_t, Gathering> found;
  std::size_t left_out = 0;
  const auto listener = session.listen([&](const JssReceived& m) {
    if (m.message_id() != jss_msg::ReportIdentification::code) return;
    const jss::JssId source = m.source();
    if (source.subsystem == session.self().subsystem || found.count(source.subsystem) > 0) return;
    auto report = jss::decode_contents<jss_msg::ReportIdentification>(m.contents);
    if (!report || report->query_type != jss_msg::identification::kSubsystem) return;
    if (found.size() >= options.max_subsystems) {
      ++left_out;
      return;
    }
    Gathering& g = found[source.subsystem];
    g.subsystem.id = source.subsystem;
    g.subsystem.name = report->identification;
    g.subsystem.type = report->type;
    g.subsystem.discovery = source;
  });
  jss_msg::QueryIdentification query;
  query.query_type = jss_msg::identification::kSubsystem;
  const auto started = session.clock().now();
  const auto deadline = started + options.timeout;
  const auto period = std::max<rt::Duration>(options.identification_period, std::chrono::milliseconds(10));
  // Until the first subsystem answers, asked again every period (IOP: 5 s).
  while (found.empty()) {
    session.send(options.target, query);
    const auto now = session.clock().now();
    if (now >= deadline) break;
    session.run_until([&] { return !found.empty(); }, std::min(period, deadline - now));
    if (session.interrupted() || session.clock().now() >= deadline) break;
  }
  if (!found.empty()) session.run_for(options.gather);  // the others that answer the same broadcast
  session.unlisten(listener);
  if (session.interrupted()) return unexpected(make_error(ErrorCode::interrupted, "interrupted"));
  if (found.empty())
    return unexpected(make_error(
        ErrorCode::timeout, "no JSS subsystem answered Query Identification within " + seconds_text(options.timeout)));
  JssSystem system;
  for (auto& [id, g] : found) {
    learn_subsystem(session, g, options, left_out);
    if (session.interrupted()) return unexpected(make_error(ErrorCode::interrupted, "interrupted"));
    std::map<std::uint8_t, JssNode> nodes;
    for (auto& [key, c] : g.components) {
      JssNode& node = nodes[key.first];
      node.id = key.first;
      node.components.push_back(std::move(c));
    }
    if (options.component_names)
      for (auto& [node_id, node] : nodes) {
        name_node(session, g.subsystem.discovery, node, options);
        if (session.interrupted()) return unexpected(make_error(ErrorCode::interrupted, "interrupted"));
      }
    for (auto& [node_id, node] : nodes) g.subsystem.nodes.push_back(std::move(node));
    system.subsystems.push_back(std::move(g.subsystem));
  }
  system.components_left_out = left_out;
  return system;
}

}  // namespace jaus::ocu
