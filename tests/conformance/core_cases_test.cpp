// The core conformance cases against a node of ours (they must pass on every
// component it hosts) and against an address where nothing answers (every
// case fails, saying why).
#include <gtest/gtest.h>

#include <set>

#include "jaus/conform/conformance_case.hpp"
#include "target_node.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using jausctl::test::kCommunicator;
using jausctl::test::kLoopback;
using jausctl::test::kNobody;
using jausctl::test::kPoseSensor;
using jausctl::test::kTargetManager;

class CoreCases : public ::testing::Test {
 protected:
  void SetUp() override {
    target = std::make_unique<jausctl::test::TargetNode>(io);
    ocu::SessionOptions options;
    options.to = {target->endpoint()};
    options.bind = transport::Ipv4Endpoint{kLoopback, 0};
    auto opened = ocu::OcuSession::open(options, &io);
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  std::string describe(const std::vector<CaseResult>& results) {
    std::string out;
    for (const auto& r : results)
      out += std::string(r.test_case->id) + ": " + std::string(to_string(r.outcome.verdict)) + " (" + r.outcome.detail + ")\n";
    return out;
  }

  boost::asio::io_context io;
  std::unique_ptr<jausctl::test::TargetNode> target;
  std::unique_ptr<ocu::OcuSession> session;
};

TEST_F(CoreCases, EveryComponentOfOurNodePassesThem) {
  ASSERT_GE(core_cases().size(), 5u);
  for (const Address& component : {kTargetManager, kCommunicator, kPoseSensor}) {
    const auto results = run_cases(*session, component, core_cases());
    ASSERT_EQ(results.size(), core_cases().size());
    for (const auto& r : results)
      EXPECT_EQ(r.outcome.verdict, Verdict::pass) << component.to_string() << "\n" << describe(results);
  }
  // The control case leaves nobody in control.
  EXPECT_FALSE(target->communicator().control().controller().has_value());
}

TEST_F(CoreCases, ACaseFailsWithTheReasonWhenNothingAnswers) {
  const auto results = run_cases(*session, kNobody, core_cases(), 200ms);
  ASSERT_EQ(results.size(), core_cases().size());
  for (const auto& r : results) {
    EXPECT_EQ(r.outcome.verdict, Verdict::fail) << describe(results);
    EXPECT_EQ(r.outcome.detail, "no reply from " + kNobody.to_string() + " within 0.2 s") << r.test_case->id;
  }
}

TEST_F(CoreCases, CaseIdsAreUnique) {
  std::set<std::string_view> ids;
  for (const auto& c : core_cases()) EXPECT_TRUE(ids.insert(c.id).second) << c.id;
}

}  // namespace
}  // namespace jaus::conform
