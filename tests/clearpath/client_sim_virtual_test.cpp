// Client core <-> simulated platform, wired in process (LoopbackClient) and
// run by the runtime's VirtualTime: deterministic ACKs, retries, subscriptions,
// watchdogs and setpoint streams.
#include <gtest/gtest.h>

#include <functional>

#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/client_core.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
using namespace std::chrono_literals;

namespace {

class VirtualLink {
 public:
  explicit VirtualLink(sim::PlatformConfig platform = {}, sim::FaultConfig faults = {}, cp::ClientConfig config = {})
      : loopback_(time_, time_, sim::LoopbackConfig{platform, faults, config}), client(loopback_.core()) {
    client.on_data([this](const cp::Envelope& e) { data.push_back(e); });
    loopback_.on_written([this](std::span<const std::uint8_t> frame) { written.emplace_back(frame.begin(), frame.end()); });
  }

  void run_for(rt::Duration d) { time_.advance(d); }
  // What an application does to keep a setpoint alive: set it again.
  void set_setpoint(cp::AnyMessage m) { client.set_setpoint(std::move(m), time_.now()); }
  void stop_setpoint(cp::AnyMessage m) { client.stop_setpoint(std::move(m), time_.now()); }
  // Every setpoint of `type` written so far, decoded.
  std::vector<cp::AnyMessage> written_of(std::uint16_t type) const {
    std::vector<cp::AnyMessage> out;
    for (const auto& frame : written) {
      const auto f = cp::decode_frame(frame);
      if (!f || f->header.type != type) continue;
      if (auto m = cp::decode(*f, cp::Direction::to_platform)) out.push_back(m->message);
    }
    return out;
  }
  std::size_t data_of(std::uint16_t type) const {
    std::size_t n = 0;
    for (const auto& e : data) n += e.header.type == type;
    return n;
  }
  const sim::SimPlatform& platform() const { return loopback_.platform(); }
  void set_plugged(bool plugged) { loopback_.set_plugged(plugged); }

  std::vector<cp::Envelope> data;
  std::vector<std::vector<std::uint8_t>> written;

 private:
  rt::VirtualTime time_;
  sim::LoopbackClient loopback_;

 public:
  cp::ClientCore& client;
};

cp::SetVelocity velocity(double v, double w) {
  cp::SetVelocity m;
  m.translational = v;
  m.rotational = w;
  m.acceleration = 1.0;
  return m;
}

}  // namespace

TEST(ClearpathClientSim, CommandsAreAcknowledged) {
  VirtualLink link;
  std::optional<cp::CommandOutcome> outcome;
  link.client.send(velocity(0.5, 0), [&](const cp::CommandOutcome& o) { outcome = o; });
  link.run_for(20ms);
  ASSERT_TRUE(outcome);
  EXPECT_TRUE(outcome->ok());
  EXPECT_EQ(outcome->attempts, 1);
  EXPECT_EQ(link.client.counters().acks_ok, 1u);
}

TEST(ClearpathClientSim, RefusalsAreTypedAndNotRetried) {
  VirtualLink link;
  std::vector<cp::CommandOutcome> outcomes;
  auto record = [&](const cp::CommandOutcome& o) { outcomes.push_back(o); };
  link.client.send(velocity(0.5, 0), record);
  link.run_for(20ms);  // answered before the next velocity, which would otherwise replace it (latest wins)
  cp::SetVelocity bad = velocity(0.5, 0);
  bad.acceleration = -1;  // encodable, but out of the documented range
  link.client.send(bad, record);
  link.client.send(cp::SetAckermannOutput{}, record);  // differential platform
  link.client.send(cp::HomeJoint{}, record);
  cp::HomeJoint no_such_joint;
  no_such_joint.joint = 200;
  link.client.send(no_such_joint, record);
  link.run_for(50ms);
  ASSERT_EQ(outcomes.size(), 5u);
  EXPECT_TRUE(outcomes[0].ok());
  EXPECT_EQ(outcomes[1].error, cp::CommandError::refused);
  EXPECT_EQ(outcomes[1].result, cp::kAckOutOfRange);
  EXPECT_EQ(outcomes[1].attempts, 1);
  EXPECT_EQ(outcomes[2].result, cp::kAckTypeNotSupported);
  EXPECT_TRUE(outcomes[3].ok());
  EXPECT_EQ(outcomes[4].result, cp::kAckOutOfRange);
  EXPECT_EQ(link.client.counters().retries, 0u);
}

TEST(ClearpathClientSim, TimestampsStrictlyIncrease) {
  VirtualLink link;
  for (int i = 0; i < 20; ++i) link.client.send(cp::RequestEcho{});
  link.run_for(10ms);  // all in the same millisecond or two
  std::uint32_t last = 0;
  ASSERT_GT(link.written.size(), 20u);
  for (const auto& frame : link.written) {
    const auto decoded = cp::decode_frame(frame);
    ASSERT_TRUE(decoded);
    EXPECT_GT(decoded->header.timestamp, last);
    last = decoded->header.timestamp;
  }
}

TEST(ClearpathClientSim, RequestsAreAnsweredAndSubscriptionsKeepTheirRate) {
  VirtualLink link;
  link.client.send(cp::RequestPlatformName{});
  cp::RequestSystemStatus status;
  status.subscription = 10;
  link.client.subscribe(status);
  link.run_for(2s);
  ASSERT_EQ(link.data_of(0x8002), 1u);
  for (const auto& e : link.data)
    if (e.header.type == 0x8002) {
      EXPECT_EQ(e.message.get<cp::PlatformName>().name, "Clearpath1");
    }
  // One immediate reply, then 10 Hz for two seconds.
  EXPECT_GE(link.data_of(0x8004), 20u);
  EXPECT_LE(link.data_of(0x8004), 22u);
}

TEST(ClearpathClientSim, SubscriptionLimitsAnswerTheRightBits) {
  sim::PlatformConfig serial;
  serial.bandwidth_bytes_per_second = sim::kSerialBytesPerSecond;
  serial.max_subscriptions = 3;
  VirtualLink link(serial);
  std::vector<cp::CommandOutcome> outcomes;
  auto record = [&](const cp::CommandOutcome& o) { outcomes.push_back(o); };
  cp::RequestEncoders too_fast;
  too_fast.subscription = 500;
  link.client.subscribe(too_fast, record);
  link.run_for(20ms);  // answered before `c` (the same request type), which would otherwise replace it
  cp::RequestSystemStatus a;
  a.subscription = 100;
  cp::RequestPowerStatus b;
  b.subscription = 100;
  cp::RequestEncoders c;
  c.subscription = 100;
  cp::RequestRawEncoders d;
  d.subscription = 100;
  link.client.subscribe(a, record);
  link.client.subscribe(b, record);
  link.client.subscribe(c, record);
  link.client.subscribe(d, record);
  link.run_for(100ms);
  ASSERT_EQ(outcomes.size(), 5u);
  EXPECT_EQ(outcomes[0].error, cp::CommandError::refused);
  EXPECT_TRUE(outcomes[0].result & cp::kAckFrequencyTooHigh);
  // 33 + 20 + 27 bytes at 100 Hz fit in 80 % of 11520 B/s; a fourth does not, and is one type too many.
  EXPECT_TRUE(outcomes[1].ok());
  EXPECT_TRUE(outcomes[2].ok());
  EXPECT_TRUE(outcomes[3].ok());
  EXPECT_EQ(outcomes[4].error, cp::CommandError::refused);
  EXPECT_EQ(outcomes[4].result, cp::kAckNoBandwidth | cp::kAckTooManyTypes);
}

TEST(ClearpathClientSim, RetriesUnderInjectedCorruption) {
  sim::FaultConfig faults;
  faults.corrupt_rate = 0.25;
  faults.seed = 99;
  cp::ClientConfig client;
  client.max_attempts = 10;
  VirtualLink link({}, faults, client);
  int ok = 0, superseded = 0;
  bool last_ok = false;
  for (int i = 0; i < 50; ++i) {
    link.client.send(velocity(0.01 * i, 0), [&, i](const cp::CommandOutcome& o) {
      ok += o.ok();
      superseded += o.error == cp::CommandError::superseded;
      if (i == 49) last_ok = o.ok();
    });
    link.run_for(100ms);
  }
  link.run_for(5s);  // let the last retries finish
  // One still being retried when the next velocity is sent is not retried
  // again (latest wins); every other one gets through.
  EXPECT_EQ(ok + superseded, 50);
  EXPECT_TRUE(last_ok);
  EXPECT_EQ(link.client.counters().commands_superseded, static_cast<std::uint64_t>(superseded));
  EXPECT_NE(link.client.state(), cp::ConnectionState::down);
  EXPECT_GT(link.client.counters().retries, 0u);
  EXPECT_GT(link.client.counters().bad_checksum_acks + link.client.counters().timeouts, 0u);
}

TEST(ClearpathClientSim, PlatformStopsWhenCommandsCease) {
  VirtualLink link;
  for (int i = 0; i < 20; ++i) {  // renewed at 10 Hz for 2 s, as a driver under an OCU's stream would
    link.set_setpoint(velocity(0.8, 0));
    link.run_for(100ms);
  }
  EXPECT_NEAR(link.platform().vehicle().linear_speed(), 0.8, 1e-6);
  EXPECT_FALSE(link.platform().vehicle().watchdog_expired());
  link.client.clear_setpoint(cp::SetVelocity::kType);
  link.run_for(2s);
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);
  EXPECT_TRUE(link.platform().vehicle().safety_flags() & sim::kSafetyTimeout);
}

TEST(ClearpathClientSim, SetpointsAreLatestWinsAndResentToFeedTheWatchdog) {
  VirtualLink link;
  link.set_setpoint(velocity(0.1, 0));
  link.set_setpoint(velocity(0.2, 0));  // replaces the unsent 0.1
  link.run_for(480ms);
  EXPECT_EQ(link.client.counters().setpoints_replaced, 1u);
  const auto sent = link.written_of(cp::SetVelocity::kType);
  for (const auto& m : sent) EXPECT_DOUBLE_EQ(m.get<cp::SetVelocity>().translational, 0.2);
  // Resent every 50 ms (never less often than the 100 ms docs/clearpath-protocol.md requires): 0, 50, ... 450 ms.
  EXPECT_EQ(sent.size(), 10u);
}

// Safety: a setpoint nobody renews is not resent past its maximum age (0.5 s
// by default), so the platform's watchdog stops the platform.
TEST(ClearpathClientSim, AStreamNobodyRenewsEndsAtItsMaximumAge) {
  VirtualLink link;
  link.set_setpoint(velocity(0.8, 0));
  link.run_for(500ms);
  EXPECT_GT(link.platform().vehicle().linear_speed(), 0.3);
  const auto sent_by_max_age = link.written_of(cp::SetVelocity::kType).size();
  link.run_for(2s);
  EXPECT_EQ(link.written_of(cp::SetVelocity::kType).size(), sent_by_max_age);
  EXPECT_EQ(link.client.counters().setpoints_expired, 1u);
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);
  EXPECT_TRUE(link.platform().vehicle().safety_flags() & sim::kSafetyTimeout);
}

// Safety: a stop is one zero setpoint, written at once, and then silence.
TEST(ClearpathClientSim, AStopIsWrittenOnceAndEndsTheStream) {
  VirtualLink link;
  for (int i = 0; i < 5; ++i) {
    link.set_setpoint(velocity(0.8, 0.5));
    link.run_for(100ms);
  }
  const auto before = link.written_of(cp::SetVelocity::kType).size();
  link.stop_setpoint(velocity(0, 0));
  link.run_for(2ms);
  auto sent = link.written_of(cp::SetVelocity::kType);
  ASSERT_EQ(sent.size(), before + 1);
  EXPECT_EQ(sent.back().get<cp::SetVelocity>().translational, 0.0);
  EXPECT_EQ(sent.back().get<cp::SetVelocity>().rotational, 0.0);
  link.run_for(1s);
  EXPECT_EQ(link.written_of(cp::SetVelocity::kType).size(), before + 1);
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);
  // A new command starts a new stream.
  link.set_setpoint(velocity(0.3, 0));
  link.run_for(100ms);
  EXPECT_GT(link.written_of(cp::SetVelocity::kType).size(), before + 1);
}

// Safety: the link going down drops every setpoint; coming back re-arms none.
TEST(ClearpathClientSim, AReconnectNeverRearmsAnOldSetpoint) {
  VirtualLink link;
  std::vector<cp::ConnectionState> states;
  link.client.on_state([&](cp::ConnectionState s) { states.push_back(s); });
  cp::RequestSafetyStatus safety;
  safety.subscription = 20;
  link.client.subscribe(safety);
  link.set_setpoint(velocity(0.8, 0));
  link.run_for(100ms);
  link.set_plugged(false);
  for (int i = 0; i < 30 && link.client.state() != cp::ConnectionState::down; ++i) {
    link.set_setpoint(velocity(0.8, 0));  // renewed while the cable is out, until the link is declared down
    link.run_for(100ms);
  }
  ASSERT_EQ(link.client.state(), cp::ConnectionState::down);
  EXPECT_EQ(link.client.counters().setpoints_dropped, 1u);
  const auto before = link.written_of(cp::SetVelocity::kType).size();
  link.set_plugged(true);
  link.run_for(3s);
  ASSERT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_EQ(link.written_of(cp::SetVelocity::kType).size(), before);
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);
  // Each change was reported, in order: down, then connecting, then connected.
  ASSERT_GE(states.size(), 3u);
  EXPECT_EQ(states.front(), cp::ConnectionState::down);
  EXPECT_EQ(states.back(), cp::ConnectionState::connected);
}

TEST(ClearpathClientSim, SilenceMeansDownThenSubscriptionsComeBack) {
  VirtualLink link;
  cp::RequestSafetyStatus safety;
  safety.subscription = 20;
  link.client.subscribe(safety);
  link.run_for(500ms);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
  link.set_plugged(false);
  link.run_for(1500ms);
  // Silent for more than data_silence: down, and reopening fails while unplugged.
  EXPECT_EQ(link.client.state(), cp::ConnectionState::down);
  EXPECT_TRUE(link.client.wants_reconnect());
  EXPECT_EQ(link.client.counters().reconnects, 0u);

  link.set_plugged(true);
  const auto before = link.data_of(0x8010);
  link.run_for(3s);  // the next attempt comes within the (doubling) backoff
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_GE(link.data_of(0x8010) - before, 18u);
  EXPECT_EQ(link.client.counters().reconnects, 1u);
}

TEST(ClearpathClientSim, ManipulatorMountsAndGpio) {
  VirtualLink link;
  cp::SetAbsoluteJoints joints;
  joints.joints = {{0, 0.5}, {2, -1.0}};
  link.client.send(joints);
  cp::SetPanTiltZoom ptz;
  ptz.mount = 1;
  ptz.pan = 45;
  ptz.tilt = -10;
  ptz.zoom = 2;
  link.client.send(ptz);
  cp::SetGpioDirection dir;
  dir.mask = 0xFF;
  dir.direction = 0x0F;
  link.client.send(dir);
  cp::SetGpioOutput out;
  out.mask = 0xFF;
  out.value = 0x05;
  link.client.send(out);
  link.run_for(2s);
  const auto& v = link.platform().vehicle();
  EXPECT_NEAR(v.joints()[0].angle, 0.5, 1e-9);
  EXPECT_NEAR(v.joints()[2].angle, -1.0, 1e-9);
  EXPECT_NEAR(v.mounts()[1].pan, 45, 1e-9);
  EXPECT_EQ(v.gpio_value() & 0x0F, 0x05u);

  link.client.send(cp::HomeJoint{});  // joint 0 back to zero, then "homed"
  link.run_for(1s);
  EXPECT_EQ(v.joints()[0].homing, 1);
  link.client.send(cp::RequestJointHoming{});
  link.client.send(cp::RequestEndEffectorPose{});
  link.run_for(20ms);
  EXPECT_EQ(link.data_of(0x9013), 1u);
  EXPECT_EQ(link.data_of(0x9022), 1u);
}
