// Discovery across implementations: our node on subsystem 2 with a static
// peer that behaves like the RA 3.3 node manager on subsystem 1 (ra33_peer.hpp),
// as issue 14 found them. Each learns of the other (the peer only from what
// is addressed to its subsystem or to 255: our communicator's heartbeats),
// our node's subsystem list shows the peer until it falls silent, and
// `jausctl discover` through our node alone lists both subsystems (our node
// relays to the peer). Real sockets: only outcomes, with generous deadlines.
#include <nlohmann/json.hpp>

#include "ocu_fixture.hpp"
#include "ra33_peer.hpp"

namespace jausctl::test {
namespace {

const jaus::Address kOurManager{2, 1, 1, 1};

class CrossSubsystemTest : public OcuTest {
 protected:
  void SetUp() override {
    TargetOptions options;
    options.subsystem = 2;
    options.peers = {peer.endpoint()};
    options.subsystem_timeout = 1500ms;
    start_target(options);
    peer.heartbeat_to({target->endpoint()});
  }

  bool target_knows_the_peer() { return target->node().liveness().find_subsystem(Ra33Peer::kManager).has_value(); }
  // What our node manager's Report Subsystem List says, asked over the wire.
  std::vector<jaus::Address> subsystem_list(ocu::OcuSession& ocu) {
    auto reply = ocu.request(kOurManager, jaus::msg::QuerySubsystemList{}, {jaus::msg::ReportSubsystemList::code}, 2s);
    if (!reply) return {};
    const auto list = jaus::wire::decode_payload<jaus::msg::ReportSubsystemList>(reply->payload);
    return list ? list->subsystems : std::vector<jaus::Address>{};
  }
  static bool lists_subsystem(const std::vector<jaus::Address>& list, std::uint8_t subsystem) {
    return std::any_of(list.begin(), list.end(), [&](const jaus::Address& a) { return a.subsystem == subsystem; });
  }

  Ra33Peer peer{context};
};

TEST_F(CrossSubsystemTest, EachLearnsOfTheOtherAndThePeerGetsNothingAddressedToOurSubsystem) {
  // The peer hears our communicator's heartbeat to every subsystem...
  ASSERT_TRUE(run_until([&] {
    return std::any_of(peer.accepted.begin(), peer.accepted.end(), [](const jaus::Header& h) {
      return h.command_code == jaus::msg::ReportHeartbeatPulse::code && h.source == jaus::Address{2, 1, 35, 1} &&
             h.destination == jaus::Address{255, 255, 1, 1};
    });
  }));
  // ...and we hear the peer.
  ASSERT_TRUE(run_until([&] { return target_knows_the_peer(); }));
  // Several of our own subsystem's heartbeats later (one a second), none went to the peer.
  const auto two_seconds_on = std::chrono::steady_clock::now() + 2s;
  run_until([&] { return std::chrono::steady_clock::now() > two_seconds_on; });
  EXPECT_TRUE(peer.dropped.empty()) << peer.dropped.size() << " messages for subsystem "
                                    << int(peer.dropped.front().destination.subsystem);
}

TEST_F(CrossSubsystemTest, OurSubsystemListShowsThePeerUntilItFallsSilent) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_TRUE(run_until([&] { return target_knows_the_peer(); }));
  const auto list = subsystem_list(*ocu);
  ASSERT_FALSE(list.empty());
  EXPECT_EQ(list.front(), kOurManager);
  // The peer's entry is the node manager we heard from it.
  EXPECT_NE(std::find(list.begin(), list.end(), Ra33Peer::kManager), list.end()) << list.size();

  peer.go_silent();
  EXPECT_TRUE(run_until([&] { return !lists_subsystem(subsystem_list(*ocu), Ra33Peer::kSubsystem); }));
  EXPECT_TRUE(lists_subsystem(subsystem_list(*ocu), 2));
}

TEST_F(CrossSubsystemTest, DiscoverThroughOurNodeListsBothSubsystems) {
  ASSERT_TRUE(run_until([&] { return target_knows_the_peer(); }));
  auto ocu = open_ocu();  // its only peer is our node
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_discover(*ocu, {3s, true}, io()), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  ASSERT_EQ(j["subsystems"].size(), 2u) << out.str();
  const auto& theirs = j["subsystems"][0];
  EXPECT_EQ(theirs["subsystem"], 1);
  EXPECT_EQ(theirs["identification"]["name"], Ra33Peer::kName) << out.str();
  ASSERT_EQ(theirs["nodes"].size(), 1u) << out.str();
  EXPECT_EQ(theirs["nodes"][0]["identification"]["name"], "ra33-node");
  std::vector<std::string> components;
  for (const auto& c : theirs["nodes"][0]["components"]) components.push_back(c["address"]);
  EXPECT_EQ(components, (std::vector<std::string>{"1.1.1.1", "1.1.35.1"})) << out.str();
  EXPECT_EQ(j["subsystems"][1]["subsystem"], 2);
  EXPECT_EQ(j["subsystems"][1]["identification"]["name"], "test-vehicle");
  // Everything reached the peer relayed by our node, none of it addressed to our subsystem.
  EXPECT_TRUE(peer.dropped.empty());
  EXPECT_GT(target->link().counters().relayed, 0u);
}

}  // namespace
}  // namespace jausctl::test
