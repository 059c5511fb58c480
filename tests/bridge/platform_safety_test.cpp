// Safety of the whole loop under virtual time: a primitive driver (and a
// sensor) on the real bridge, the Clearpath protocol and the in-process
// simulated platform with its hardware e-stop and pause, the latches wired as
// jausd's host wires them (PlatformEmergencyMirror). The checks read the
// simulated platform's true state and every frame written to it.
// docs/safety.md names each test here with the hazard it covers.
#include <gtest/gtest.h>

#include "harness.hpp"
#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/bridge/platform_emergency.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"
#include "jaus/components/primitive_driver.hpp"

namespace jaus::test {
namespace {

namespace bridge = jaus::bridge;
namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
using namespace std::chrono_literals;
using S = msg::PrimaryStatus;

sim::LoopbackConfig loopback_for(sim::Drive drive) {
  sim::LoopbackConfig c;
  c.platform.vehicle.drive = drive;
  return c;
}

bridge::ClearpathVehicleConfig husky(std::uint16_t emergency_flags = 0x08) {
  bridge::ClearpathVehicleConfig c;
  c.emergency_flags = emergency_flags;  // Husky: the e-stop's bit
  return c;
}

// One frame the bridge wrote to the platform, when.
struct Written {
  rt::TimePoint at;
  cp::Envelope envelope;
};

class PlatformSafety : public ::testing::Test {
 protected:
  void start(bridge::ClearpathVehicleConfig config = husky(), sim::Drive drive = sim::Drive::differential,
             const std::function<void()>& before_the_bridge = {}) {
    loopback = std::make_unique<sim::LoopbackClient>(time, time, loopback_for(drive));
    loopback->on_written([this](std::span<const std::uint8_t> frame) {
      if (auto f = cp::decode_frame(frame))
        if (auto e = cp::decode(*f, cp::Direction::to_platform)) written.push_back({time.now(), *e});
    });
    if (before_the_bridge) before_the_bridge();
    connection = std::make_unique<bridge::PlatformConnection>(*loopback, time);
    vehicle = std::make_unique<bridge::ClearpathVehicle>(*connection, config);
    rt::ComponentConfig c;
    c.name = "primitive driver";
    c.address = kDriver;
    outbox.clock = &time;
    driver = std::make_unique<components::PrimitiveDriver>(
        c, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); }},
        *vehicle);
    driver->share_emergency(vehicle_latch);
    driver->on_state_change([this](S, S after) { states.push_back(after); });
    driver->start();
    mirror = std::make_unique<bridge::PlatformEmergencyMirror>(
        *vehicle, std::vector<rt::EmergencyLatch*>{&vehicle_latch}, &vehicle_latch);
    time.advance(300ms);  // the platform heard: Initialize -> Ready
  }
  void TearDown() override {
    mirror.reset();
    driver.reset();
  }

  template <class M>
  void deliver(const Address& from, const M& m) {
    deliver_to(*driver, time, from, m);
  }
  // An OCU streaming Set Wrench Effort at 10 Hz for `d`.
  void stream(double percent, rt::Duration d) {
    for (auto t = rt::Duration::zero(); t < d; t += 100ms) {
      msg::SetWrenchEffort m;
      m.propulsive_linear_effort_x_percent = percent;
      deliver(kOcuA, m);
      time.advance(100ms);
    }
  }
  const sim::VehicleModel& model() const { return loopback->platform().vehicle(); }
  bool wheels_still() const { return model().left().speed == 0 && model().right().speed == 0; }
  void press(sim::HardwareInput input, bool on) { loopback->platform().press(input, on, time.now()); }
  std::vector<std::uint16_t> safety_words_written() const {
    std::vector<std::uint16_t> words;
    for (const auto& w : written)
      if (const auto* m = w.envelope.message.get_if<cp::SetSafetySystem>()) words.push_back(m->flags);
    return words;
  }
  bool was_ready_since(std::size_t from) const {
    return std::find(states.begin() + static_cast<std::ptrdiff_t>(from), states.end(), S::ready) != states.end();
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  std::vector<S> states;
  std::vector<Written> written;
  rt::EmergencyLatch vehicle_latch;  // the host's: outlives the driver
  std::unique_ptr<sim::LoopbackClient> loopback;
  std::unique_ptr<bridge::PlatformConnection> connection;
  std::unique_ptr<bridge::ClearpathVehicle> vehicle;
  std::unique_ptr<components::PrimitiveDriver> driver;
  std::unique_ptr<bridge::PlatformEmergencyMirror> mirror;
};

// Issue 27, failure 1: a pause on the platform holds every component in
// Emergency until the platform itself releases it; jausd writes nothing that
// could erase it, and a controller streaming all along moves nothing.
TEST_F(PlatformSafety, APlatformPauseIsHeldUntilThePlatformReleasesIt) {
  start();
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  stream(60, 1s);
  ASSERT_FALSE(wheels_still());
  press(sim::HardwareInput::pause, true);
  const auto before = states.size();
  stream(60, 3s);
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_FALSE(was_ready_since(before)) << "flip-flop";
  EXPECT_TRUE(wheels_still());
  EXPECT_EQ(model().safety_flags() & sim::kSafetyPause, sim::kSafetyPause);
  EXPECT_EQ(model().commanded_safety() & sim::kSafetyPause, 0) << "jausd wrote the platform's pause";
  press(sim::HardwareInput::pause, false);
  time.advance(300ms);
  EXPECT_EQ(driver->state(), S::ready);  // back to what the pause interrupted
  EXPECT_TRUE(wheels_still());           // and nothing moves until a new command
}

// Issue 42: a platform pause of 50 ms, pressed at every phase of the safety
// status subscription (3 ms steps over 100 ms), is always seen: the driver
// enters Emergency (and counts the stop, which every Report Component
// Status then carries), stays there until the platform reports the pause
// released, and only then is Ready. Returns how many pauses were seen.
class PlatformPauses : public PlatformSafety {
 protected:
  static constexpr int kPhases = 34;
  int pauses_seen(std::uint16_t rate_hz) {
    auto config = husky();
    config.safety_status_rate_hz = rate_hz;
    start(config);
    int seen = 0;
    for (int phase_ms = 0; phase_ms < 3 * kPhases; phase_ms += 3) {
      time.advance(std::chrono::milliseconds(phase_ms));
      const auto stops = driver->counters().stops_entered;
      const auto before = states.size();
      press(sim::HardwareInput::pause, true);
      time.advance(50ms);
      press(sim::HardwareInput::pause, false);
      if (driver->counters().stops_entered == stops + 1) {
        ++seen;
        // Held until the platform says it is released: never Ready during the pause.
        EXPECT_FALSE(was_ready_since(before)) << "Ready during the pause at phase " << phase_ms << " ms";
      }
      time.advance(250ms);
      EXPECT_EQ(driver->state(), S::ready);
      EXPECT_LE(driver->counters().stops_entered, stops + 1);
    }
    return seen;
  }
};

TEST_F(PlatformPauses, AFiftyMillisecondPauseIsSeenWheneverItFalls) {
  EXPECT_EQ(pauses_seen(bridge::ClearpathVehicleConfig{}.safety_status_rate_hz), kPhases);
}

// The former 10 Hz subscription misses some of them entirely: the check that
// the test above can fail.
TEST_F(PlatformPauses, AtTenHertzAFiftyMillisecondPauseCanBeMissed) { EXPECT_LT(pauses_seen(10), kPhases); }

// A JAUS Emergency set during the pause waits to be written until the pause
// is released (a write could only erase or latch it), then holds the platform.
TEST_F(PlatformSafety, SetEmergencyDuringAPauseIsWrittenOnceThePauseIsReleased) {
  start();
  press(sim::HardwareInput::pause, true);
  time.advance(300ms);
  ASSERT_EQ(driver->state(), S::emergency);
  deliver(kOcuB, msg::SetEmergency{});
  time.advance(500ms);
  EXPECT_TRUE(safety_words_written().empty());
  press(sim::HardwareInput::pause, false);
  time.advance(500ms);
  EXPECT_EQ(model().commanded_safety(), 0x08);
  EXPECT_EQ(driver->state(), S::emergency);  // Set Emergency still holds it
  deliver(kOcuB, msg::ClearEmergency{});
  time.advance(500ms);
  EXPECT_EQ(model().commanded_safety(), 0);
  EXPECT_EQ(driver->state(), S::ready);
}

// The Husky's e-stop shares jausd's emergency bit (0x08): pressed while jausd
// holds the bit, the JAUS clear must not release the vehicle, nor make it
// flip between Emergency and Ready at the status rate.
TEST_F(PlatformSafety, AHardwareEstopOnJausdsOwnBitNeverFlipFlops) {
  start();
  deliver(kOcuA, msg::SetEmergency{});
  time.advance(300ms);
  ASSERT_EQ(model().commanded_safety(), 0x08);
  press(sim::HardwareInput::estop, true);
  time.advance(300ms);
  const auto before = states.size();
  deliver(kOcuA, msg::ClearEmergency{});
  time.advance(3s);
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_FALSE(was_ready_since(before));
  EXPECT_EQ(model().commanded_safety(), 0);  // jausd's bit is clear; the e-stop's is the platform's
  EXPECT_TRUE(std::any_of(logs.begin(), logs.end(), [](const std::string&) { return true; }));
  press(sim::HardwareInput::estop, false);
  time.advance(300ms);
  EXPECT_EQ(driver->state(), S::ready);
}

// jausd's own flag is never taken for the platform's stop; its clear is held
// until the platform reports it (no Ready while the platform may still be stopped).
TEST_F(PlatformSafety, OurOwnEmergencyFlagIsNotAPlatformStopAndItsClearIsConfirmed) {
  start();
  deliver(kOcuA, msg::SetEmergency{});
  time.advance(500ms);
  EXPECT_EQ(vehicle_latch.local_holds().size(), 0u);
  const auto before = states.size();
  deliver(kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);  // until the platform shows the bit clear
  time.advance(500ms);
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(std::count(states.begin() + static_cast<std::ptrdiff_t>(before), states.end(), S::ready), 1);
}

// Other bits of the safety word are kept as the platform last reported them.
TEST_F(PlatformSafety, TheSafetyWordKeepsBitsJausdDoesNotOwn) {
  start();
  cp::SetSafetySystem other;
  other.flags = 0x0100;  // set by another client of the platform
  loopback->send(other);
  time.advance(300ms);
  deliver(kOcuA, msg::SetEmergency{});
  time.advance(300ms);
  EXPECT_EQ(model().commanded_safety(), 0x0108);
  deliver(kOcuA, msg::ClearEmergency{});
  time.advance(300ms);
  EXPECT_EQ(model().commanded_safety(), 0x0100);
}

TEST_F(PlatformSafety, ShutdownInEmergencyNeverClearsThePlatformsEmergencyFlag) {
  start();
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  deliver(kOcuB, msg::SetEmergency{});
  time.advance(300ms);
  ASSERT_EQ(model().commanded_safety(), 0x08);
  deliver(kOcuA, msg::Shutdown{});
  ASSERT_EQ(driver->state(), S::shutdown);
  time.advance(1s);
  EXPECT_EQ(model().commanded_safety(), 0x08);
}

// A restarted jausd whose hold was persisted finds its own flag on the
// platform: it is jausd's, not a platform stop, and clears with the hold.
TEST_F(PlatformSafety, AHoldRestoredAtStartOwnsTheFlagAnEarlierRunLeft) {
  vehicle_latch.restore({kOcuA}, false);
  start(husky(), sim::Drive::differential, [&] {
    cp::SetSafetySystem left;
    left.flags = 0x08;
    loopback->send(left);
    time.advance(100ms);
  });
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_TRUE(vehicle_latch.local_holds().empty());
  deliver(kOcuA, msg::ClearEmergency{});
  time.advance(500ms);
  EXPECT_EQ(model().commanded_safety(), 0);
  EXPECT_EQ(driver->state(), S::ready);
}

// ...and without the hold (not persisted, or cleared locally while jausd was
// stopped) the flag is a stop jausd cannot tell from the e-stop: held, until
// the local clear reclaims it; a real e-stop on that bit stays held even then.
TEST_F(PlatformSafety, TheLocalClearReclaimsAFlagAnEarlierRunLeftButNeverTheEstop) {
  start(husky(), sim::Drive::differential, [&] {
    cp::SetSafetySystem left;
    left.flags = 0x08;
    loopback->send(left);
    time.advance(100ms);
  });
  time.advance(1s);
  EXPECT_EQ(driver->state(), S::emergency);
  vehicle->reclaim_safety_bits();
  time.advance(500ms);
  EXPECT_EQ(model().commanded_safety(), 0);
  EXPECT_EQ(driver->state(), S::ready);

  press(sim::HardwareInput::estop, true);
  time.advance(300ms);
  ASSERT_EQ(driver->state(), S::emergency);
  vehicle->reclaim_safety_bits();
  time.advance(1s);
  EXPECT_EQ(driver->state(), S::emergency);
}

// Issue 27, failure 2: the controller goes silent; the driver's command
// timeout writes the zero (with the brake) itself, well before the
// platform's watchdog would have stopped it.
TEST_F(PlatformSafety, ASilentControllerIsStoppedByJausdNotByThePlatformsWatchdog) {
  start();
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  stream(60, 1s);
  const rt::TimePoint last_effort = time.now() - 100ms;
  ASSERT_FALSE(wheels_still());
  time.advance(2s);
  std::optional<rt::TimePoint> zero_at;
  for (const auto& w : written)
    if (const auto* m = w.envelope.message.get_if<cp::SetDifferentialOutput>(); m && w.at > last_effort)
      if (m->left == 0 && m->right == 0 && !zero_at) zero_at = w.at;
  ASSERT_TRUE(zero_at);
  EXPECT_LE(*zero_at - last_effort, 550ms);  // command_timeout_s 0.5 + one tick
  EXPECT_TRUE(wheels_still());
  EXPECT_FALSE(model().watchdog_expired() && model().safety_flags() == 0) << "the watchdog was first";
  EXPECT_EQ(driver->driver_counters().command_timeouts, 1u);
}

// Every stop of an Ackermann platform keeps its steering angle.
TEST_F(PlatformSafety, AnAckermannStopHoldsTheSteeringAngle) {
  auto config = husky();
  config.drive = bridge::DriveMode::ackermann;
  start(config, sim::Drive::ackermann);
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = 40;
  m.propulsive_rotational_effort_z_percent = -30;  // left
  deliver(kOcuA, m);
  time.advance(100ms);
  deliver(kOcuB, msg::SetEmergency{});
  time.advance(300ms);
  const auto* last = [&]() -> const cp::SetAckermannOutput* {
    for (auto it = written.rbegin(); it != written.rend(); ++it)
      if (const auto* a = it->envelope.message.get_if<cp::SetAckermannOutput>()) return a;
    return nullptr;
  }();
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->throttle, 0);
  EXPECT_EQ(last->brake, 100);
  EXPECT_NEAR(last->steering, 30, 0.01);  // Clearpath's steering is positive left
}

// Issue 27, failure 5: Standby, then the platform's link drops and returns:
// Standby again, and a streaming controller moves nothing.
TEST_F(PlatformSafety, StandbySurvivesALostPlatformLink) {
  start();
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  deliver(kOcuB, msg::Standby{});
  loopback->set_plugged(false);
  time.advance(3s);
  EXPECT_EQ(driver->state(), S::failure);
  loopback->set_plugged(true);
  time.advance(5s);
  EXPECT_EQ(driver->state(), S::standby);
  stream(60, 1s);
  EXPECT_TRUE(wheels_still());
}

}  // namespace
}  // namespace jaus::test
