// The simulated platform's safety system under rt::VirtualTime: hardware
// inputs (e-stop button, pause input) kept apart from the word Set Safety
// System (0x0010) writes, Safety Status (0x8010) = commanded | hardware |
// watchdog, and a released stop that never starts motion by itself. Driven
// through a real client (LoopbackClient), so every command crosses the codec.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
using namespace std::chrono_literals;
using sim::HardwareInput;

namespace {

class Rig {
 public:
  explicit Rig(sim::Drive drive = sim::Drive::differential)
      : loopback_(time_, time_, config(drive)) {
    loopback_.on_data([this](const cp::Envelope& e) {
      if (const auto* s = e.message.get_if<cp::SafetyStatus>()) reported_safety = s->flags;
    });
    loopback_.platform().on_event([this](const sim::PlatformEvent& e) { events.push_back(e); });
    cp::RequestSafetyStatus safety;
    safety.subscription = 50;
    loopback_.subscribe(safety);
    run_for(50ms);
  }

  void run_for(rt::Duration d) { time_.advance(d); }
  rt::TimePoint now() const { return time_.now(); }
  // Sends one command (no stream) and waits for its ACK.
  std::optional<cp::CommandOutcome> send(cp::AnyMessage m) {
    std::optional<cp::CommandOutcome> outcome;
    loopback_.send(std::move(m), [&](const cp::CommandOutcome& o) { outcome = o; });
    run_for(20ms);
    return outcome;
  }
  bool accepted(cp::AnyMessage m) {
    const auto outcome = send(std::move(m));
    return outcome && outcome->ok();
  }
  void press(HardwareInput input, bool on) { loopback_.platform().press(input, on, time_.now()); }
  const sim::VehicleModel& model() const { return loopback_.platform().vehicle(); }
  double speed() const { return model().linear_speed(); }
  std::size_t count(sim::PlatformEvent::Kind kind) const {
    std::size_t n = 0;
    for (const auto& e : events) n += e.kind == kind;
    return n;
  }

  std::optional<std::uint16_t> reported_safety;  // the newest 0x8010 the client received
  std::vector<sim::PlatformEvent> events;

 private:
  static sim::LoopbackConfig config(sim::Drive drive) {
    sim::LoopbackConfig c;
    c.platform.vehicle.drive = drive;
    return c;
  }
  rt::VirtualTime time_;
  sim::LoopbackClient loopback_;
};

cp::SetVelocity velocity(double v) {
  cp::SetVelocity m;
  m.translational = v;
  m.acceleration = 5.0;  // at speed within 0.2 s
  return m;
}
cp::SetSafetySystem safety(std::uint16_t flags) {
  cp::SetSafetySystem m;
  m.flags = flags;
  return m;
}
cp::SetAckermannOutput ackermann(double throttle) {
  cp::SetAckermannOutput m;
  m.throttle = throttle;
  return m;
}

constexpr std::uint16_t kEstop = sim::kSafetyEmergencyStop;
constexpr std::uint16_t kPause = sim::kSafetyPause;
constexpr std::uint16_t kTimeout = sim::kSafetyTimeout;

}  // namespace

TEST(SimSafety, SetSafetySystemCannotClearThePauseInput) {
  Rig rig;
  rig.press(HardwareInput::pause, true);
  ASSERT_TRUE(rig.accepted(safety(kEstop)));
  ASSERT_TRUE(rig.accepted(velocity(0.5)));  // feeds the watchdog: no 0x01 below
  rig.run_for(100ms);
  EXPECT_EQ(rig.reported_safety, kEstop | kPause);
  EXPECT_EQ(rig.model().commanded_safety(), kEstop);
  EXPECT_EQ(rig.model().hardware_inputs(), kPause);

  // The software word cleared entirely: the pause is still there.
  ASSERT_TRUE(rig.accepted(safety(0)));
  ASSERT_TRUE(rig.accepted(velocity(0.5)));
  rig.run_for(100ms);
  EXPECT_EQ(rig.reported_safety, kPause);
  EXPECT_EQ(rig.speed(), 0.0);
}

TEST(SimSafety, ThePauseReleasedWithTheSoftwareBitStillSetKeepsTheWheelsStopped) {
  Rig rig;
  rig.press(HardwareInput::pause, true);
  ASSERT_TRUE(rig.accepted(safety(kEstop)));
  rig.press(HardwareInput::pause, false);
  EXPECT_EQ(rig.model().hardware_inputs(), 0);
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(rig.accepted(velocity(0.8)));  // accepted, as a real platform does, but no motion
    rig.run_for(80ms);
  }
  EXPECT_EQ(rig.reported_safety, kEstop);
  EXPECT_EQ(rig.speed(), 0.0);
}

TEST(SimSafety, AStopBrakesTheMovingWheelsToZero) {
  Rig rig;
  ASSERT_TRUE(rig.accepted(velocity(0.8)));
  rig.run_for(300ms);
  ASSERT_NEAR(rig.speed(), 0.8, 1e-9);
  rig.press(HardwareInput::estop, true);
  rig.run_for(150ms);  // before the watchdog's 0.5 s: the e-stop alone brakes
  EXPECT_LT(rig.speed(), 0.8);
  rig.run_for(500ms);
  EXPECT_EQ(rig.speed(), 0.0);
}

// A released stop never starts motion: the setpoint from before the stop is
// dropped, and one that arrived during the stop is not kept for after it.
TEST(SimSafety, ReleasingEveryStopDoesNotStartMotionANewCommandDoes) {
  Rig rig;
  ASSERT_TRUE(rig.accepted(velocity(0.8)));
  rig.run_for(200ms);
  ASSERT_GT(rig.speed(), 0.5);
  rig.press(HardwareInput::estop, true);
  rig.press(HardwareInput::pause, true);
  ASSERT_TRUE(rig.accepted(safety(kEstop)));
  ASSERT_TRUE(rig.accepted(velocity(0.8)));  // during the stop
  rig.run_for(100ms);
  rig.press(HardwareInput::estop, false);
  rig.press(HardwareInput::pause, false);
  ASSERT_TRUE(rig.accepted(safety(0)));
  // Within the watchdog's 0.5 s of the last (non-zero) command, yet still.
  rig.run_for(300ms);
  EXPECT_FALSE(rig.model().watchdog_expired());
  EXPECT_EQ(rig.reported_safety, 0);
  EXPECT_EQ(rig.speed(), 0.0);
  EXPECT_EQ(rig.model().mode(), sim::MotionMode::none);

  ASSERT_TRUE(rig.accepted(velocity(0.8)));  // after the clear
  rig.run_for(300ms);
  EXPECT_NEAR(rig.speed(), 0.8, 1e-9);
}

TEST(SimSafety, TheWatchdogBitJoinsTheOthers) {
  Rig rig;
  rig.press(HardwareInput::pause, true);
  ASSERT_TRUE(rig.accepted(safety(kEstop)));
  rig.run_for(100ms);
  EXPECT_EQ(rig.reported_safety, kTimeout | kEstop | kPause);  // no motion command yet
  ASSERT_TRUE(rig.accepted(velocity(0)));
  rig.run_for(100ms);
  EXPECT_EQ(rig.reported_safety, kEstop | kPause);
  rig.run_for(1s);  // commands ceased
  EXPECT_EQ(rig.reported_safety, kTimeout | kEstop | kPause);
}

TEST(SimSafety, AckermannStopsAndDoesNotRestartEither) {
  Rig rig(sim::Drive::ackermann);
  ASSERT_TRUE(rig.accepted(ackermann(50)));
  rig.run_for(300ms);
  ASSERT_GT(rig.speed(), 0.2);
  rig.press(HardwareInput::pause, true);
  ASSERT_TRUE(rig.accepted(safety(kEstop)));
  EXPECT_EQ(rig.model().safety_flags() & ~kTimeout, kEstop | kPause);
  rig.press(HardwareInput::pause, false);
  ASSERT_TRUE(rig.accepted(ackermann(50)));  // still under the software e-stop
  rig.run_for(150ms);
  ASSERT_TRUE(rig.accepted(safety(0)));
  rig.run_for(250ms);
  EXPECT_FALSE(rig.model().watchdog_expired());  // the command during the stop is not what stops it
  EXPECT_EQ(rig.speed(), 0.0);
  ASSERT_TRUE(rig.accepted(ackermann(50)));
  rig.run_for(300ms);
  EXPECT_GT(rig.speed(), 0.2);
}

TEST(SimSafety, AResetKeepsAPressedButtonPressed) {
  Rig rig;
  rig.press(HardwareInput::estop, true);
  ASSERT_TRUE(rig.accepted(cp::ResetProcessor{}));
  rig.run_for(100ms);
  EXPECT_EQ(rig.model().hardware_inputs(), kEstop);
}

// The events clearpath-sim --events prints, each at the platform's time.
TEST(SimSafety, EventsMarkZeroCommandsStoppedWheelsSafetyAndInputs) {
  Rig rig;
  rig.events.clear();
  ASSERT_TRUE(rig.accepted(velocity(0)));  // zero after no motion: no event
  EXPECT_EQ(rig.count(sim::PlatformEvent::Kind::zero_command), 0u);
  ASSERT_TRUE(rig.accepted(velocity(0.5)));
  rig.run_for(200ms);
  const auto zero_sent = rig.now();
  ASSERT_TRUE(rig.accepted(velocity(0)));
  ASSERT_TRUE(rig.accepted(velocity(0)));  // only the first zero after motion counts
  rig.run_for(500ms);
  ASSERT_EQ(rig.count(sim::PlatformEvent::Kind::zero_command), 1u);
  ASSERT_EQ(rig.count(sim::PlatformEvent::Kind::wheels_stopped), 1u);
  rt::TimePoint zero_at{}, stopped_at{};
  for (const auto& e : rig.events) {
    if (e.kind == sim::PlatformEvent::Kind::zero_command) zero_at = e.at;
    if (e.kind == sim::PlatformEvent::Kind::wheels_stopped) stopped_at = e.at;
  }
  EXPECT_GE(zero_at, zero_sent);
  EXPECT_LE(zero_at, zero_sent + 20ms);
  // 0.5 m/s at 5 m/s^2: 0.1 s of braking, in 5 ms physics steps.
  EXPECT_NEAR(std::chrono::duration<double>(stopped_at - zero_at).count(), 0.1, 0.011);

  rig.events.clear();
  rig.press(HardwareInput::pause, true);
  ASSERT_EQ(rig.events.size(), 2u);  // the input, then the word it changed
  EXPECT_EQ(rig.events[0].kind, sim::PlatformEvent::Kind::input);
  EXPECT_EQ(rig.events[0].input, HardwareInput::pause);
  EXPECT_TRUE(rig.events[0].on);
  EXPECT_EQ(rig.events[1].kind, sim::PlatformEvent::Kind::safety);
  EXPECT_EQ(rig.events[1].flags, rig.model().safety_flags());
  EXPECT_TRUE(rig.events[1].flags & kPause);
  EXPECT_EQ(rig.events[1].at, rig.now());
}
