// The discovery cases against nodes in this process, on a memory network
// under virtual time: our node manager on subsystem 2, which hears a peer
// that behaves like the RA 3.3 node manager (subsystem 1,
// tests/support/ra33_peer.hpp) and lists it, passes them all (the peer's
// entry answering); each is seen failing, with its reason, against a node
// manager broken on purpose (broken_discovery_components.hpp). The Event of
// a configuration change is checked where the test changes the node while
// the case listens. Reaching the peer through our node's relay is UDP's
// (tests/ocu/cross_subsystem_test.cpp, on sockets).
#include <gtest/gtest.h>

#include <memory>

#include "broken_discovery_components.hpp"
#include "case_results.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "ra33_peer.hpp"
#include "virtual_target.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using jausctl::test::Ra33MemoryPeer;
using test::describe;
using test::NodeManagerFlaw;

const Address kOurManager{2, 1, 1, 1};
const Address kOurCommunicator{2, 1, 35, 1};

// Adds a component to a node every 200 ms while it lives: a node whose
// configuration changes while a case listens for Events.
class ConfigurationChanger {
 public:
  ConfigurationChanger(rt::VirtualTime& time, node::Node& node) : time_(time), node_(node) { add_later(); }
  int added() const { return added_; }

 private:
  void add_later() {
    time_.call_at(time_.now() + 200ms, [this, alive = std::weak_ptr<char>(alive_)] {
      if (alive.expired()) return;
      rt::ComponentConfig config;
      config.name = "added " + std::to_string(added_);
      config.address =
          Address{node_.config().subsystem, node_.config().node, static_cast<std::uint8_t>(100 + added_++), 1};
      node_.add_as(std::make_unique<test::Worker>(std::move(config), node_.environment()));
      add_later();
    });
  }

  rt::VirtualTime& time_;
  node::Node& node_;
  int added_ = 0;
  std::shared_ptr<char> alive_ = std::make_shared<char>(0);  // the additions stop when it goes
};

class DiscoveryCases : public ::testing::Test {
 protected:
  void SetUp() override {
    jausctl::test::TargetOptions options;
    options.subsystem = 2;
    target = std::make_unique<jausctl::test::VirtualTarget>(net.time, net.network, options);
    peer.start_heartbeats();
    for (const auto flaw : kFlaws) broken.push_back(std::make_unique<test::BrokenDiscoveryNode>(net.time, net.network, flaw));
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
    ASSERT_TRUE(session->run_until(
        [&] { return target->node().liveness().find_subsystem(Ra33MemoryPeer::kManager).has_value(); }, 10s))
        << "our node never heard the RA 3.3 peer";
  }

  std::vector<CaseResult> run(const Address& address, std::string only, Profile profile = Profile::ra) {
    RunOptions options;
    options.only = std::move(only);
    options.profile = profile;
    return net.run_on(*session, address, options);
  }

  // The one case `id` against the node manager broken with `flaw`: it fails.
  CaseResult broken_result(NodeManagerFlaw flaw, std::string_view id) {
    const auto results = run(test::broken_manager(flaw), std::string(id));
    EXPECT_EQ(results.size(), 1u) << describe(results);
    if (results.empty()) return {};
    EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
    return results[0];
  }
  test::BrokenDiscoveryNode& broken_node(NodeManagerFlaw flaw) { return *broken[static_cast<std::size_t>(flaw)]; }

  static constexpr NodeManagerFlaw kFlaws[] = {NodeManagerFlaw::identifies_every_level_as_component,
                                               NodeManagerFlaw::omits_answering_component,
                                               NodeManagerFlaw::omits_service_entry,
                                               NodeManagerFlaw::lists_silent_subsystem,
                                               NodeManagerFlaw::never_confirms_event,
                                               NodeManagerFlaw::events_after_cancel};

  test::VirtualNetwork net;
  Ra33MemoryPeer peer{net.time, net.network};
  std::unique_ptr<jausctl::test::VirtualTarget> target;
  std::vector<std::unique_ptr<test::BrokenDiscoveryNode>> broken;
  std::unique_ptr<ocu::OcuSession> session;
};

TEST_F(DiscoveryCases, OurNodeManagerPassesWithThePeersSubsystemInItsList) {
  for (const Profile profile : {Profile::ra, Profile::openjaus}) {
    const auto results = run(kOurManager, "discovery.", profile);
    ASSERT_EQ(results.size(), discovery_cases().size());
    for (const auto& r : results) EXPECT_EQ(r.outcome.verdict, Verdict::pass) << describe(results);
    // The peer's subsystem was listed, and its node manager answered.
    const auto& listed = results[3];
    ASSERT_EQ(listed.test_case->id, std::string_view("discovery.subsystem_list"));
    EXPECT_NE(listed.outcome.detail.find("1.1.1.1 'ra33-vehicle'"), std::string::npos) << listed.outcome.detail;
    // Nothing changed our node while the event case listened: it says what it did not check.
    EXPECT_NE(results[4].outcome.detail.find("the Event itself not checked"), std::string::npos)
        << results[4].outcome.detail;
  }
  // None of what reached the peer was addressed to another subsystem.
  EXPECT_FALSE(peer.accepted.empty());
  EXPECT_TRUE(peer.dropped.empty());
}

TEST_F(DiscoveryCases, TheEventIsCheckedWhenOurNodeChangesWhileTheCaseListens) {
  ConfigurationChanger changer(net.time, target->node());
  const auto results = run(kOurManager, "discovery.change_event");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::pass) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("Events on change"), std::string::npos) << results[0].outcome.detail;
  EXPECT_GT(changer.added(), 0);
}

TEST_F(DiscoveryCases, OnlyNodeManagersAreAsked) {
  const auto results = run(kOurCommunicator, "discovery.");
  ASSERT_EQ(results.size(), discovery_cases().size());
  for (const auto& r : results) {
    EXPECT_EQ(r.outcome.verdict, Verdict::skip) << describe(results);
    EXPECT_NE(r.outcome.detail.find("not a node manager (component ID 1)"), std::string::npos) << r.outcome.detail;
    EXPECT_TRUE(r.exchange.empty());
  }
}

TEST_F(DiscoveryCases, IdentificationOfTheWrongLevelFails) {
  const auto r = broken_result(NodeManagerFlaw::identifies_every_level_as_component, "discovery.identification");
  EXPECT_NE(r.outcome.detail.find("Query Identification (subsystem, 2) answered with query type 4"), std::string::npos)
      << r.outcome.detail;
}

TEST_F(DiscoveryCases, AConfigurationThatLeavesOutAComponentThatAnswersFails) {
  const auto r = broken_result(NodeManagerFlaw::omits_answering_component, "discovery.configuration");
  const std::string worker =
      Address{test::subsystem_of(NodeManagerFlaw::omits_answering_component), 1, 50, 1}.to_string();
  EXPECT_NE(r.outcome.detail.find(worker + " answers Query Component Status but Report Configuration (node) does not "
                                           "list it"),
            std::string::npos)
      << r.outcome.detail;
}

TEST_F(DiscoveryCases, ServicesWithoutAConfiguredComponentsEntryFail) {
  const auto r = broken_result(NodeManagerFlaw::omits_service_entry, "discovery.services");
  EXPECT_NE(r.outcome.detail.find("has no entry of type 50"), std::string::npos) << r.outcome.detail;
}

TEST_F(DiscoveryCases, ASubsystemListNamingASubsystemThatNeverAnswersFails) {
  const auto r = broken_result(NodeManagerFlaw::lists_silent_subsystem, "discovery.subsystem_list");
  EXPECT_NE(r.outcome.detail.find("9.1.1.1 does not answer Query Identification (subsystem): no reply from 9.1.1.1"),
            std::string::npos)
      << r.outcome.detail;
}

TEST_F(DiscoveryCases, ACreateEventNeverConfirmedFails) {
  const auto r = broken_result(NodeManagerFlaw::never_confirms_event, "discovery.change_event");
  EXPECT_NE(r.outcome.detail.find("Create Event (Report Configuration, every change): no reply from"),
            std::string::npos)
      << r.outcome.detail;
}

TEST_F(DiscoveryCases, EventsThatGoOnAfterCancelFail) {
  ConfigurationChanger changer(net.time, broken_node(NodeManagerFlaw::events_after_cancel).node());
  const auto r = broken_result(NodeManagerFlaw::events_after_cancel, "discovery.change_event");
  EXPECT_NE(r.outcome.detail.find("still sent after Cancel Event was confirmed"), std::string::npos)
      << r.outcome.detail;
}

}  // namespace
}  // namespace jaus::conform
