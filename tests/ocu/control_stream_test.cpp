// `jausctl control --send`: the repeated command goes only to a Ready
// component. Emergency or Standby stops it for good (control released, exit
// kExitLeftReady), so that a Clear Emergency or Resume by anyone does not
// restart the motion; a component not Ready at the start gets nothing; with
// --resume-when-ready it pauses and resumes. The driver counts the Set
// Wrench Efforts that reach it; the OCU's own count shows that none went out
// after it learnt the state (one in flight may still arrive, refused).
// Under virtual time (virtual_fixture.hpp); each step acts on what has
// happened (efforts applied, a line printed), never at a fixed time.
#include "jaus/ocu/control_hold.hpp"
#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

const jaus::Address kOcuB{254, 2, 40, 1};
constexpr const char* kEmergencyStop =
    "jausctl control: 1.1.33.1 entered Emergency: stopped sending Set Wrench Effort; not resuming "
    "(see --resume-when-ready)\n";

class ControlStreamTest : public VirtualOcuTest {
 protected:
  void SetUp() override {
    TargetOptions options;
    options.primitive_driver = true;
    start_target(options);
  }

  static ocu::PreparedMessage forward() {
    const auto message = ocu::prepare_message(
        ocu::Json::parse(R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":60}})"),
        jaus::wire::Dialect::ra);
    EXPECT_TRUE(message) << message.error().message();
    return *message;
  }

  ocu::ControlOptions streaming() const {
    ocu::ControlOptions options;
    options.target = kDriver;
    options.authority = 7;
    options.hold_for = 30s;  // only if the test's events never happen
    options.send = forward();
    options.send_rate_hz = 20;
    return options;
  }

  std::uint64_t applied() const { return target->driver().driver_counters().efforts_applied; }
  jaus::msg::PrimaryStatus driver_state() const { return target->driver().state(); }
  bool controlled() const { return target->driver().control().controller().has_value(); }

  // Lets `d` of virtual time pass: long enough for a command that would
  // still come to have come (the tool streams at 20 Hz).
  void run_for(jaus::rt::Duration d) { jaus::testing::run_for(time, d); }
};

TEST_F(ControlStreamTest, NoCommandGoesOutAfterTheOcuLearntOfTheEmergency) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  ocu::ControlHold control(*ocu, kDriver, 7);
  control.send_while_held(forward(), 50ms);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  once([&] { return applied() >= 3; }, [&] { other->send(kDriver, jaus::msg::SetEmergency{{1}}); });
  std::optional<std::uint64_t> sent_when_learnt;
  const auto end = control.hold(30s, [&](const std::string& state) {
    if (state == "Ready -> Emergency") sent_when_learnt = control.sent_while_held();
  });
  EXPECT_EQ(end, ocu::ControlHold::End::not_ready);
  ASSERT_TRUE(sent_when_learnt);
  EXPECT_GE(*sent_when_learnt, 3u);
  EXPECT_EQ(control.sent_while_held(), *sent_when_learnt);
  control.release();
  // Everything sent arrived (loopback), and nothing more.
  ASSERT_TRUE(run_until([&] { return !controlled(); }));
  EXPECT_EQ(target->efforts_arrived(), control.sent_while_held());
}

TEST_F(ControlStreamTest, EmergencyStopsTheStreamAndAClearDoesNotRestartIt) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  once([&] { return applied() >= 3; }, [&] { other->send(kDriver, jaus::msg::SetEmergency{{1}}); });
  EXPECT_EQ(ocu::run_control(*ocu, streaming(), io()), kExitLeftReady) << err.str();
  EXPECT_EQ(err.str(), kEmergencyStop);
  const auto lines = out_lines();
  ASSERT_EQ(lines.size(), 3u) << out.str();
  EXPECT_EQ(lines[0], "control of 1.1.33.1 granted to 254.1.40.1 (authority 7)");
  EXPECT_EQ(lines[1], "1.1.33.1: state Ready");
  EXPECT_EQ(lines[2], "1.1.33.1: state Ready -> Emergency");
  // Released: the Release comes after every command sent.
  ASSERT_TRUE(run_until([&] { return !controlled(); }));
  const auto arrived = target->efforts_arrived();

  other->send(kDriver, jaus::msg::ClearEmergency{{1}});
  ASSERT_TRUE(run_until([&] { return driver_state() == jaus::msg::PrimaryStatus::ready; }));
  run_for(500ms);
  EXPECT_EQ(target->efforts_arrived(), arrived);
}

// Issue 42: another OCU sets and clears the emergency back to back, between
// two status reports, both of which say Ready: the stop shows only as the
// stop counter of the next report. The stream stops for good, and the Clear
// restarts nothing.
TEST_F(ControlStreamTest, AnEmergencySetAndClearedBackToBackStopsTheStreamForGood) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  const auto stops_before = target->driver().counters().stops_entered;
  once([&] { return applied() >= 3; },
       [&] {
         other->send(kDriver, jaus::msg::SetEmergency{{1}});
         other->send(kDriver, jaus::msg::ClearEmergency{{1}});
       });
  EXPECT_EQ(ocu::run_control(*ocu, streaming(), io()), kExitLeftReady) << err.str();
  EXPECT_EQ(target->driver().counters().stops_entered, stops_before + 1);
  EXPECT_EQ(err.str(), "jausctl control: 1.1.33.1 stopped and went back to Ready between two status reports (stop "
                       "counter " + std::to_string(stops_before) + " -> " + std::to_string(stops_before + 1) +
                       "): stopped sending Set Wrench Effort; not resuming (see --resume-when-ready)\n");
  ASSERT_TRUE(run_until([&] { return !controlled(); }));
  EXPECT_EQ(driver_state(), jaus::msg::PrimaryStatus::ready);
  const auto arrived = target->efforts_arrived();
  run_for(500ms);
  EXPECT_EQ(target->efforts_arrived(), arrived);
}

TEST_F(ControlStreamTest, AComponentInEmergencyAtTheStartGetsNothingEvenOnceCleared) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  other->send(kDriver, jaus::msg::SetEmergency{{1}});
  ASSERT_TRUE(run_until([&] { return driver_state() == jaus::msg::PrimaryStatus::emergency; }));

  EXPECT_EQ(ocu::run_control(*ocu, streaming(), io()), kExitLeftReady) << err.str();
  EXPECT_EQ(err.str(),
            "jausctl control: 1.1.33.1 is in Emergency, not Ready: sent no Set Wrench Effort; not starting "
            "(see --resume-when-ready)\n");
  EXPECT_EQ(out.str(), "control of 1.1.33.1 granted to 254.1.40.1 (authority 7)\n1.1.33.1: state Emergency\n");
  ASSERT_TRUE(run_until([&] { return !controlled(); }));

  other->send(kDriver, jaus::msg::ClearEmergency{{1}});
  ASSERT_TRUE(run_until([&] { return driver_state() == jaus::msg::PrimaryStatus::ready; }));
  run_for(500ms);
  EXPECT_EQ(target->efforts_arrived(), 0u);
}

TEST_F(ControlStreamTest, StandbyStopsTheStreamAndAResumeDoesNotRestartIt) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  once([&] { return applied() >= 3; }, [&] { other->send(kDriver, jaus::msg::Standby{}); });
  EXPECT_EQ(ocu::run_control(*ocu, streaming(), io()), kExitLeftReady) << err.str();
  EXPECT_EQ(err.str(),
            "jausctl control: 1.1.33.1 entered Standby: stopped sending Set Wrench Effort; not resuming "
            "(see --resume-when-ready)\n");
  ASSERT_TRUE(run_until([&] { return !controlled(); }));
  const auto arrived = target->efforts_arrived();

  // Resume needs control: the other OCU takes it and resumes the driver.
  ocu::ControlHold resumer(*other, kDriver, 5);
  ASSERT_EQ(resumer.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  other->send(kDriver, jaus::msg::Resume{});
  ASSERT_TRUE(run_until([&] { return driver_state() == jaus::msg::PrimaryStatus::ready; }));
  run_for(500ms);
  EXPECT_EQ(target->efforts_arrived(), arrived);
  resumer.release();
}

TEST_F(ControlStreamTest, ResumeWhenReadyPausesThroughAnEmergencyAndResumesAfterTheClear) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  std::uint64_t applied_when_paused = 0;
  once([&] { return applied() >= 3; }, [&] { other->send(kDriver, jaus::msg::SetEmergency{{1}}); });
  once([&] { return out_has("paused"); },
       [&] {
         applied_when_paused = applied();
         other->send(kDriver, jaus::msg::ClearEmergency{{1}});
       });
  once([&] { return applied_when_paused > 0 && applied() >= applied_when_paused + 3; }, [&] { ocu->interrupt(); });
  auto options = streaming();
  options.resume_when_ready = true;
  EXPECT_EQ(ocu::run_control(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_EQ(err.str(), "");
  const auto lines = out_lines();
  ASSERT_EQ(lines.size(), 8u) << out.str();
  EXPECT_EQ(lines[1], "1.1.33.1: state Ready");
  EXPECT_EQ(lines[2], "1.1.33.1: Ready: sending Set Wrench Effort");
  EXPECT_EQ(lines[3], "1.1.33.1: state Ready -> Emergency");
  EXPECT_EQ(lines[4], "1.1.33.1: not Ready: paused Set Wrench Effort until it is Ready again (--resume-when-ready)");
  EXPECT_EQ(lines[5], "1.1.33.1: state Emergency -> Ready");
  EXPECT_EQ(lines[6], "1.1.33.1: Ready: sending Set Wrench Effort");
  EXPECT_EQ(lines[7].rfind("control of 1.1.33.1 released after ", 0), 0u) << lines[7];
}

TEST_F(ControlStreamTest, ResumeWhenReadySendsNothingInStandbyAndResumesAfterResume) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  ocu::ControlHold control(*ocu, kDriver, 7);
  std::vector<std::uint64_t> sent_at;  // when sending started, paused, started again
  control.send_while_held(forward(), 50ms, ocu::ControlHold::WhenNotReady::pause,
                          [&](bool) { sent_at.push_back(control.sent_while_held()); });
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  once([&] { return applied() >= 3; }, [&] { other->send(kDriver, jaus::msg::Standby{}); });
  // Resume is the controller's: this OCU's (the tool's operator, here).
  once([&] { return sent_at.size() == 2; }, [&] { ocu->send(kDriver, jaus::msg::Resume{}); });
  once([&] { return sent_at.size() == 3 && control.sent_while_held() >= sent_at[2] + 3; }, [&] { ocu->interrupt(); });
  EXPECT_EQ(control.hold(30s), ocu::ControlHold::End::interrupted);
  ASSERT_EQ(sent_at.size(), 3u);
  EXPECT_EQ(sent_at[0], 0u);
  EXPECT_GE(sent_at[1], 3u);
  EXPECT_EQ(sent_at[2], sent_at[1]);  // nothing while in Standby
  control.release();
  ASSERT_TRUE(run_until([&] { return !controlled(); }));
  EXPECT_EQ(target->efforts_arrived(), control.sent_while_held());
}

TEST_F(ControlStreamTest, WithResumeWhenReadyAComponentInEmergencyAtTheStartGetsCommandsOnlyOnceCleared) {
  auto ocu = open_ocu();
  auto other = open_ocu(kOcuB);
  ASSERT_TRUE(ocu && other);
  other->send(kDriver, jaus::msg::SetEmergency{{1}});
  ASSERT_TRUE(run_until([&] { return driver_state() == jaus::msg::PrimaryStatus::emergency; }));
  std::uint64_t arrived_before_clear = 1;  // set when cleared
  once([&] { return out_has("1.1.33.1: state Emergency\n"); },
       [&] {
         arrived_before_clear = target->efforts_arrived();
         other->send(kDriver, jaus::msg::ClearEmergency{{1}});
       });
  once([&] { return applied() >= 3; }, [&] { ocu->interrupt(); });
  auto options = streaming();
  options.resume_when_ready = true;
  EXPECT_EQ(ocu::run_control(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_EQ(arrived_before_clear, 0u);
  EXPECT_NE(out.str().find("1.1.33.1: state Emergency\n1.1.33.1: state Emergency -> Ready\n"
                           "1.1.33.1: Ready: sending Set Wrench Effort\n"),
            std::string::npos)
      << out.str();
}

}  // namespace
}  // namespace jausctl::test
