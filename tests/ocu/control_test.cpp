// `jausctl control`: granted, held past the component's controller timeout
// (its liveness checks are answered), released on exit; a takeover or a
// refusal is reported. Against a node in process under virtual time
// (virtual_fixture.hpp); each test acts on what it has seen (a state shown,
// enough checks answered); the liveness rule itself is timed in
// tests/runtime/control_test.cpp.
#include "jaus/ocu/control_hold.hpp"
#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

const jaus::Address kOcuB{254, 2, 40, 1};

class ControlTest : public VirtualOcuTest {
 protected:
  // The component checks its controller every 0.5 s.
  static constexpr jaus::rt::Duration kControllerTimeout = 1500ms;
  void SetUp() override { start_target(TargetOptions{kControllerTimeout, false}); }

  std::optional<jaus::Address> controller() const {
    const auto& c = target->communicator().control().controller();
    return c ? std::optional(c->address) : std::nullopt;
  }
};

TEST_F(ControlTest, GrantedHeldPastTheControllerTimeoutAndReleased) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kCommunicator, 5);
  const auto requested = control.request(1s);
  ASSERT_EQ(requested.outcome, ocu::ControlHold::Outcome::granted) << ocu::control_request_text(requested, kCommunicator, 5, ocu->self());
  EXPECT_FALSE(requested.error);
  EXPECT_EQ(ocu::control_request_text(requested, kCommunicator, 5, ocu->self()), "control of 1.1.35.1 granted to 254.1.40.1 (authority 5)");
  EXPECT_EQ(controller(), ocu->self());

  // The fourth check comes a third of a timeout past the controller timeout: had
  // the first three gone unanswered, the component would have dropped us instead.
  once([&] { return control.liveness_checks() >= 4; }, [&] { ocu->interrupt(); });
  EXPECT_EQ(control.hold(30s), ocu::ControlHold::End::interrupted);
  EXPECT_EQ(controller(), ocu->self());
  EXPECT_GE(control.liveness_checks(), 4u);

  control.release();
  ASSERT_TRUE(run_until([&] { return !controller(); }));
}

TEST_F(ControlTest, CommandHoldsForAWhileThenReleases) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ocu::ControlOptions options;
  options.target = kCommunicator;
  options.authority = 7;
  // Long enough for the first status report (due at once) on any machine.
  options.hold_for = 2s;
  ASSERT_EQ(ocu::run_control(*ocu, options, io()), kExitOk) << err.str();
  const auto lines = out_lines();
  ASSERT_EQ(lines.size(), 3u) << out.str();
  EXPECT_EQ(lines[0], "control of 1.1.35.1 granted to 254.1.40.1 (authority 7)");
  EXPECT_EQ(lines[1], "1.1.35.1: state Ready");  // from the 5 Hz Report Component Status
  EXPECT_EQ(lines[2].rfind("control of 1.1.35.1 released after ", 0), 0u) << lines[2];
  EXPECT_EQ(err.str(), "");
  EXPECT_FALSE(controller());  // the Release was acknowledged before the command returned
  // The status service connection ended with it.
  ASSERT_TRUE(run_until([&] { return target->communicator().service_connections().active() == 0; }));
}

TEST_F(ControlTest, StateChangesWhileHeldAreShown) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  // Emergency once Ready is shown; the hold ends once the change is shown.
  once([&] { return out_has("1.1.35.1: state Ready\n"); },
       [&] { other->send(kCommunicator, jaus::msg::SetEmergency{{1}}); });
  once([&] { return out_has("Ready -> Emergency"); }, [&] { ocu->interrupt(); });
  ocu::ControlOptions options;
  options.target = kCommunicator;
  options.authority = 7;
  options.hold_for = 30s;  // only if the change never shows
  ASSERT_EQ(ocu::run_control(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_NE(out.str().find("1.1.35.1: state Ready\n1.1.35.1: state Ready -> Emergency\n"), std::string::npos)
      << out.str();
}

TEST_F(ControlTest, ANodeThatFallsSilentEndsTheHold) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kCommunicator, 5, 600ms);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  std::vector<std::string> states;
  // The node goes quiet once its first status report has come.
  once([&] { return !states.empty(); }, [&] { target->go_silent(); });
  EXPECT_EQ(control.hold(30s, [&](const std::string& s) { states.push_back(s); }), ocu::ControlHold::End::silent);
  ASSERT_FALSE(states.empty());
  EXPECT_EQ(states.front(), "Ready");
}

TEST_F(ControlTest, AnInterruptReleases) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  // What SIGINT does: interrupt the session while it holds control (once the state is shown).
  once([&] { return out_has("1.1.35.1: state Ready\n"); }, [&] { ocu->interrupt(); });
  ocu::ControlOptions options;
  options.target = kCommunicator;
  options.authority = 7;
  ASSERT_EQ(ocu::run_control(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_EQ(out_lines().size(), 3u) << out.str();
  ASSERT_TRUE(run_until([&] { return !controller(); }));
}

TEST_F(ControlTest, AHigherAuthorityTakeoverIsReportedAsLost) {
  auto a = open_ocu();
  auto b = open_ocu(kOcuB);
  ASSERT_TRUE(a && b);
  // B asks for control with a higher authority while A holds it (and has shown its state).
  once([&] { return out_has("1.1.35.1: state Ready\n"); },
       [&] { b->send(kCommunicator, jaus::msg::RequestComponentControl{{10}}); });
  ocu::ControlOptions options;
  options.target = kCommunicator;
  options.authority = 5;
  options.hold_for = 30s;  // only if B never takes over
  EXPECT_EQ(ocu::run_control(*a, options, io()), kExitFailure);
  EXPECT_EQ(out.str(), "control of 1.1.35.1 granted to 254.1.40.1 (authority 5)\n1.1.35.1: state Ready\n");
  const std::string e = err.str();
  EXPECT_EQ(e.rfind("jausctl control: control of 1.1.35.1 lost after ", 0), 0u) << e;
  EXPECT_NE(e.find(": Reject Component Control received; taken over by 254.2.40.1 (authority 10)\n"),
            std::string::npos)
      << e;
  EXPECT_EQ(controller(), kOcuB);
}

TEST_F(ControlTest, ALowerAuthorityIsRefusedWithTheResponseCode) {
  auto a = open_ocu();
  auto b = open_ocu(kOcuB);
  ASSERT_TRUE(a && b);
  ocu::ControlHold held(*a, kCommunicator, 10);
  ASSERT_EQ(held.request(1s).outcome, ocu::ControlHold::Outcome::granted);

  ocu::ControlOptions options;
  options.target = kCommunicator;
  options.authority = 5;
  options.hold_for = 1s;
  EXPECT_EQ(ocu::run_control(*b, options, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl control: control of 1.1.35.1 refused: not available (response 2)\n");
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(controller(), a->self());
}

TEST_F(ControlTest, ARejectAsTheAnswerIsARefusal) {
  start_target(TargetOptions{kControllerTimeout, true});
  auto a = open_ocu();
  auto b = open_ocu(kOcuB);
  ASSERT_TRUE(a && b);
  ocu::ControlHold held(*a, kCommunicator, 10);
  ASSERT_EQ(held.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  ocu::ControlHold refused(*b, kCommunicator, 5);
  const auto result = refused.request(1s);
  EXPECT_EQ(result.outcome, ocu::ControlHold::Outcome::rejected);
  EXPECT_EQ(ocu::control_request_text(result, kCommunicator, 5, b->self()), "control of 1.1.35.1 refused (Reject Component Control)");
}

TEST_F(ControlTest, NoReplyTimesOut) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ocu::ControlOptions options;
  options.target = kNobody;
  options.authority = 5;
  options.timeout = 300ms;
  EXPECT_EQ(ocu::run_control(*ocu, options, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl control: no reply from 1.1.42.1 within 0.3 s\n");
}

}  // namespace
}  // namespace jausctl::test
