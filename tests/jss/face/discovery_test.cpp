// Discovery through the face: the node manager is the subsystem's discovery
// service, every component names itself, services are URIs per component.
#include <algorithm>

#include "face_node.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;

std::vector<std::string> uris_of(const msg::ServicesComponent& c) {
  std::vector<std::string> uris;
  for (const auto& s : c.services) uris.push_back(s.uri + " " + std::to_string(s.major_version) + "." +
                                                  std::to_string(s.minor_version));
  return uris;
}

const msg::ServicesComponent* component_in(const std::vector<msg::ServicesNode>& nodes, std::uint8_t id) {
  for (const auto& n : nodes)
    for (const auto& c : n.components)
      if (c.component_id == id) return &c;
  return nullptr;
}

const std::vector<std::string> kNodeManagerServices = {"urn:jaus:jss:core:Transport 1.1", "urn:jaus:jss:core:Events 1.1",
                                                       "urn:jaus:jss:core:Liveness 1.1",
                                                       "urn:jaus:jss:core:Discovery 1.1"};
const std::vector<std::string> kDriverServices = {
    "urn:jaus:jss:core:Transport 1.1",  "urn:jaus:jss:core:Events 1.1",   "urn:jaus:jss:core:AccessControl 1.1",
    "urn:jaus:jss:core:Management 1.1", "urn:jaus:jss:core:Liveness 1.1", "urn:jaus:jss:mobility:PrimitiveDriver 1.0"};

TEST(JssFaceDiscovery, BroadcastQueryIdentificationIsAnsweredByTheNodeManagerForTheSubsystem) {
  jss_face::FaceConfig config;
  config.subsystem_name = "husky";
  FaceNode node(config);
  node.send(kClientA, kEveryone, msg::QueryIdentification{{jaus::msg::identification::kSubsystem}});
  node.run_for(50ms);
  const auto reports = node.take_all<msg::ReportIdentification>(kClientA);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].first, kNodeManager);
  EXPECT_EQ(reports[0].second.query_type, jaus::msg::identification::kSubsystem);
  EXPECT_EQ(reports[0].second.type, msg::identification_type::kVehicle);
  EXPECT_EQ(reports[0].second.identification, "husky");
}

TEST(JssFaceDiscovery, EveryComponentAnswersQueryIdentificationType4WithItsName) {
  FaceNode node;
  node.send(kClientA, kEveryone, msg::QueryIdentification{{jaus::msg::identification::kComponent}});
  node.run_for(50ms);
  const auto reports = node.take_all<msg::ReportIdentification>(kClientA);
  ASSERT_EQ(reports.size(), 3u);
  for (const auto& [from, report] : reports) {
    EXPECT_EQ(report.type, msg::identification_type::kComponent);
    if (from == kDriver) {
      EXPECT_EQ(report.identification, "driver");
    }
  }
  const auto node_report =
      node.ask<msg::ReportIdentification>(kClientA, kNodeManager, msg::QueryIdentification{{jaus::msg::identification::kNode}});
  ASSERT_TRUE(node_report.has_value());
  EXPECT_EQ(node_report->type, msg::identification_type::kNode);
}

TEST(JssFaceDiscovery, QueryServicesWithNoNodesListsEveryComponentsServiceUris) {
  FaceNode node;
  const auto report = node.ask<msg::ReportServices>(kClientA, kNodeManager, msg::QueryServices{});  // count 0 = all
  ASSERT_TRUE(report.has_value());
  ASSERT_EQ(report->nodes.size(), 1u);
  EXPECT_EQ(report->nodes[0].node_id, 1);
  EXPECT_EQ(report->nodes[0].components.size(), 3u);
  const auto* manager = component_in(report->nodes, 1);
  const auto* driver = component_in(report->nodes, 33);
  ASSERT_NE(manager, nullptr);
  ASSERT_NE(driver, nullptr);
  EXPECT_EQ(uris_of(*manager), kNodeManagerServices);
  EXPECT_EQ(uris_of(*driver), kDriverServices);
  EXPECT_EQ(driver->instance_id, 0);

  // One component asked by ID.
  msg::QueryServices one;
  one.nodes.push_back(msg::QueryServicesNode{1, {33}});
  const auto only = node.ask<msg::ReportServices>(kClientA, kNodeManager, one);
  ASSERT_TRUE(only.has_value());
  ASSERT_EQ(only->nodes.size(), 1u);
  ASSERT_EQ(only->nodes[0].components.size(), 1u);
  EXPECT_EQ(only->nodes[0].components[0].component_id, 33);
}

TEST(JssFaceDiscovery, QueryServiceListForEverythingAndWithASearchFilter) {
  FaceNode node;
  msg::QueryServiceList all;
  all.subsystems.push_back({jss::JssId::kAllSubsystems, {{jss::JssId::kAll, {{jss::JssId::kAll, std::nullopt}}}}});
  const auto report = node.ask<msg::ReportServiceList>(kClientA, kNodeManager, all);
  ASSERT_TRUE(report.has_value());
  ASSERT_EQ(report->subsystems.size(), 1u);
  EXPECT_EQ(report->subsystems[0].subsystem_id, 1);
  const auto* driver = component_in(report->subsystems[0].nodes, 33);
  ASSERT_NE(driver, nullptr);
  EXPECT_EQ(uris_of(*driver), kDriverServices);

  msg::QueryServiceList filtered;
  filtered.subsystems.push_back({1, {{1, {{jss::JssId::kAll, std::string("mobility")}}}}});
  const auto mobility = node.ask<msg::ReportServiceList>(kClientA, kNodeManager, filtered);
  ASSERT_TRUE(mobility.has_value());
  ASSERT_EQ(mobility->subsystems.size(), 1u);
  const auto* filtered_driver = component_in(mobility->subsystems[0].nodes, 33);
  ASSERT_NE(filtered_driver, nullptr);
  EXPECT_EQ(uris_of(*filtered_driver), std::vector<std::string>{"urn:jaus:jss:mobility:PrimitiveDriver 1.0"});
}

TEST(JssFaceDiscovery, ConfigurationAndSubsystemListUseJssIds) {
  jss_face::FaceConfig config;
  config.subsystem = 300;  // beyond RA's u8
  config.component_ids = {{33, 200}};
  FaceNode node(config);
  const jss::JssId manager{300, 1, 1};
  const auto configuration =
      node.ask<msg::ReportConfiguration>(kClientA, manager, msg::QueryConfiguration{{jaus::msg::identification::kSubsystem}});
  ASSERT_TRUE(configuration.has_value());
  ASSERT_EQ(configuration->nodes.size(), 1u);
  std::vector<int> ids;
  for (const auto& c : configuration->nodes[0].components) {
    ids.push_back(c.component_id);
    EXPECT_EQ(c.instance_id, 0);
  }
  EXPECT_EQ(ids, (std::vector<int>{1, 42, 200}));
  const auto list = node.ask<msg::ReportSubsystemList>(kClientA, manager, msg::QuerySubsystemList{});
  ASSERT_TRUE(list.has_value());
  EXPECT_EQ(list->subsystems, std::vector<jss::JssId>{manager});
  // The driver answers at its configured JSS ID.
  EXPECT_TRUE(node.ask<msg::ReportHeartbeatPulse>(kClientA, jss::JssId{300, 1, 200}, msg::QueryHeartbeatPulse{}));
  EXPECT_EQ(node.face().jss_id_of(kRaDriver), (jss::JssId{300, 1, 200}));
}

TEST(JssFaceDiscovery, RegisterServicesIsKeptWithoutReply) {
  FaceNode node;
  msg::RegisterServices registration;
  registration.services.push_back({"urn:jaus:jss:core:Transport", 1, 1});
  node.send(kClientA, kNodeManager, registration);
  node.run_for(50ms);
  EXPECT_TRUE(node.received().empty());
  EXPECT_EQ(node.counters().malformed, 0u);
  EXPECT_EQ(node.counters().unsupported, 0u);
}

}  // namespace
}  // namespace jaus::test
