#include "jaus/ocu/discovery.hpp"

namespace jaus::ocu {

namespace {

namespace id = jaus::msg::identification;
constexpr std::uint8_t kNodeManager = 1;
constexpr std::uint8_t kAny = jaus::Address::kBroadcast;

jaus::Address node_manager(std::uint8_t subsystem, std::uint8_t node) {
  return jaus::Address{subsystem, node, kNodeManager, 1};
}

template <class M>
std::optional<M> decode(std::span<const std::uint8_t> payload, jaus::wire::Dialect dialect) {
  M message{};
  if (!jaus::wire::decode_payload_into(payload, message, dialect, jaus::kHeaderSize)) return std::nullopt;
  return message;
}

bool is_real_id(std::uint8_t v) { return v != 0 && v != kAny; }

}  // namespace

std::vector<DiscoveryQuery> Discovery::start() {
  return {DiscoveryQuery{jaus::Address{kAny, kAny, kNodeManager, 1}, Kind::identification, id::kSubsystem}};
}

const DiscoveredNode* Discovery::find_node(std::uint8_t subsystem, std::uint8_t node) const {
  const auto s = subsystems_.find(subsystem);
  if (s == subsystems_.end()) return nullptr;
  const auto n = s->second.nodes.find(node);
  return n == s->second.nodes.end() ? nullptr : &n->second;
}

DiscoveredNode& Discovery::node_of(std::uint8_t subsystem, std::uint8_t node) {
  auto& s = subsystems_[subsystem];
  s.id = subsystem;
  auto& n = s.nodes[node];
  n.id = node;
  return n;
}

void Discovery::ask(std::vector<DiscoveryQuery>& out, const jaus::Address& to, Kind kind, std::uint8_t field,
                    const jaus::Address& key) {
  const DiscoveryQuery query{to, kind, field};
  if (asked_.try_emplace(QuestionKey{key, kind, field}, Question{query, false}).second) out.push_back(query);
}

void Discovery::answered(const jaus::Address& key, Kind kind, std::uint8_t field) {
  if (const auto it = asked_.find(QuestionKey{key, kind, field}); it != asked_.end()) it->second.answered = true;
}

std::vector<DiscoveryQuery> Discovery::unanswered() const {
  std::vector<DiscoveryQuery> out;
  for (const auto& [key, question] : asked_)
    if (!question.answered) out.push_back(question.query);
  return out;
}

void Discovery::add_node(std::uint8_t subsystem, std::uint8_t node, std::vector<DiscoveryQuery>& out) {
  node_of(subsystem, node);
  const auto manager = node_manager(subsystem, node);
  const jaus::Address whole_subsystem{subsystem, 0, 0, 0};
  ask(out, manager, Kind::identification, id::kSubsystem, whole_subsystem);
  ask(out, manager, Kind::configuration, id::kSubsystem, whole_subsystem);
  ask(out, manager, Kind::subsystem_list, 0, whole_subsystem);
  ask(out, manager, Kind::identification, id::kNode, manager);
  // A node manager may describe only its own node in a subsystem answer.
  ask(out, manager, Kind::configuration, id::kNode, manager);
}

void Discovery::add_component(const jaus::Address& a, std::vector<DiscoveryQuery>& out) {
  const auto* known = find_node(a.subsystem, a.node);
  const bool is_new = !known || !known->components.contains({a.component, a.instance});
  if (is_new && (components_in(a.subsystem) >= kMaxComponentsPerSubsystem || component_count() >= kMaxComponents)) {
    ++components_left_out_;
    return;
  }
  add_node(a.subsystem, a.node, out);
  auto& c = node_of(a.subsystem, a.node).components[{a.component, a.instance}];
  c.address = a;
  ask(out, a, Kind::identification, id::kComponent, a);
  ask(out, a, Kind::services, 0, a);
}

std::vector<DiscoveryQuery> Discovery::heard(const jaus::Address& source) {
  std::vector<DiscoveryQuery> out;
  if (!source.is_valid() || source.is_broadcast() || is_self(source)) return out;
  add_component(source, out);
  return out;
}

std::vector<DiscoveryQuery> Discovery::received(const jaus::Header& h, std::span<const std::uint8_t> payload,
                                                jaus::wire::Dialect dialect) {
  if (!h.source.is_valid() || h.source.is_broadcast() || is_self(h.source)) return {};
  std::vector<DiscoveryQuery> out = heard(h.source);
  const jaus::Address& from = h.source;
  const jaus::Address whole_subsystem{from.subsystem, 0, 0, 0};
  const auto manager = node_manager(from.subsystem, from.node);
  switch (h.command_code) {
    case jaus::msg::ReportIdentification::code: {
      const auto report = decode<jaus::msg::ReportIdentification>(payload, dialect);
      if (!report) break;
      const Identification identification{report->identification, report->type, report->authority};
      if (report->query_type == id::kSubsystem) answered(whole_subsystem, Kind::identification, id::kSubsystem);
      if (report->query_type == id::kNode) answered(manager, Kind::identification, id::kNode);
      if (report->query_type == id::kComponent) answered(from, Kind::identification, id::kComponent);
      if (report->query_type == id::kSubsystem) subsystems_[from.subsystem].identification = identification;
      if (report->query_type == id::kNode) node_of(from.subsystem, from.node).identification = identification;
      if (report->query_type == id::kComponent)
        node_of(from.subsystem, from.node).components[{from.component, from.instance}].identification = identification;
      break;
    }
    case jaus::msg::ReportConfiguration::code: {
      const auto report = decode<jaus::msg::ReportConfiguration>(payload, dialect);
      if (!report) break;
      answered(whole_subsystem, Kind::configuration, id::kSubsystem);
      answered(manager, Kind::configuration, id::kNode);
      for (const auto& node : report->nodes) {
        if (!is_real_id(node.node_id)) continue;
        add_node(from.subsystem, node.node_id, out);
        for (const auto& c : node.components)
          if (is_real_id(c.component_id) && is_real_id(c.instance))
            add_component(jaus::Address{from.subsystem, node.node_id, c.component_id, c.instance}, out);
      }
      break;
    }
    case jaus::msg::ReportSubsystemList::code: {
      const auto report = decode<jaus::msg::ReportSubsystemList>(payload, dialect);
      if (!report) break;
      answered(whole_subsystem, Kind::subsystem_list, 0);
      // Each entry speaks for its subsystem: asked like a heartbeat's source.
      for (const auto& entry : report->subsystems) {
        auto more = heard(entry);
        out.insert(out.end(), more.begin(), more.end());
      }
      break;
    }
    case jaus::msg::ReportServices::code: {
      const auto report = decode<jaus::msg::ReportServices>(payload, dialect);
      if (!report) break;
      answered(from, Kind::services, 0);
      auto& node = node_of(from.subsystem, from.node);
      if (from.component == kNodeManager) {
        for (const auto& service : report->services) node.services_by_type[service.type] = service;
      } else {
        node.components[{from.component, from.instance}].own_services = report->services;
      }
      break;
    }
    default:
      break;
  }
  return out;
}

std::size_t Discovery::components_in(std::uint8_t subsystem) const {
  const auto s = subsystems_.find(subsystem);
  if (s == subsystems_.end()) return 0;
  std::size_t n = 0;
  for (const auto& [nid, node] : s->second.nodes) n += node.components.size();
  return n;
}

std::size_t Discovery::component_count() const {
  std::size_t n = 0;
  for (const auto& [sid, s] : subsystems_)
    for (const auto& [nid, node] : s.nodes) n += node.components.size();
  return n;
}

std::vector<jaus::msg::ServiceEntry> Discovery::services_of(const DiscoveredNode& node,
                                                            const DiscoveredComponent& component) {
  if (component.own_services) return *component.own_services;
  if (const auto it = node.services_by_type.find(component.address.component); it != node.services_by_type.end())
    return {it->second};
  return {};
}

}  // namespace jaus::ocu
