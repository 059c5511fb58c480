// The cases that need a second requester (the runner's second OCU,
// 254.2.40.1) or a silent one: control taken over, refused and released
// between two requesters, an emergency with two holders, and a requester
// that falls silent. Each passes on our node and leaves it as found; each
// fails, with its reason, against a component broken the way it looks for
// (broken_components.hpp). On a memory network under virtual time: the
// silent-requester runs' several seconds (controller timeout 3 s, node
// timeout 5 s, at most 10 s when broken) take no real time.
#include <gtest/gtest.h>

#include <tuple>

#include "broken_components.hpp"
#include "case_results.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "virtual_target.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using jausctl::test::kCommunicator;
using jausctl::test::kPoseSensor;
using jausctl::test::kTargetManager;

// The verdicts, then the Markdown report's failures with their exchanges.
std::string describe(const std::vector<CaseResult>& results) {
  return test::describe(results) + markdown_report(RunReport{"in process", Profile::ra, results});
}

class MultiRequester : public ::testing::Test {
 protected:
  void SetUp() override {
    target = std::make_unique<jausctl::test::VirtualTarget>(net.time, net.network, jausctl::test::TargetOptions{});
    broken = std::make_unique<test::BrokenNode>(net.time, net.network);
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  // Runs the one case `id` against `address`.
  CaseResult run_one(const Address& address, std::string_view id, Profile profile = Profile::ra) {
    RunOptions options;
    options.profile = profile;
    options.only = std::string(id);
    auto results = net.run_on(*session, address, options);
    EXPECT_EQ(results.size(), 1u) << describe(results);
    if (results.empty()) return {};
    EXPECT_EQ(results[0].test_case->id, id);
    return results[0];
  }

  void expect_fails_with(const Address& address, std::string_view id, std::string_view reason) {
    const CaseResult result = run_one(address, id);
    EXPECT_EQ(result.outcome.verdict, Verdict::fail) << describe({result});
    EXPECT_NE(result.outcome.detail.find(reason), std::string::npos) << result.outcome.detail;
  }

  test::VirtualNetwork net;
  std::unique_ptr<jausctl::test::VirtualTarget> target;
  std::unique_ptr<test::BrokenNode> broken;
  std::unique_ptr<ocu::OcuSession> session;
};

constexpr std::string_view kNewCases[] = {
    "core.emergency_two_holders",         "control.other_requester_refused", "control.higher_authority_takes_over",
    "control.release_by_other_requester", "control.silent_requester",        "control.controller_lowers_authority",
};

// One (component, case) per test.
class OurNodePassesMultiRequesterCases : public MultiRequester,
                                         public ::testing::WithParamInterface<std::tuple<Address, std::string_view>> {};

TEST_P(OurNodePassesMultiRequesterCases, AndIsLeftAsFound) {
  const auto [address, id] = GetParam();
  const CaseResult result = run_one(address, id);
  EXPECT_EQ(result.outcome.verdict, Verdict::pass) << describe({result});
  // The second OCU took part (its messages are in the exchange).
  bool second_sent = false;
  for (const auto& e : result.exchange) second_sent |= e.sent && e.second;
  EXPECT_TRUE(second_sent) << describe({result});
  // Left as found: nobody in control, no emergency, no service connection.
  session->run_for(200ms);  // the last Release or Terminate on its way
  EXPECT_FALSE(target->communicator().control().controller().has_value());
  EXPECT_EQ(target->communicator().state(), rt::PrimaryStatus::ready);
  EXPECT_FALSE(target->pose_sensor().control().controller().has_value());
  EXPECT_EQ(target->pose_sensor().state(), rt::PrimaryStatus::ready);
  EXPECT_EQ(target->pose_sensor().service_connections().active(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Cases, OurNodePassesMultiRequesterCases,
                         ::testing::Combine(::testing::Values(kTargetManager, kCommunicator, kPoseSensor),
                                            ::testing::ValuesIn(kNewCases)),
                         [](const auto& p) {
                           std::string id(std::get<1>(p.param));
                           for (auto& ch : id)
                             if (ch == '.') ch = '_';
                           return "component_" + std::to_string(std::get<0>(p.param).component) + "_" + id;
                         });

TEST_F(MultiRequester, TheSilentRequesterCaseSeesControlDroppedAndReportsStop) {
  const CaseResult result = run_one(kPoseSensor, "control.silent_requester");
  ASSERT_EQ(result.outcome.verdict, Verdict::pass) << describe({result});
  EXPECT_NE(result.outcome.detail.find("control dropped after"), std::string::npos) << result.outcome.detail;
  EXPECT_NE(result.outcome.detail.find("reports stopped after"), std::string::npos) << result.outcome.detail;
  // What reached the silent OCU's port after its link closed was heard.
  bool heard_on_sc = false;
  for (const auto& e : result.exchange) heard_on_sc |= e.second && !e.sent && e.header.service_connection;
  EXPECT_TRUE(heard_on_sc) << describe({result});
}

TEST_F(MultiRequester, AComponentThatLetsALowerAuthorityTakeOverFails) {
  expect_fails_with(test::kAnyoneTakesOver, "control.other_requester_refused", "took control from its controller");
}

TEST_F(MultiRequester, AComponentThatIsNeverTakenOverFails) {
  expect_fails_with(test::kNeverTakenOver, "control.higher_authority_takes_over",
                    "the highest authority must be accepted");
}

TEST_F(MultiRequester, AComponentThatAnyoneReleasesFails) {
  expect_fails_with(test::kAnyoneReleases, "control.release_by_other_requester",
                    "a Release from another requester moved its controller");
}

TEST_F(MultiRequester, AComponentThatLeavesEmergencyOnTheFirstClearFails) {
  const CaseResult result = run_one(test::kFirstClearEnds, "core.emergency_two_holders");
  EXPECT_EQ(result.outcome.verdict, Verdict::fail) << describe({result});
  EXPECT_NE(result.outcome.detail.find("the first holder's Clear Emergency left Emergency"), std::string::npos)
      << result.outcome.detail;
  // The report says which messages the second OCU sent.
  RunReport report{"in process", Profile::ra, {result}};
  const std::string markdown = markdown_report(report);
  EXPECT_NE(markdown.find("0x0006 Set Emergency to " + test::kFirstClearEnds.to_string() + " by the second OCU"),
            std::string::npos)
      << markdown;
}

TEST_F(MultiRequester, AComponentThatKeepsASilentControllerFails) {
  expect_fails_with(test::kKeepsSilentController, "control.silent_requester", "kept control for 10 s");
  // The fresh requester at the silent one's address released it.
  session->run_for(200ms);
  session->send(test::kKeepsSilentController, msg::QueryComponentControl{});
  auto reply = session->await_reply(test::kKeepsSilentController, {msg::ReportComponentControl::code}, 1s);
  ASSERT_TRUE(reply) << reply.error().message();
  msg::ReportComponentControl control{};
  ASSERT_TRUE(wire::decode_payload_into(reply->payload, control, wire::Dialect::ra, kHeaderSize));
  EXPECT_FALSE(control.controller.is_valid()) << control.controller.to_string();
}

TEST_F(MultiRequester, AServiceConnectionThatOutlivesItsSilentRequesterFails) {
  // Its hand-made service connection has no liveness; its control is the runtime's.
  expect_fails_with(test::kEchoesPresence, "control.silent_requester",
                    "reports on a silent requester's service connection still came");
}

// Listed with these in issue 14, needing no second requester: our pose
// sensor's Report Global Pose stops on Suspend; a hand-made service
// connection that ignores Suspend is caught.
TEST_F(MultiRequester, SuspendStopsReportsOnOurNodeAndACaseCatchesOneThatKeepsSending) {
  const CaseResult ours = run_one(kPoseSensor, "sc.suspend");
  EXPECT_EQ(ours.outcome.verdict, Verdict::pass) << describe({ours});
  session->run_for(200ms);  // the Terminate on its way
  EXPECT_EQ(target->pose_sensor().service_connections().active(), 0u);
  expect_fails_with(test::kEchoesPresence, "sc.suspend", "reports in the half second after Suspend");
}

// The RA 3.3 implementation never compares authorities and has no control
// timeout (docs/wire-format.md, "Interoperability"): under openjaus those checks are skipped, saying why.
TEST_F(MultiRequester, TheOpenjausProfileSkipsTheAuthorityAndTimeoutChecks) {
  const CaseResult refused = run_one(test::kAnyoneTakesOver, "control.other_requester_refused", Profile::openjaus);
  EXPECT_EQ(refused.outcome.verdict, Verdict::skip);
  EXPECT_NE(refused.outcome.detail.find("profile openjaus"), std::string::npos) << refused.outcome.detail;
  EXPECT_TRUE(refused.exchange.empty());
  // Its control is left alone (released at once); its service connection
  // (Report Component Status, which every component provides) is still judged.
  const CaseResult silent = run_one(test::kKeepsSilentController, "control.silent_requester", Profile::openjaus);
  EXPECT_EQ(silent.outcome.verdict, Verdict::pass) << describe({silent});
  EXPECT_NE(silent.outcome.detail.find("control not checked (profile openjaus"), std::string::npos)
      << silent.outcome.detail;
}

}  // namespace
}  // namespace jaus::conform
