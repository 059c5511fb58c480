// The core, control, service connection and robustness cases that the other
// suites see failing only against a silent address or a component that never
// confirms: here each fails, with its reason, against a component broken the
// one way it looks for (broken_components.hpp; for the robustness cases a
// component that never checks a payload, lenient_peer.hpp), on a memory
// network under virtual time.
#include <gtest/gtest.h>

#include "broken_components.hpp"
#include "case_results.hpp"
#include "jaus/conform/runner.hpp"
#include "lenient_peer.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using test::describe;

struct Flawed {
  const char* name;
  Address address;
  std::string_view case_id;
  std::string_view says;
  // Another OCU controls it when the case runs (the case judges what a
  // non-controller's message does to a controlled component).
  bool controlled_by_another = false;
};

void PrintTo(const Flawed& f, std::ostream* out) { *out << f.name; }

class FlawedComponentsFail : public ::testing::TestWithParam<Flawed> {
 protected:
  void SetUp() override {
    broken = std::make_unique<test::BrokenNode>(net.time, net.network);
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  test::VirtualNetwork net;
  std::unique_ptr<test::BrokenNode> broken;
  std::unique_ptr<ocu::OcuSession> session;
};

TEST_P(FlawedComponentsFail, TheCaseThatLooksForTheFlawFailsSayingWhy) {
  const Flawed& flawed = GetParam();
  std::unique_ptr<ocu::OcuSession> other;
  if (flawed.controlled_by_another) {
    auto opened = net.open_session(Address{254, 7, 40, 1});
    ASSERT_TRUE(opened) << opened.error().message();
    other = std::move(*opened);
    other->send(flawed.address, msg::RequestComponentControl{{255}});
    auto confirm = other->await_reply(flawed.address, {msg::ConfirmComponentControl::code}, 2s);
    ASSERT_TRUE(confirm) << confirm.error().message();
  }
  RunOptions options;
  options.only = std::string(flawed.case_id);
  const auto results = net.run_on(*session, flawed.address, options);
  ASSERT_EQ(results.size(), 1u) << describe(results);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find(flawed.says), std::string::npos) << results[0].outcome.detail;
  EXPECT_FALSE(results[0].exchange.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Flaws, FlawedComponentsFail,
    ::testing::Values(Flawed{"GrantsBelowOwnAuthority", test::kGrantsBelowOwnAuthority,
                             "control.lower_authority_refused", "granted to authority 4 below its own 5"},
                      Flawed{"IgnoresRelease", test::kIgnoresRelease, "control.round_trip",
                             "still reports the runner as controller after Release Component Control"},
                      Flawed{"RefusesRenewal", test::kRefusesRenewal, "control.controller_asks_again",
                             "the controller asked again and got response 2"},
                      Flawed{"KeepsFirstAuthority", test::kKeepsFirstAuthority, "control.controller_lowers_authority",
                             "the controller asked again at authority 1, Report Component Control gives 2"},
                      Flawed{"AnyoneReleases", test::kAnyoneReleases, "control.release_by_non_controller",
                             "a Release from a non-controller moved its controller from 254.7.40.1 to 0.0.0.0", true},
                      Flawed{"SlowReports", test::kSlowReports, "sc.rate", "reports in 1 s at a confirmed 20"},
                      Flawed{"IgnoresTerminate", test::kIgnoresTerminate, "sc.terminate",
                             "reports in the half second after Terminate"},
                      Flawed{"AcceptsAnyConnection", test::kAcceptsAnyConnection, "sc.refusals",
                             "created a service connection for 0x4FFE"},
                      Flawed{"IgnoresStandby", test::kIgnoresStandby, "core.standby_resume",
                             "Standby from its controller left it in Ready"},
                      Flawed{"AnswersAuthorityEmpty", test::kAnswersWrongly, "core.authority",
                             "Report Component Authority does not decode"},
                      Flawed{"NeverAnswersHeartbeat", test::kAnswersWrongly, "core.heartbeat",
                             "no reply from 3.1.84.1"}),
    [](const ::testing::TestParamInfo<Flawed>& p) { return std::string(p.param.name); });

// The robustness cases, against a component that answers an unknown code,
// a Query Identification cut short, and acts on an overlong Set Emergency.
TEST(RobustnessCases, EachFailsAgainstAComponentThatNeverChecksAPayload) {
  test::VirtualNetwork net;
  test::LenientPeer lenient(net.time, net.network);
  auto session = net.open_session();
  ASSERT_TRUE(session) << session.error().message();
  RunOptions run;
  run.only = "robust.";
  const auto results = net.run_on(**session, test::LenientPeer::kAddress, run);
  ASSERT_EQ(results.size(), robustness_cases().size()) << describe(results);
  const std::pair<std::string_view, std::string_view> expected[] = {
      {"robust.unknown_code", "answered an unknown code with 0x4002"},
      {"robust.truncated", "answered a Query Identification without its query type with Report Identification"},
      {"robust.overlong", "acted on a Set Emergency with two bytes too many: Ready -> Emergency"},
  };
  for (const auto& [id, says] : expected) {
    const CaseResult* result = test::result_of(results, id);
    ASSERT_NE(result, nullptr) << id;
    EXPECT_EQ(result->outcome.verdict, Verdict::fail) << describe(results);
    EXPECT_NE(result->outcome.detail.find(says), std::string::npos) << result->outcome.detail;
  }
}

}  // namespace
}  // namespace jaus::conform
