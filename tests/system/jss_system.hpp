// What the JSS system tests share: a JSS operator unit (ocu::JssSession on
// UDP, AS5669A only) beside a real jausd with its JSS face on, typed
// queries that fail the test with what was seen, and finding components by
// the services Report Services lists.
#pragma once

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/jss/all.hpp"
#include "jaus/ocu/jss_session.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::test {

// jausd's configuration lines that turn its JSS face on (the rest is the default).
inline std::string jss_on_config() { return "jss: {enabled: true}\n"; }

// A JSS operator unit bound to `bind_address` (any port), talking to the node at `node_address`:3794.
inline std::unique_ptr<ocu::JssSession> open_jss_operator(const jss::JssId& self, const std::string& bind_address,
                                                          const std::string& node_address, const std::string& name,
                                                          boost::asio::io_context* io = nullptr) {
  ocu::JssSessionOptions options;
  options.self = self;
  options.name = name;
  auto node = transport::parse_endpoint(node_address + ":3794");
  auto bind = transport::parse_endpoint(bind_address, 0);  // any free port
  EXPECT_TRUE(node && bind) << node_address << " " << bind_address;
  if (!node || !bind) return nullptr;
  options.to = {*node};
  options.bind = *bind;
  auto session = ocu::JssSession::open(options, io);
  EXPECT_TRUE(session) << (session ? "" : session.error().message());
  return session ? std::move(*session) : nullptr;
}

// A service of a component in Report Services.
struct ListedComponent {
  jss::JssId id;
  std::vector<std::string> uris;
  bool has(const std::string& uri) const {
    for (const auto& u : uris)
      if (u == uri) return true;
    return false;
  }
  bool has_mobility() const {
    for (const auto& u : uris)
      if (u.rfind("urn:jaus:jss:mobility:", 0) == 0) return true;
    return false;
  }
};

inline std::vector<ListedComponent> listed_components(std::uint16_t subsystem, const jss::msg::ReportServices& report) {
  std::vector<ListedComponent> out;
  for (const auto& node : report.nodes)
    for (const auto& component : node.components) {
      ListedComponent c{jss::JssId{subsystem, node.node_id, component.component_id}, {}};
      for (const auto& s : component.services) c.uris.push_back(s.uri);
      out.push_back(std::move(c));
    }
  return out;
}

inline const ListedComponent* first_with(const std::vector<ListedComponent>& components, const std::string& uri) {
  for (const auto& c : components)
    if (c.has(uri)) return &c;
  return nullptr;
}

inline jss::msg::QueryServices all_services_query() {
  jss::msg::QueryServices query;
  query.nodes.push_back(jss::msg::QueryServicesNode{jss::JssId::kAll, {jss::JssId::kAll}});
  return query;
}

// The presence vector of a report's contents (the u16 after its ID).
inline std::uint16_t presence_vector_of(const std::vector<std::uint8_t>& contents) {
  return contents.size() < 4 ? 0 : static_cast<std::uint16_t>(contents[2] | (contents[3] << 8));
}

}  // namespace jaus::test
