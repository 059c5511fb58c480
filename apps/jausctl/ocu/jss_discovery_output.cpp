// `jausctl discover --dialect jss`: what discover_jss found, as a table or JSON.
#include "jaus/ocu/jss_discovery.hpp"
#include "jaus/ocu/names.hpp"
#include "discovery_output.hpp"
#include "jss_commands.hpp"

namespace jausctl::ocu {

namespace {

std::string version_text(const JssService& s) { return std::to_string(s.major) + "." + std::to_string(s.minor); }

Json discovery_json(const JssSystem& system) {
  Json subsystems = Json::array();
  for (const auto& s : system.subsystems) {
    Json nodes = Json::array();
    for (const auto& node : s.nodes) {
      Json components = Json::array();
      for (const auto& c : node.components) {
        Json services = Json::array();
        for (const auto& service : c.services)
          services.push_back(Json{{"uri", service.uri}, {"version", version_text(service)}});
        components.push_back(Json{{"id", c.id.to_string()},
                                  {"component", c.id.component},
                                  {"instance", c.instance},
                                  {"name", c.name.empty() ? Json(nullptr) : Json(c.name)},
                                  {"services", std::move(services)}});
      }
      nodes.push_back(Json{{"node", node.id},
                           {"name", node.name.empty() ? Json(nullptr) : Json(node.name)},
                           {"components", std::move(components)}});
    }
    subsystems.push_back(Json{{"subsystem", s.id},
                              {"name", s.name},
                              {"type", s.type},
                              {"class", identification_class(s.type)},
                              {"discovery", s.discovery.to_string()},
                              {"services_listed", s.services_listed},
                              {"nodes", std::move(nodes)}});
  }
  return Json{{"subsystems", std::move(subsystems)}};
}

// "            services  Transport 1.1, Events 1.1, ..." wrapped at 100 columns.
std::string services_line(const JssComponent& c) {
  constexpr std::size_t kWidth = 100;
  const std::string indent = std::string(14, ' ') + table_cell("services", 8);
  if (c.services.empty()) return indent + "-\n";
  std::string out;
  std::string line = indent;
  for (std::size_t i = 0; i < c.services.size(); ++i) {
    std::string item = std::string(jaus::jss::service_name(c.services[i].uri)) + " " + version_text(c.services[i]) +
                       (i + 1 < c.services.size() ? "," : "");
    if (line.size() > indent.size() && line.size() + 1 + item.size() > kWidth) {
      out += line + "\n";
      line = std::string(indent.size(), ' ');
    }
    if (line.size() > indent.size()) line += ' ';
    line += item;
  }
  return out + line + "\n";
}

std::string discovery_table(const JssSystem& system) {
  std::string out = table_cell("JSS ID", 12) + table_cell("KIND", 20) + table_cell("TYPE", 6) + "IDENTIFICATION\n";
  for (const auto& s : system.subsystems) {
    out += table_cell(std::to_string(s.id), 12) + table_cell("subsystem (" + identification_class(s.type) + ")", 20) +
           table_cell(std::to_string(s.type), 6) + s.name + "\n";
    for (const auto& node : s.nodes) {
      out += table_cell(std::to_string(s.id) + "." + std::to_string(node.id), 12) + table_cell("node", 20) + table_cell("-", 6) +
             (node.name.empty() ? "(no identification)" : node.name) + "\n";
      for (const auto& c : node.components) {
        out += table_cell(c.id.to_string(), 12) + table_cell("component", 20) + table_cell("-", 6) +
               (c.name.empty() ? "(no identification)" : c.name) + "\n";
        out += services_line(c);
      }
    }
    if (!s.services_listed)
      out += std::string(14, ' ') + "(no service list: Query Service List and Query Services unanswered)\n";
  }
  return out;
}

}  // namespace

int run_jss_discover(JssSession& session, jaus::rt::Duration wait, bool json, CommandIo io) {
  JssDiscoveryOptions options;
  options.timeout = wait;
  // Within a wait of seconds a lost broadcast is asked again at once, as the RA discover does (the library's
  // default, 5 s, is for a client that waits for nodes to come up).
  options.identification_period = std::chrono::milliseconds(500);
  auto system = discover_jss(session, options);
  if (!system) {
    if (system.error().code == jaus::ErrorCode::interrupted) {
      io.err << "jausctl discover: interrupted\n";
      return kExitFailure;
    }
    std::string asked;
    for (const auto& peer : session.options().to)
      asked += (asked.empty() ? "" : ", ") + jaus::transport::to_string(peer);
    if (const auto& group = session.options().multicast)
      asked +=
          (asked.empty() ? "the multicast group " : " and the multicast group ") + jaus::transport::to_string(*group);
    io.err << "jausctl discover: " << system.error().message() << " (asked " << asked << ")\n";
    return kExitFailure;
  }
  if (json)
    io.out << discovery_json(*system).dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  else
    io.out << discovery_table(*system);
  if (system->components_left_out > 0)
    io.err << "jausctl discover: " << system->components_left_out
           << " subsystems or components left out (more than a system is believed to have)\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
