// The conformance cases against nodes in this process: every case that
// applies passes on each component of a node of ours; each is seen failing,
// with its reason and exchange, against a component broken on purpose (one
// that obeys anyone, one that never confirms a service connection, one that
// echoes the presence vector it is asked for), and against an address where
// nothing answers. The cases run as jaus-conform runs them (runner.hpp), on
// a memory network under virtual time.
#include <gtest/gtest.h>

#include <set>

#include "broken_components.hpp"
#include "case_results.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "virtual_target.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using jausctl::test::kCommunicator;
using jausctl::test::kNobody;
using jausctl::test::kPoseSensor;
using jausctl::test::kTargetManager;
using test::describe;
using test::result_of;

class Conformance : public ::testing::Test {
 protected:
  void SetUp() override {
    target = std::make_unique<jausctl::test::VirtualTarget>(net.time, net.network, jausctl::test::TargetOptions{});
    broken = std::make_unique<test::BrokenNode>(net.time, net.network);
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  std::vector<CaseResult> run(const Address& address, std::string only = {}) {
    RunOptions options;
    options.only = std::move(only);
    // The silent-requester case runs on three components in
    // multi_requester_cases_test.cpp, not again here.
    options.skip = "control.silent_requester";
    return net.run_on(*session, address, options);
  }

  test::VirtualNetwork net;
  std::unique_ptr<jausctl::test::VirtualTarget> target;
  std::unique_ptr<test::BrokenNode> broken;
  std::unique_ptr<ocu::OcuSession> session;
};

// One component per test.
class OurNodeConforms : public Conformance, public ::testing::WithParamInterface<Address> {};

TEST_P(OurNodeConforms, EveryApplicableCasePasses) {
  const Address component = GetParam();
  const auto results = run(component);
  ASSERT_EQ(results.size(), all_cases().size() - 1);  // all but the silent-requester case
  for (const auto& r : results) EXPECT_NE(r.outcome.verdict, Verdict::fail) << describe(results);
  // The pose sensor provides Report Global Pose: its presence vector was checked.
  if (component == kPoseSensor) {
    EXPECT_EQ(result_of(results, "sc.reports")->outcome.verdict, Verdict::pass) << describe(results);
    EXPECT_NE(result_of(results, "sc.reports")->outcome.detail.find("presence 0x"), std::string::npos);
  }
  // The cases leave nobody in control.
  EXPECT_FALSE(target->communicator().control().controller().has_value());
}

INSTANTIATE_TEST_SUITE_P(Components, OurNodeConforms, ::testing::Values(kTargetManager, kCommunicator, kPoseSensor),
                         [](const ::testing::TestParamInfo<Address>& p) {
                           return "component_" + std::to_string(p.param.component);
                         });

TEST_F(Conformance, AComponentThatObeysAnyoneFailsTheControllerCase) {
  const auto results = run(test::kObeysAnyone, "core.refused_without_control");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("from a non-controller moved it"), std::string::npos)
      << results[0].outcome.detail;
  // The report shows what was sent and what came back.
  RunReport report{"in process", Profile::ra, results};
  const std::string markdown = markdown_report(report);
  EXPECT_NE(markdown.find("## Failures"), std::string::npos);
  EXPECT_NE(markdown.find("-> 0x0005 Reset to " + test::kObeysAnyone.to_string()), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("<- 0x4002 Report Component Status from"), std::string::npos) << markdown;
}

// The openjaus profile accepts what the RA 3.3 implementation is documented
// to do (anyone may Reset it): the case is skipped, saying why, and nothing
// is sent; everything else is judged as the RA says.
TEST_F(Conformance, TheOpenjausProfileSkipsWhatThatImplementationIsDocumentedToDoOtherwise) {
  auto component = learn_component(*session, test::kObeysAnyone, nullptr, 1s);
  ASSERT_TRUE(component) << component.error().message();
  RunOptions options;
  options.profile = Profile::openjaus;
  options.only = "core.";
  const auto results = run_cases(*session, *component, all_cases(), net.on_this_network(options));
  ASSERT_EQ(results.size(), core_cases().size());
  for (const auto& r : results) {
    if (r.test_case->id == std::string_view("core.refused_without_control")) {
      EXPECT_EQ(r.outcome.verdict, Verdict::skip);
      EXPECT_NE(r.outcome.detail.find("profile openjaus"), std::string::npos) << r.outcome.detail;
      EXPECT_TRUE(r.exchange.empty());
    } else {
      EXPECT_EQ(r.outcome.verdict, Verdict::pass) << describe(results);
    }
  }
}

TEST_F(Conformance, AComponentThatNeverConfirmsFailsTheServiceConnectionCases) {
  const auto results = run(test::kNeverConfirms, "sc.");
  ASSERT_EQ(results.size(), service_connection_cases().size());
  for (const auto& r : results) {
    EXPECT_EQ(r.outcome.verdict, Verdict::fail) << describe(results);
    EXPECT_NE(r.outcome.detail.find("no reply from " + test::kNeverConfirms.to_string()), std::string::npos)
        << r.outcome.detail;
  }
}

TEST_F(Conformance, ASensorThatEchoesThePresenceVectorFailsThePresenceCase) {
  const auto results = run(test::kEchoesPresence, "sc.reports");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("presence vector 0x"), std::string::npos) << results[0].outcome.detail;
}

TEST_F(Conformance, AComponentSilentInStandbyFailsTheQueriesInEveryStateCase) {
  const auto results = run(test::kSilentInStandby, "core.queries_in_every_state");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("in Standby, Component Authority: no reply from"), std::string::npos)
      << results[0].outcome.detail;
  // Left as found: Ready, nobody in control.
  const auto status = run(test::kSilentInStandby, "core.status");
  ASSERT_EQ(status.size(), 1u);
  EXPECT_NE(status[0].outcome.detail.find("Ready"), std::string::npos) << status[0].outcome.detail;
}

// A provider that gives every connection instance 0 fails the limit case
// at its second connection; one that takes Activate from an inform
// connection's creator fails the Activate case. Our pose sensor refuses
// with 4 past its limit.
TEST_F(Conformance, TheConnectionLimitAndActivateCasesCatchWhatTheyLookFor) {
  auto results = run(test::kEchoesPresence, "sc.too_many");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("instance 0 given to presence 0x0 and to 0x1"), std::string::npos)
      << results[0].outcome.detail;

  results = run(test::kActivatesInform, "sc.activate_by_inform_requester");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("reports in the half second after Activate from the inform requester"),
            std::string::npos)
      << results[0].outcome.detail;

  results = run(kPoseSensor, "sc.too_many");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::pass) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find("64 connections of 0x4402"), std::string::npos) << results[0].outcome.detail;
}

TEST_F(Conformance, CasesThatDoNotApplyAreSkippedWithWhy) {
  // The communicator provides Report Component Status only; a component
  // whose services are unknown gets no service connection case.
  ComponentUnderTest unknown;
  unknown.address = kCommunicator;
  RunOptions options;
  options.only = "sc.";
  const auto results = run_cases(*session, unknown, all_cases(), net.on_this_network(options));
  ASSERT_EQ(results.size(), service_connection_cases().size());
  for (const auto& r : results) {
    EXPECT_EQ(r.outcome.verdict, Verdict::skip);
    EXPECT_EQ(r.outcome.detail, "does not apply: its services are unknown (no Report Services)");
  }
}

TEST_F(Conformance, EveryCaseFailsWithTheReasonWhenNothingAnswers) {
  EXPECT_FALSE(learn_component(*session, kNobody, nullptr, 200ms).has_value());
  ComponentUnderTest nobody;
  nobody.address = kNobody;
  RunOptions options;
  options.reply_timeout = 200ms;
  options.only = "core.";
  const auto results = run_cases(*session, nobody, all_cases(), net.on_this_network(options));
  ASSERT_EQ(results.size(), core_cases().size());
  for (const auto& r : results) {
    EXPECT_EQ(r.outcome.verdict, Verdict::fail) << describe(results);
    EXPECT_NE(r.outcome.detail.find("no reply from " + kNobody.to_string() + " within 0.2 s"), std::string::npos)
        << r.test_case->id << ": " << r.outcome.detail;
  }
}

TEST(ConformanceCases, IdsAreUniqueAndEachCaseSaysWhatItChecksAndWhere) {
  std::set<std::string_view> ids;
  for (const auto* c : all_cases()) {
    EXPECT_TRUE(ids.insert(c->id).second) << c->id;
    EXPECT_FALSE(c->title.empty()) << c->id;
    EXPECT_FALSE(c->reference.empty()) << c->id;
    EXPECT_TRUE(c->run) << c->id;
  }
}

}  // namespace
}  // namespace jaus::conform
