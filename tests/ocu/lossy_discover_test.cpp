// Discovery over a lossy link: a question or its answer lost is asked again
// (Discovery::unanswered, every 0.5 s of discover's wait), so at 10 % loss
// each way `jausctl discover` still lists every component with its
// identification and services in its default 2 s, at 30 % in 4 s.
#include <nlohmann/json.hpp>

#include "jaus/messages/all.hpp"
#include "jaus/ocu/discovery.hpp"
#include "lossy_fixture.hpp"

namespace jausctl::test {
namespace {

using K = ocu::DiscoveryQuery::Kind;

bool has(const std::vector<ocu::DiscoveryQuery>& qs, const jaus::Address& to, K kind, std::uint8_t field) {
  return std::find(qs.begin(), qs.end(), ocu::DiscoveryQuery{to, kind, field}) != qs.end();
}

template <class M>
void reply(ocu::Discovery& discovery, const jaus::Address& from, const M& message) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  ASSERT_TRUE(size);
  payload.resize(*size);
  jaus::Header h;
  h.command_code = M::code;
  h.source = from;
  h.destination = ocu::kDefaultOcuAddress;
  discovery.received(h, payload, jaus::wire::Dialect::ra);
}

TEST(DiscoveryUnanswered, EveryQuestionIsUnansweredUntilItsReportComes) {
  ocu::Discovery discovery(ocu::kDefaultOcuAddress);
  const jaus::Address manager{3, 2, 1, 1};
  const auto asked = discovery.heard(manager);
  EXPECT_EQ(discovery.unanswered().size(), asked.size());

  reply(discovery, manager, jaus::msg::ReportIdentification{{2, 0, 10001, "rover"}});
  reply(discovery, manager, jaus::msg::ReportIdentification{{3, 0, 40001, "computer"}});
  reply(discovery, manager, jaus::msg::ReportSubsystemList{{{manager}}});
  jaus::msg::ReportConfiguration configuration;
  configuration.nodes.push_back({2, {{1, 1}}});
  reply(discovery, manager, configuration);
  const auto left = discovery.unanswered();
  EXPECT_FALSE(has(left, manager, K::identification, 2));
  EXPECT_FALSE(has(left, manager, K::identification, 3));
  EXPECT_FALSE(has(left, manager, K::configuration, 2));
  EXPECT_FALSE(has(left, manager, K::configuration, 3));
  EXPECT_FALSE(has(left, manager, K::subsystem_list, 0));
  EXPECT_TRUE(has(left, manager, K::identification, 4));  // the node manager as a component
  EXPECT_TRUE(has(left, manager, K::services, 0));

  reply(discovery, manager, jaus::msg::ReportIdentification{{4, 0, 0, "node manager"}});
  reply(discovery, manager, jaus::msg::ReportServices{});
  EXPECT_TRUE(discovery.unanswered().empty());
}

class LossyDiscoverTest : public LossyOcuTest {
 protected:
  // discover --wait W --json at `loss` each way: every component of the
  // target has its identification and its services.
  void finds_everything(double loss, std::uint32_t seed, jaus::rt::Duration wait) {
    auto ocu = open_lossy_ocu();
    ASSERT_TRUE(ocu);
    lose(loss, loss, seed);
    ASSERT_EQ(ocu::run_discover(*ocu, {wait, true}, io()), kExitOk) << err.str();
    const auto j = nlohmann::json::parse(out.str());
    ASSERT_EQ(j["subsystems"].size(), 1u) << out.str();
    const auto& subsystem = j["subsystems"][0];
    EXPECT_EQ(subsystem["identification"]["name"], "test-vehicle");
    ASSERT_EQ(subsystem["nodes"].size(), 1u);
    const auto& node = subsystem["nodes"][0];
    EXPECT_EQ(node["identification"]["name"], "test-node");
    ASSERT_EQ(node["components"].size(), 3u) << node.dump();
    for (const auto& component : node["components"]) {
      EXPECT_TRUE(component["identification"].is_object()) << component.dump();
      EXPECT_FALSE(component["inputs"].empty()) << component.dump();
    }
    std::printf("discover at %.0f %% loss each way: %llu packets lost, everything found in %.0f s\n", loss * 100,
                static_cast<unsigned long long>(ocu_link->packets_lost()), ms(wait) / 1000);
  }
};

TEST_F(LossyDiscoverTest, AtTenPercentLossEachWayEverythingIsFoundInTheDefaultTwoSeconds) {
  finds_everything(0.10, 10, 2s);
}

// A question is asked every 0.5 s: at 30 % a round trip fails half the time,
// and 8 tries (--wait 4) all fail once in 200.
TEST_F(LossyDiscoverTest, AtThirtyPercentLossEachWayEverythingIsFoundInFourSeconds) {
  finds_everything(0.30, 30, 4s);
}

}  // namespace
}  // namespace jausctl::test
