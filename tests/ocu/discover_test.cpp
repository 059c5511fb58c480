// `jausctl discover` against a live node: subsystem, node and components with
// identification and services, in JSON and as a table (in process under
// virtual time, virtual_fixture.hpp); every node given with --to, and nobody
// there, on loopback sockets (ocu_fixture.hpp).
#include <nlohmann/json.hpp>

#include "ocu_fixture.hpp"
#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

const nlohmann::json* find_component(const nlohmann::json& node, const std::string& address) {
  for (const auto& c : node["components"])
    if (c["address"] == address) return &c;
  return nullptr;
}

bool has_code(const nlohmann::json& codes, const std::string& code) {
  for (const auto& c : codes)
    if (c["code"] == code) return true;
  return false;
}

TEST_F(VirtualOcuTest, DiscoverFindsTheSubsystemNodeAndComponentsWithIdentificationAndServices) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_discover(*ocu, {1s, true}, io()), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  ASSERT_EQ(j["subsystems"].size(), 1u) << out.str();  // the OCU's own subsystem is not listed
  const auto& subsystem = j["subsystems"][0];
  EXPECT_EQ(subsystem["subsystem"], 1);
  EXPECT_EQ(subsystem["identification"]["name"], "test-vehicle");
  EXPECT_EQ(subsystem["identification"]["type"], 10001);
  EXPECT_EQ(subsystem["identification"]["class"], "vehicle");
  ASSERT_EQ(subsystem["nodes"].size(), 1u);
  const auto& node = subsystem["nodes"][0];
  EXPECT_EQ(node["node"], 1);
  EXPECT_EQ(node["identification"]["name"], "test-node");
  EXPECT_EQ(node["identification"]["type"], 40001);
  ASSERT_EQ(node["components"].size(), 3u);

  const auto* manager = find_component(node, "1.1.1.1");
  ASSERT_TRUE(manager);
  EXPECT_EQ((*manager)["kind"], "node manager");
  EXPECT_EQ((*manager)["identification"]["name"], "node manager");
  EXPECT_TRUE(has_code((*manager)["inputs"], "0x2B00"));  // Query Identification

  const auto* communicator = find_component(node, "1.1.35.1");
  ASSERT_TRUE(communicator);
  EXPECT_EQ((*communicator)["kind"], "communicator");
  EXPECT_EQ((*communicator)["identification"]["name"], "communicator");  // every component answers type 4
  EXPECT_TRUE(has_code((*communicator)["inputs"], "0x0200"));  // Set Data Link Status
  EXPECT_TRUE(has_code((*communicator)["inputs"], "0x000D"));  // Request Component Control

  const auto* pose = find_component(node, "1.1.38.1");
  ASSERT_TRUE(pose);
  const nlohmann::json* global_pose = nullptr;
  for (const auto& output : (*pose)["outputs"])
    if (output["code"] == "0x4402") global_pose = &output;
  ASSERT_TRUE(global_pose) << (*pose)["outputs"].dump();
  EXPECT_EQ((*global_pose)["name"], "Report Global Pose");
  EXPECT_EQ((*global_pose)["presence_vector"], PoseSensor::kAvailable);
}

TEST_F(VirtualOcuTest, DiscoverPrintsATable) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_discover(*ocu, {1s, false}, io()), kExitOk) << err.str();
  const std::string table = out.str();
  EXPECT_NE(table.find("subsystem (vehicle)"), std::string::npos) << table;
  EXPECT_NE(table.find("test-vehicle"), std::string::npos) << table;
  EXPECT_NE(table.find("1.1.35.1"), std::string::npos) << table;
  EXPECT_NE(table.find("communicator"), std::string::npos) << table;
  EXPECT_NE(table.find("provides  0x4002 0x4402\n"), std::string::npos) << table;
}

TEST_F(OcuTest, DiscoverAsksEveryNodeGivenWithTo) {
  TargetOptions second_options;
  second_options.subsystem = 2;
  TargetNode second(context, second_options);
  ocu::SessionOptions options;
  options.to = {target->endpoint(), second.endpoint()};
  options.bind = jaus::transport::Ipv4Endpoint{kLoopback, 0};
  auto ocu = ocu::OcuSession::open(options, &context);
  ASSERT_TRUE(ocu) << ocu.error().message();
  ASSERT_EQ(ocu::run_discover(**ocu, {1s, true}, io()), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  ASSERT_EQ(j["subsystems"].size(), 2u) << out.str();
  EXPECT_EQ(j["subsystems"][1]["subsystem"], 2);
  EXPECT_EQ(j["subsystems"][1]["nodes"][0]["components"].size(), 3u);
}

TEST_F(OcuTest, DiscoverWithNobodyThereSaysSo) {
  const auto port = target->endpoint().port;
  target.reset();
  ocu::SessionOptions options;
  options.to = {jaus::transport::Ipv4Endpoint{kLoopback, port}};
  options.bind = jaus::transport::Ipv4Endpoint{kLoopback, 0};
  auto ocu = ocu::OcuSession::open(options, &context);
  ASSERT_TRUE(ocu) << ocu.error().message();
  EXPECT_EQ(ocu::run_discover(**ocu, {300ms, false}, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl discover: no JAUS node heard within 0.3 s (asked 127.0.0.1:" + std::to_string(port) + ")\n");
  EXPECT_EQ(out.str(), "");
}

}  // namespace
}  // namespace jausctl::test
