// Discovery (docs/jss.md, "Discovery"), answered by the face from what the node has:
// the node manager (RA component 1) is the subsystem's discovery service
// (Query Identification types 2 and 3, Configuration, Subsystem List,
// Services, Service List, Register Services); every component answers Query
// Identification type 4 with its own name. JSS layouts: no authority byte,
// str8 names, u16 subsystems, instance 0, service URIs per component from
// every translator (FacePort::services_of). Register Services is kept per
// sender, bounded (FaceConfig::max_registered_services), never answered.
#include <algorithm>
#include <map>

#include "core_translators.hpp"
#include "jaus/jss/messages/discovery.hpp"
#include "jaus/node/node.hpp"

namespace jaus::jss_face {
namespace {

namespace jss_msg = jss::msg;
namespace identification = jaus::msg::identification;
constexpr std::uint8_t kAll = jss::JssId::kAll;
constexpr std::size_t kMaxList = 255;  // u8 counts

struct Ours {
  jss::JssId jss;
  Address ra;
};

class DiscoveryTranslator final : public ServiceTranslator {
 public:
  explicit DiscoveryTranslator(const FaceConfig& config) : max_registered_(config.max_registered_services) {}

  std::string_view name() const override { return "discovery"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id != component_id::kNodeManager) return {};
    return {core_service("Discovery")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    if (message_id == jss_msg::QueryIdentification::code) return true;
    return ra_id == component_id::kNodeManager &&
           is_one_of<jss_msg::RegisterServices, jss_msg::QueryConfiguration, jss_msg::QuerySubsystemList,
                     jss_msg::QueryServices, jss_msg::QueryServiceList>(message_id);
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    switch (m.message_id) {
      case jss_msg::QueryIdentification::code:
        if (auto q = decode_jss<jss_msg::QueryIdentification>(m, port)) identification(m, *q, port);
        break;
      case jss_msg::QueryConfiguration::code:
        if (decode_jss<jss_msg::QueryConfiguration>(m, port)) configuration(m, port);
        break;
      case jss_msg::QuerySubsystemList::code:
        if (decode_jss<jss_msg::QuerySubsystemList>(m, port))
          reply_jss(port, m.origin, m.our_component, jss_msg::ReportSubsystemList{{{m.our_component}}});
        break;
      case jss_msg::QueryServices::code:
        if (auto q = decode_jss<jss_msg::QueryServices>(m, port)) query_services(m, *q, port);
        break;
      case jss_msg::QueryServiceList::code:
        if (auto q = decode_jss<jss_msg::QueryServiceList>(m, port)) query_service_list(m, *q, port);
        break;
      case jss_msg::RegisterServices::code:
        if (auto r = decode_jss<jss_msg::RegisterServices>(m, port)) register_services(m, *r, port);
        break;
      default:
        return false;
    }
    return true;
  }
  bool from_ra(const RaOutbound&, FacePort&) override { return false; }

  void forget(const jss::JssId& client_node) override {
    for (auto it = registered_.begin(); it != registered_.end();) {
      if (client_node.matches(it->first)) {
        registered_count_ -= it->second.size();
        it = registered_.erase(it);
      } else {
        ++it;
      }
    }
  }

 private:
  static std::vector<Ours> ours(FacePort& port) {
    std::vector<Ours> all;
    for (const rt::Component* c : port.node().local_components())
      if (auto jss = port.jss_id_of(c->address())) all.push_back({*jss, c->address()});
    std::sort(all.begin(), all.end(), [](const Ours& a, const Ours& b) { return a.jss < b.jss; });
    if (all.size() > kMaxList) all.resize(kMaxList);
    return all;
  }

  void identification(const JssInbound& m, const jss_msg::QueryIdentification& q, FacePort& port) {
    const FaceConfig& config = port.config();
    const bool manager = m.ra_component.component == component_id::kNodeManager;
    jss_msg::ReportIdentification report;
    report.query_type = q.query_type;
    if (q.query_type == identification::kSubsystem && manager) {
      report.type = config.subsystem_type;
      report.identification = config.subsystem_name;
    } else if (q.query_type == identification::kNode && manager) {
      report.type = jss_msg::identification_type::kNode;
      report.identification = config.node_name;
    } else if (q.query_type == identification::kComponent) {
      const rt::Component* component = port.node().find(m.ra_component);
      report.type = jss_msg::identification_type::kComponent;
      report.identification = component != nullptr ? component->name() : "component";
    } else {
      return;  // the system (type 1) is not ours to name; types 2 and 3 are the node manager's
    }
    if (report.identification.size() > 255) report.identification.resize(255);
    reply_jss(port, m.origin, m.our_component, report);
  }

  void configuration(const JssInbound& m, FacePort& port) {
    // One node: ours, with every component (instance 0: JSS components).
    jss_msg::ReportConfiguration report;
    jss_msg::ConfigurationNode node;
    node.node_id = m.our_component.node;
    for (const Ours& c : ours(port)) node.components.push_back({c.jss.component, 0});
    report.nodes.push_back(std::move(node));
    reply_jss(port, m.origin, m.our_component, report);
  }

  // One component's entry of Report Services / Report Service List.
  static jss_msg::ServicesComponent entry_of(const Ours& c, FacePort& port, const std::string& filter) {
    jss_msg::ServicesComponent entry;
    entry.component_id = c.jss.component;
    entry.instance_id = 0;
    for (auto& s : port.services_of(c.ra.component)) {
      if (!filter.empty() && s.uri.find(filter) == std::string::npos) continue;
      if (entry.services.size() == kMaxList) break;
      entry.services.push_back({std::move(s.uri), s.major, s.minor});
    }
    return entry;
  }

  void query_services(const JssInbound& m, const jss_msg::QueryServices& q, FacePort& port) {
    // An empty node list, an empty component list or 255 means all (IOP's fallback sends none).
    bool all = q.nodes.empty();
    std::vector<std::uint8_t> wanted;
    for (const auto& node : q.nodes) {
      if (node.node_id != kAll && node.node_id != m.our_component.node) continue;
      if (node.component_ids.empty()) all = true;
      for (std::uint8_t id : node.component_ids) {
        if (id == kAll) all = true;
        wanted.push_back(id);
      }
    }
    jss_msg::ServicesNode node;
    node.node_id = m.our_component.node;
    for (const Ours& c : ours(port))
      if (all || std::find(wanted.begin(), wanted.end(), c.jss.component) != wanted.end())
        node.components.push_back(entry_of(c, port, {}));
    jss_msg::ReportServices report;
    if (!node.components.empty()) report.nodes.push_back(std::move(node));
    reply_jss(port, m.origin, m.our_component, report);
  }

  void query_service_list(const JssInbound& m, const jss_msg::QueryServiceList& q, FacePort& port) {
    const std::uint16_t our_subsystem = m.our_component.subsystem;
    std::map<std::uint8_t, std::string> wanted;  // our component (255: all) -> search filter
    for (const auto& subsystem : q.subsystems) {
      if (subsystem.subsystem_id != jss::JssId::kAllSubsystems && subsystem.subsystem_id != our_subsystem) continue;
      for (const auto& node : subsystem.nodes) {
        if (node.node_id != kAll && node.node_id != m.our_component.node) continue;
        for (const auto& component : node.components)
          wanted.emplace(component.component_id, component.search_filter.value_or(""));
      }
    }
    jss_msg::ServicesNode node;
    node.node_id = m.our_component.node;
    for (const Ours& c : ours(port)) {
      if (auto it = wanted.find(c.jss.component); it != wanted.end())
        node.components.push_back(entry_of(c, port, it->second));
      else if (auto every = wanted.find(kAll); every != wanted.end())
        node.components.push_back(entry_of(c, port, every->second));
    }
    jss_msg::ReportServiceList report;
    if (!node.components.empty()) report.subsystems.push_back({our_subsystem, {std::move(node)}});
    reply_jss(port, m.origin, m.our_component, report);
  }

  void register_services(const JssInbound& m, const jss_msg::RegisterServices& r, FacePort& port) {
    auto& kept = registered_[m.origin.client];
    for (const auto& s : r.services) {
      const ServiceUri service{s.uri, s.major_version, s.minor_version};
      if (std::find(kept.begin(), kept.end(), service) != kept.end()) continue;
      if (registered_count_ >= max_registered_) {
        port.log(rt::LogLevel::warn, "Register Services from " + port.describe_client(m.origin.client) + ": table full (" +
                                         std::to_string(max_registered_) +
                                         " services, jss.max_registered_services); the rest not kept");
        break;
      }
      kept.push_back(service);
      ++registered_count_;
    }
    if (kept.empty()) registered_.erase(m.origin.client);
  }

  std::size_t max_registered_;
  std::size_t registered_count_ = 0;
  std::map<jss::JssId, std::vector<ServiceUri>> registered_;
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_discovery_translator(const FaceConfig& config) {
  return std::make_unique<DiscoveryTranslator>(config);
}

}  // namespace jaus::jss_face
