// Discovery (jss-notes.md 3.6), answered by the face from what the node has:
// the node manager (RA component 1) is the subsystem's discovery service
// (Query Identification types 2 and 3, Configuration, Subsystem List,
// Services, Service List, Register Services); every component answers Query
// Identification type 4 with its own name. JSS layouts: no authority byte,
// str8 names, u16 subsystems, instance 0, service URIs per component from
// every translator (FacePort::services_of). Register Services is kept per
// sender, bounded (FaceConfig::max_registered_services), never answered.
#include <map>

#include "core_translators.hpp"
#include "face_bytes.hpp"
#include "jaus/node/node.hpp"

namespace jaus::jss_face {
namespace {

namespace id {
constexpr std::uint16_t kRegisterServices = 0x0B00;
constexpr std::uint16_t kQueryIdentification = 0x2B00;
constexpr std::uint16_t kQueryConfiguration = 0x2B01;
constexpr std::uint16_t kQuerySubsystemList = 0x2B02;
constexpr std::uint16_t kQueryServices = 0x2B03;
constexpr std::uint16_t kQueryServiceList = 0x2B04;
constexpr std::uint16_t kReportIdentification = 0x4B00;
constexpr std::uint16_t kReportConfiguration = 0x4B01;
constexpr std::uint16_t kReportSubsystemList = 0x4B02;
constexpr std::uint16_t kReportServices = 0x4B03;
constexpr std::uint16_t kReportServiceList = 0x4B04;
}  // namespace id

namespace identification {
constexpr std::uint8_t kSubsystem = 2;
constexpr std::uint8_t kNode = 3;
constexpr std::uint8_t kComponent = 4;
constexpr std::uint16_t kNodeType = 40001;
constexpr std::uint16_t kComponentType = 60001;
}  // namespace identification

constexpr std::uint8_t kAll = 255;

struct Ours {
  jss::JssId jss;
  Address ra;
};

class DiscoveryTranslator final : public ServiceTranslator {
 public:
  explicit DiscoveryTranslator(const FaceConfig& config) : max_registered_(config.max_registered_services) {}

  std::string_view name() const override { return "discovery"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id != kNodeManagerId) return {};
    return {core_service("Discovery")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    if (message_id == id::kQueryIdentification) return true;
    if (ra_id != kNodeManagerId) return false;
    switch (message_id) {
      case id::kRegisterServices:
      case id::kQueryConfiguration:
      case id::kQuerySubsystemList:
      case id::kQueryServices:
      case id::kQueryServiceList:
        return true;
      default:
        return false;
    }
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    switch (m.message_id) {
      case id::kQueryIdentification: identification(m, port); break;
      case id::kQueryConfiguration: configuration(m, port); break;
      case id::kQuerySubsystemList: subsystem_list(m, port); break;
      case id::kQueryServices: query_services(m, port); break;
      case id::kQueryServiceList: query_service_list(m, port); break;
      case id::kRegisterServices: register_services(m, port); break;
      default: return false;
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
    return all;
  }
  static std::uint16_t subsystem(FacePort& port) {
    return port.config().subsystem.value_or(port.node().config().subsystem);
  }

  void identification(const JssInbound& m, FacePort& port) {
    BodyReader r(m.body);
    std::uint8_t type = 0;
    if (!r.u8(type) || !r.done()) return port.malformed("Query Identification", "not one byte");
    const FaceConfig& config = port.config();
    const bool manager = m.ra_component.component == kNodeManagerId;
    ContentsWriter report(id::kReportIdentification);
    report.u8(type);
    if (type == identification::kSubsystem && manager) {
      report.u16(config.subsystem_type).str8(config.subsystem_name);
    } else if (type == identification::kNode && manager) {
      report.u16(identification::kNodeType).str8(config.node_name);
    } else if (type == identification::kComponent) {
      const rt::Component* component = port.node().find(m.ra_component);
      report.u16(identification::kComponentType).str8(component != nullptr ? component->name() : "component");
    } else {
      return;  // the system (type 1) is not ours to name; types 2 and 3 are the node manager's
    }
    port.reply(m.origin, m.our_component, report);
  }

  void configuration(const JssInbound& m, FacePort& port) {
    BodyReader r(m.body);
    std::uint8_t type = 0;
    if (!r.u8(type) || !r.done()) return port.malformed("Query Configuration", "not one byte");
    // One node: ours, with every component (instance 0: JSS components).
    const auto all = ours(port);
    ContentsWriter report(id::kReportConfiguration);
    report.u8(1).u8(port.node().config().node).u8(static_cast<std::uint8_t>(std::min<std::size_t>(all.size(), 255)));
    for (std::size_t i = 0; i < all.size() && i < 255; ++i) report.u8(all[i].jss.component).u8(0);
    port.reply(m.origin, m.our_component, report);
  }

  void subsystem_list(const JssInbound& m, FacePort& port) {
    if (!m.body.empty()) return port.malformed("Query Subsystem List", "a body where none belongs");
    ContentsWriter report(id::kReportSubsystemList);
    report.u8(1).u16(m.our_component.subsystem).u8(m.our_component.node).u8(m.our_component.component);
    port.reply(m.origin, m.our_component, report);
  }

  // One component's entry of Report Services / Report Service List.
  static void write_component(ContentsWriter& w, const Ours& c, FacePort& port, const std::string& filter) {
    std::vector<ServiceUri> services;
    for (auto& s : port.services_of(c.ra.component))
      if (filter.empty() || s.uri.find(filter) != std::string::npos) services.push_back(std::move(s));
    w.u8(c.jss.component).u8(0).u8(static_cast<std::uint8_t>(std::min<std::size_t>(services.size(), 255)));
    for (std::size_t i = 0; i < services.size() && i < 255; ++i)
      w.str8(services[i].uri).u8(services[i].major).u8(services[i].minor);
  }

  void query_services(const JssInbound& m, FacePort& port) {
    // list8{ u8 node; list8{ u8 component } }; an empty list means all (IOP's fallback).
    BodyReader r(m.body);
    std::uint8_t nodes = 0;
    bool wanted_all = false;
    std::vector<std::uint8_t> wanted_components;
    bool node_wanted = false;
    bool ok = r.u8(nodes);
    if (ok && nodes == 0) wanted_all = node_wanted = true;
    for (std::uint8_t n = 0; ok && n < nodes; ++n) {
      std::uint8_t node = 0;
      std::uint8_t count = 0;
      ok = r.u8(node) && r.u8(count);
      const bool ours_node = node == kAll || node == m.our_component.node;
      node_wanted = node_wanted || ours_node;
      if (ours_node && count == 0) wanted_all = true;
      for (std::uint8_t c = 0; ok && c < count; ++c) {
        std::uint8_t component = 0;
        ok = r.u8(component);
        if (!ours_node) continue;
        if (component == kAll) wanted_all = true;
        wanted_components.push_back(component);
      }
    }
    if (!ok || !r.done()) return port.malformed("Query Services from " + m.origin.client.to_string(), "truncated");
    std::vector<Ours> chosen;
    if (node_wanted)
      for (const Ours& c : ours(port))
        if (wanted_all || std::find(wanted_components.begin(), wanted_components.end(), c.jss.component) !=
                              wanted_components.end())
          chosen.push_back(c);
    ContentsWriter report(id::kReportServices);
    if (chosen.empty()) {
      report.u8(0);
    } else {
      report.u8(1).u8(m.our_component.node).u8(static_cast<std::uint8_t>(std::min<std::size_t>(chosen.size(), 255)));
      for (std::size_t i = 0; i < chosen.size() && i < 255; ++i) write_component(report, chosen[i], port, {});
    }
    port.reply(m.origin, m.our_component, report);
  }

  void query_service_list(const JssInbound& m, FacePort& port) {
    // list16{ u16 subsystem; list8{ u8 node; list8{ PV u8; u8 component; ?0 str8 filter } } }
    BodyReader r(m.body);
    std::uint16_t subsystems = 0;
    std::map<std::uint8_t, std::string> wanted;  // our component (255: all) -> filter
    bool ok = r.u16(subsystems);
    const std::uint16_t our_subsystem = subsystem(port);
    for (std::uint16_t s = 0; ok && s < subsystems; ++s) {
      std::uint16_t sub = 0;
      std::uint8_t nodes = 0;
      ok = r.u16(sub) && r.u8(nodes);
      for (std::uint8_t n = 0; ok && n < nodes; ++n) {
        std::uint8_t node = 0;
        std::uint8_t components = 0;
        ok = r.u8(node) && r.u8(components);
        for (std::uint8_t c = 0; ok && c < components; ++c) {
          std::uint8_t pv = 0;
          std::uint8_t component = 0;
          std::string filter;
          ok = r.u8(pv) && r.u8(component) && ((pv & 1) == 0 || r.str8(filter));
          const bool ours_node = (sub == jss::JssId::kAllSubsystems || sub == our_subsystem) &&
                                 (node == kAll || node == m.our_component.node);
          if (ok && ours_node) wanted.emplace(component, filter);
        }
      }
    }
    if (!ok || !r.done())
      return port.malformed("Query Service List from " + m.origin.client.to_string(), "truncated");
    std::vector<std::pair<Ours, std::string>> chosen;
    for (const Ours& c : ours(port)) {
      if (auto it = wanted.find(c.jss.component); it != wanted.end())
        chosen.emplace_back(c, it->second);
      else if (auto all = wanted.find(kAll); all != wanted.end())
        chosen.emplace_back(c, all->second);
    }
    ContentsWriter report(id::kReportServiceList);
    if (chosen.empty()) {
      report.u16(0);
    } else {
      report.u16(1).u16(our_subsystem).u8(1).u8(m.our_component.node);
      report.u8(static_cast<std::uint8_t>(std::min<std::size_t>(chosen.size(), 255)));
      for (std::size_t i = 0; i < chosen.size() && i < 255; ++i)
        write_component(report, chosen[i].first, port, chosen[i].second);
    }
    port.reply(m.origin, m.our_component, report);
  }

  void register_services(const JssInbound& m, FacePort& port) {
    BodyReader r(m.body);
    std::uint8_t count = 0;
    std::vector<ServiceUri> services;
    bool ok = r.u8(count);
    for (std::uint8_t i = 0; ok && i < count; ++i) {
      ServiceUri s;
      ok = r.str8(s.uri) && r.u8(s.major) && r.u8(s.minor);
      if (ok) services.push_back(std::move(s));
    }
    if (!ok || !r.done())
      return port.malformed("Register Services from " + m.origin.client.to_string(), "truncated");
    auto& kept = registered_[m.origin.client];
    for (auto& s : services) {
      if (std::find(kept.begin(), kept.end(), s) != kept.end()) continue;
      if (registered_count_ >= max_registered_) {
        port.log(rt::LogLevel::warn, "Register Services from " + m.origin.client.to_string() + ": table full (" +
                                         std::to_string(max_registered_) + " services, jss.max_registered_services); " +
                                         s.uri + " not kept");
        break;
      }
      kept.push_back(std::move(s));
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
