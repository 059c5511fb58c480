// The component runtime under virtual time: lifecycle commands, emergency
// holders, core queries in every state, malformed input, time.
#include <algorithm>

#include "harness.hpp"

namespace jaus::test {
namespace {

using S = msg::PrimaryStatus;

TEST_F(ComponentTest, StartsReadyOrFailure) {
  EXPECT_EQ(driver->state(), S::ready);
  make(5, std::chrono::seconds(3), false, /*init_ok=*/false);
  EXPECT_EQ(driver->state(), S::failure);
  EXPECT_FALSE(driver->stops.empty());  // Failure stops the platform
}

TEST_F(ComponentTest, StandbyFromAnyoneStopsThePlatform) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  drive(kOcuA, 50);
  ASSERT_TRUE(driver->moving);
  deliver(kOcuB, msg::Standby{});  // not the controller, still honoured: it only makes things safer
  EXPECT_EQ(driver->state(), S::standby);
  EXPECT_FALSE(driver->moving);
  drive(kOcuA, 50);  // commands do not execute outside Ready
  EXPECT_EQ(driver->executed.size(), 1u);
  EXPECT_EQ(driver->counters().refused_wrong_state, 1u);
  // Resume needs the controller.
  deliver(kOcuB, msg::Resume{});
  EXPECT_EQ(driver->state(), S::standby);
  deliver(kOcuA, msg::Resume{});
  EXPECT_EQ(driver->state(), S::ready);
}

TEST_F(ComponentTest, RefusedTransitionsAreCountedAndLogged) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuA, msg::Resume{});  // Resume from Ready
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(driver->counters().refused_transitions, 1u);
  EXPECT_TRUE(logged("Resume from 2.1.40.1 refused in Ready"));
  deliver(kOcuA, msg::SetEmergency{});
  deliver(kOcuA, msg::Standby{});  // Standby while Emergency
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_EQ(driver->counters().refused_transitions, 2u);
}

TEST_F(ComponentTest, EmergencyNeedsEveryHolderToClear) {
  drive(kOcuA, 30);  // not controlled: refused anyway
  deliver(kOcuA, msg::SetEmergency{});
  deliver(kOcuB, msg::SetEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  deliver(kOcuC, msg::ClearEmergency{});  // holds nothing
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_TRUE(logged("Clear Emergency from 4.1.40.1 refused"));
  deliver(kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_TRUE(logged("still held by 3.1.40.1"));
  deliver(kOcuB, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(driver->counters().refused_clears, 2u);
}

// Forged senders cannot grow the latch without bound, nor release a hold they
// did not set: the component stays in Emergency, and the hardware's own hold
// is always kept.
TEST_F(ComponentTest, AFloodOfEmergencyHoldersIsBoundedAndNeverReleasesTheHardwareHold) {
  driver->hold_hardware_emergency("e-stop pressed");
  for (int i = 0; i < 1000; ++i)
    deliver(Address{static_cast<std::uint8_t>(10 + i % 200), static_cast<std::uint8_t>(1 + i / 200), 40, 1},
            msg::SetEmergency{});
  EXPECT_EQ(driver->emergency().holders().size(), rt::EmergencyLatch::kMaxHolders);
  EXPECT_EQ(driver->emergency().unrecorded(), 1000u - rt::EmergencyLatch::kMaxHolders);
  EXPECT_TRUE(driver->emergency().overflowed());
  for (int i = 0; i < 1000; ++i)
    deliver(Address{static_cast<std::uint8_t>(10 + i % 200), static_cast<std::uint8_t>(1 + i / 200), 40, 1},
            msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);  // the hardware still holds it, and so do the unrecorded
  EXPECT_TRUE(driver->emergency().holders().empty());
  std::size_t lines = 0;
  for (const auto& l : logs) lines += l.find("emergency") != std::string::npos || l.find("Emergency") != std::string::npos;
  EXPECT_LT(lines, 10u);  // one line a second per reason, not 2000
  driver->release_hardware_emergency("e-stop pressed");
  EXPECT_EQ(driver->state(), S::emergency);  // holders beyond the recorded ones were not forgotten
}

// Issue 28: a controller that loops what it may do (control, Standby and
// Resume, emergencies, its authority) writes a few dozen lines per 10 s
// window, not one per cycle; what was left out is counted when the window
// ends. The stops themselves are never limited.
TEST_F(ComponentTest, AControllerLoopingControlStateAndEmergencyWritesABoundedLog) {
  logs.clear();
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(request_control(kOcuA, 10), 0);
    deliver(kOcuA, msg::SetComponentAuthority{{static_cast<std::uint8_t>(1 + i % 2)}});
    deliver(kOcuA, msg::Standby{});
    deliver(kOcuA, msg::Resume{});
    deliver(kOcuA, msg::SetEmergency{});
    deliver(kOcuA, msg::ClearEmergency{});
    deliver(kOcuA, msg::ReleaseComponentControl{});
  }
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(driver->counters().control_changes, 2000u);
  EXPECT_GE(driver->stops.size(), 3000u);  // every Standby, Emergency and release stopped the platform
  // Each kind writes its first lines as before.
  EXPECT_TRUE(logged("controlled by 2.1.40.1"));
  EXPECT_TRUE(logged("authority 5 -> 1 (by 2.1.40.1)"));
  EXPECT_TRUE(logged("released by 2.1.40.1"));
  EXPECT_LE(logs.size(), 40u);  // 7000 messages, 8000 lines without the limiter
  const auto before_summary = logs.size();
  time.advance(std::chrono::seconds(10));
  ASSERT_GT(logs.size(), before_summary);
  std::string summary;  // one line per level
  for (std::size_t i = before_summary; i < logs.size(); ++i) summary += logs[i] + "\n";
  EXPECT_NE(summary.find("left out in the last 10 s: "), std::string::npos) << summary;
  for (const char* kind : {"x control granted", "x control released", "x authority changes", "x state changes"})
    EXPECT_NE(summary.find(kind), std::string::npos) << kind << " in " << summary;
}

// A controller that takes control and goes silent, in a loop: each time its
// control is dropped (and the platform stopped), a line up to the burst.
TEST_F(ComponentTest, AControllerLoopingTakeAndGoSilentWritesABoundedLog) {
  make(5, std::chrono::milliseconds(100));
  logs.clear();
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(request_control(kOcuA, 10), 0);
    time.advance(std::chrono::milliseconds(200));  // beyond the 100 ms controller timeout
    ASSERT_FALSE(driver->control().controller());
  }
  time.advance(std::chrono::seconds(10));
  std::size_t dropped = 0;
  for (const auto& l : logs) dropped += l.find("dropped: controller silent") != std::string::npos;
  EXPECT_GE(dropped, 1u);
  EXPECT_LE(dropped, 3u * static_cast<std::size_t>(rt::kNoteworthyBurst));  // 20 s: 100 drops, three windows
  EXPECT_TRUE(logged("x control dropped"));
}

// Issue 27, failure 3: twenty operators set Emergency and nineteen clear; the
// one left still holds it, however many there were.
TEST_F(ComponentTest, NoEmergencyHolderIsForgottenBeyondTheRecordedOnes) {
  const auto operator_at = [](int i) { return Address{static_cast<std::uint8_t>(10 + i), 1, 40, 1}; };
  const int operators = static_cast<int>(rt::EmergencyLatch::kMaxHolders) + 4;
  for (int i = 0; i < operators; ++i) deliver(operator_at(i), msg::SetEmergency{});
  for (int i = 0; i + 1 < operators; ++i) deliver(operator_at(i), msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  deliver(operator_at(operators - 1), msg::ClearEmergency{});
  // The last operator was beyond the recorded ones: its own clear cannot be
  // matched to it, so the latch stays (fail safe) until the local clear.
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_TRUE(driver->emergency().overflowed());
}

TEST_F(ComponentTest, EmergencyReturnsToStandbyWhenItInterruptedStandby) {
  deliver(kOcuA, msg::Standby{});
  deliver(kOcuA, msg::SetEmergency{});
  deliver(kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::standby);
}

TEST_F(ComponentTest, EmergencyStaysLatchedThroughReset) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuB, msg::SetEmergency{});
  deliver(kOcuA, msg::Reset{});
  EXPECT_EQ(driver->state(), S::emergency);
  deliver(kOcuB, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
}

TEST_F(ComponentTest, EmergencyWithoutStopBitIsIgnored) {
  deliver(kOcuA, msg::SetEmergency{{0}});
  EXPECT_EQ(driver->state(), S::ready);
}

TEST_F(ComponentTest, ShutdownIsFinalAndSilent) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuA, msg::Shutdown{});
  EXPECT_EQ(driver->state(), S::shutdown);
  EXPECT_FALSE(driver->control().controller());
  outbox.clear();
  deliver(kOcuA, msg::QueryComponentStatus{});
  deliver(kOcuA, msg::Reset{});
  EXPECT_EQ(driver->state(), S::shutdown);
  EXPECT_TRUE(outbox.sent.empty());
}

TEST_F(ComponentTest, CoreQueriesAreAnsweredInEveryState) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  auto check = [&](S expected) {
    outbox.clear();
    deliver(kOcuB, msg::QueryComponentStatus{});
    deliver(kOcuB, msg::QueryComponentAuthority{});
    deliver(kOcuB, msg::QueryComponentControl{});
    deliver(kOcuB, msg::QueryTime{{3}});
    deliver(kOcuB, msg::QueryHeartbeatPulse{});
    deliver(kOcuB, msg::QueryIdentification{{msg::identification::kComponent}});
    deliver(kOcuB, msg::QueryIdentification{{msg::identification::kSubsystem}});  // the node manager's to answer
    const auto identification = outbox.to<msg::ReportIdentification>(kOcuB);
    ASSERT_EQ(identification.size(), 1u);
    EXPECT_EQ(identification[0].query_type, msg::identification::kComponent);
    EXPECT_EQ(identification[0].identification, "driver");
    EXPECT_EQ(identification[0].authority, 5);
    const auto status = outbox.to<msg::ReportComponentStatus>(kOcuB);
    ASSERT_EQ(status.size(), 1u);
    EXPECT_EQ(status[0].primary_status, static_cast<std::uint8_t>(expected));
    EXPECT_EQ(status[0].secondary_status & 1u, expected == S::emergency ? 1u : 0u);
    EXPECT_EQ(outbox.to<msg::ReportComponentAuthority>(kOcuB).at(0).authority, 5);
    EXPECT_EQ(outbox.to<msg::ReportComponentControl>(kOcuB).at(0).controller, kOcuA);
    // The harness clock starts at 1970, before the date stamp's range: time only.
    const auto time_reports = outbox.to<msg::ReportTime>(kOcuB);
    ASSERT_EQ(time_reports.size(), 1u);
    EXPECT_TRUE(time_reports[0].time.has_value());
    EXPECT_FALSE(time_reports[0].date.has_value());
    EXPECT_EQ(outbox.count<msg::ReportHeartbeatPulse>(), 1u);
    // OCUs ask each component for its services: its own entry, inputs and outputs.
    deliver(kOcuB, msg::QueryServices{});
    const auto services = outbox.to<msg::ReportServices>(kOcuB);
    ASSERT_EQ(services.size(), 1u);
    ASSERT_EQ(services[0].services.size(), 1u);
    EXPECT_EQ(services[0].services[0], driver->service_entry());
    EXPECT_EQ(services[0].services[0].type, kDriver.component);
    const auto& inputs = services[0].services[0].inputs;
    EXPECT_TRUE(std::any_of(inputs.begin(), inputs.end(), [](const auto& e) {
      return e.command_code == msg::QueryServices::code;
    }));
  };
  check(S::ready);
  deliver(kOcuA, msg::Standby{});
  check(S::standby);
  deliver(kOcuA, msg::SetEmergency{});
  check(S::emergency);
}

TEST_F(ComponentTest, ReportTimeComesFromTheInjectedClock) {
  using namespace std::chrono;
  rt::VirtualTime t(sys_days{2026y / November / 21} + hours{13} + minutes{37} + seconds{42} + milliseconds{789});
  rt::ComponentConfig config;
  config.address = kDriver;
  TestDriver d(config, rt::Environment{t, t, outbox});
  d.start();
  outbox.clear();
  Header h;
  h.command_code = msg::QueryTime::code;
  h.source = kOcuA;
  h.destination = kDriver;
  const std::uint8_t pv[] = {0x03};
  h.data_size = 1;
  d.receive(h, pv);
  const auto reports = outbox.to<msg::ReportTime>(kOcuA);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].time, (TimeStamp{789, 42, 37, 13, 21}));
  EXPECT_EQ(reports[0].date, (DateStamp{21, 11, 2026}));
}

TEST_F(ComponentTest, SetTimeNeedsControlAndMovesOnlyThisComponentsClock) {
  msg::SetTime set;
  set.time = TimeStamp{0, 0, 0, 12, 3};
  set.date = DateStamp{3, 4, 2030};
  deliver(kOcuA, set);  // not the controller
  EXPECT_EQ(driver->counters().refused_not_controller, 1u);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuA, set);
  time.advance(std::chrono::seconds(61));
  outbox.clear();
  deliver(kOcuA, msg::QueryTime{{3}});
  const auto report = outbox.to<msg::ReportTime>(kOcuA).at(0);
  EXPECT_EQ(report.date, (DateStamp{3, 4, 2030}));
  EXPECT_EQ(report.time->hour, 12);
  EXPECT_EQ(report.time->minute, 1);
  EXPECT_EQ(report.time->second, 1);
}

TEST_F(ComponentTest, MalformedPayloadsAreCountedNeverActedUpon) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  Header h;
  h.command_code = msg::SetWrenchEffort::code;
  h.source = kOcuA;
  h.destination = kDriver;
  const std::uint8_t truncated[] = {0x01, 0x00, 0x10};  // pv says effort X follows; one byte of it
  driver->receive(h, truncated);
  EXPECT_TRUE(driver->executed.empty());
  EXPECT_EQ(driver->counters().decode_errors, 1u);
  EXPECT_TRUE(logged("malformed Set Wrench Effort from 2.1.40.1"));
}

TEST_F(ComponentTest, UnsupportedMessagesAreCounted) {
  deliver(kOcuA, msg::SetJointEfforts{{{10.0}}});
  EXPECT_EQ(driver->counters().unsupported, 1u);
}

TEST_F(ComponentTest, SetAuthorityNeedsControl) {
  deliver(kOcuA, msg::SetComponentAuthority{{77}});
  EXPECT_EQ(driver->control().own_authority(), 5);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuA, msg::SetComponentAuthority{{77}});
  EXPECT_EQ(driver->control().own_authority(), 77);
}

// Issue 42: a component that controls others (the drivers above the
// primitive driver) has a ceiling its controller cannot raise its authority
// above, so an operator above the ceiling always wins. Refused means not
// applied (the RA has no reply): counted, logged with the reason, and Query
// Component Authority keeps reporting the authority in effect.
TEST_F(ComponentTest, SetAuthorityAboveTheCeilingIsRefusedAndAtOrBelowItIsApplied) {
  make(1, std::chrono::seconds(3), false, true, /*max_authority=*/1);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  logs.clear();
  deliver(kOcuA, msg::SetComponentAuthority{{255}});
  EXPECT_EQ(driver->control().own_authority(), 1);
  EXPECT_EQ(driver->counters().refused_authority_changes, 1u);
  EXPECT_TRUE(logged("Set Component Authority 255 from 2.1.40.1 refused: above max_authority 1"));
  EXPECT_TRUE(logged("authority stays 1"));
  outbox.clear();
  deliver(kOcuB, msg::QueryComponentAuthority{});
  const auto reported = outbox.to<msg::ReportComponentAuthority>(kOcuB);
  ASSERT_EQ(reported.size(), 1u);
  EXPECT_EQ(reported.back().authority, 1);
  // Lower, and back up to the ceiling: applied.
  deliver(kOcuA, msg::SetComponentAuthority{{0}});
  EXPECT_EQ(driver->control().own_authority(), 0);
  deliver(kOcuA, msg::SetComponentAuthority{{2}});
  EXPECT_EQ(driver->control().own_authority(), 0);
  deliver(kOcuA, msg::SetComponentAuthority{{1}});
  EXPECT_EQ(driver->control().own_authority(), 1);
  EXPECT_EQ(driver->counters().refused_authority_changes, 2u);
  // Only the controller may ask at all: a non-controller's is not even counted as above the ceiling.
  deliver(kOcuB, msg::SetComponentAuthority{{200}});
  EXPECT_EQ(driver->counters().refused_authority_changes, 2u);
  EXPECT_EQ(driver->counters().refused_not_controller, 1u);
}

TEST_F(ComponentTest, AFloodOfSetAuthorityAboveTheCeilingWritesABoundedLog) {
  make(1, std::chrono::seconds(3), false, true, /*max_authority=*/1);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  logs.clear();
  for (int i = 0; i < 1000; ++i) deliver(kOcuA, msg::SetComponentAuthority{{static_cast<std::uint8_t>(2 + i % 250)}});
  EXPECT_EQ(driver->control().own_authority(), 1);
  EXPECT_EQ(driver->counters().refused_authority_changes, 1000u);
  EXPECT_LE(logs.size(), static_cast<std::size_t>(rt::kNoteworthyBurst));
}

// Built directly (not through a kind, which refuses it) with an authority
// above its ceiling: it starts at the ceiling, and says so.
TEST_F(ComponentTest, AnAuthorityAboveTheCeilingAtConstructionStartsAtTheCeiling) {
  logs.clear();
  make(200, std::chrono::seconds(3), false, true, /*max_authority=*/3);
  EXPECT_EQ(driver->control().own_authority(), 3);
  EXPECT_TRUE(logged("authority 200 above max_authority 3: 3 used"));
  // A request at the configured 200's level is not needed: 3 is the floor now.
  EXPECT_EQ(request_control(kOcuA, 3), 0);
}

}  // namespace
}  // namespace jaus::test
