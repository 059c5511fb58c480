#include "discovery_output.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "jaus/messages/catalogue.hpp"
#include "jaus/ocu/names.hpp"

namespace jausctl::ocu {

namespace {

// Input and output codes of every service entry, merged and sorted.
struct CodeLists {
  std::map<std::uint16_t, std::uint32_t> inputs;
  std::map<std::uint16_t, std::uint32_t> outputs;
};

CodeLists code_lists(const std::vector<jaus::msg::ServiceEntry>& services) {
  CodeLists out;
  for (const auto& service : services) {
    for (const auto& m : service.inputs) out.inputs[m.command_code] |= m.presence_vector;
    for (const auto& m : service.outputs) out.outputs[m.command_code] |= m.presence_vector;
  }
  return out;
}

Json identification_json(const std::optional<Identification>& identification) {
  if (!identification) return nullptr;
  return Json{{"name", identification->name},
              {"type", identification->type},
              {"class", identification_class(identification->type)},
              {"authority", identification->authority}};
}

Json codes_json(const std::map<std::uint16_t, std::uint32_t>& codes) {
  Json out = Json::array();
  for (const auto& [code, presence] : codes) {
    const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, code);
    out.push_back(Json{{"code", code_text(code)},
                       {"name", info ? Json(info->name) : Json(nullptr)},
                       {"presence_vector", presence}});
  }
  return out;
}

std::string row(const std::string& address, const std::string& kind, const std::optional<Identification>& ident) {
  std::string type = "-";
  std::string authority = "-";
  std::string name = "(no identification)";
  if (ident) {
    type = std::to_string(ident->type);
    authority = std::to_string(ident->authority);
    name = ident->name;
  }
  return table_cell(address, 12) + table_cell(kind, 28) + table_cell(type, 6) + table_cell(authority, 4) + name + "\n";
}

// "            accepts   0x0001 0x0002 ..." under the row, wrapped at 100 columns.
std::string code_line(const std::string& label, const std::map<std::uint16_t, std::uint32_t>& codes) {
  constexpr std::size_t kWidth = 100;
  const std::string indent = std::string(12, ' ') + table_cell(label, 8);
  if (codes.empty()) return indent + "-\n";
  std::string out;
  std::string line = indent;
  for (const auto& [code, presence] : codes) {
    if (line.size() > indent.size() && line.size() + 7 > kWidth) {
      out += line + "\n";
      line = std::string(indent.size(), ' ');
    }
    if (line.size() > indent.size()) line += ' ';
    line += code_text(code);
  }
  return out + line + "\n";
}

}  // namespace

std::string table_cell(std::string text, std::size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text + "  ";
}

Json discovery_json(const Discovery& discovery) {
  Json subsystems = Json::array();
  for (const auto& [sid, s] : discovery.subsystems()) {
    Json nodes = Json::array();
    for (const auto& [nid, node] : s.nodes) {
      Json components = Json::array();
      for (const auto& [key, c] : node.components) {
        const auto lists = code_lists(Discovery::services_of(node, c));
        components.push_back(Json{{"address", c.address.to_string()},
                                  {"component", c.address.component},
                                  {"instance", c.address.instance},
                                  {"kind", component_kind(c.address.component)},
                                  {"identification", identification_json(c.identification)},
                                  {"inputs", codes_json(lists.inputs)},
                                  {"outputs", codes_json(lists.outputs)}});
      }
      nodes.push_back(Json{{"node", nid},
                           {"identification", identification_json(node.identification)},
                           {"components", std::move(components)}});
    }
    subsystems.push_back(Json{{"subsystem", sid},
                              {"identification", identification_json(s.identification)},
                              {"nodes", std::move(nodes)}});
  }
  return Json{{"subsystems", std::move(subsystems)}};
}

std::string discovery_table(const Discovery& discovery) {
  std::string out = table_cell("ADDRESS", 12) + table_cell("KIND", 28) + table_cell("TYPE", 6) + table_cell("AUTH", 4) + "IDENTIFICATION\n";
  for (const auto& [sid, s] : discovery.subsystems()) {
    const std::string kind = "subsystem" + (s.identification ? " (" + identification_class(s.identification->type) + ")" : "");
    out += row(std::to_string(sid), kind, s.identification);
    for (const auto& [nid, node] : s.nodes) {
      out += row(std::to_string(sid) + "." + std::to_string(nid), "node", node.identification);
      for (const auto& [key, c] : node.components) {
        out += row(c.address.to_string(), component_kind(c.address.component), c.identification);
        const auto lists = code_lists(Discovery::services_of(node, c));
        out += code_line("accepts", lists.inputs);
        out += code_line("provides", lists.outputs);
      }
    }
  }
  return out;
}

}  // namespace jausctl::ocu
