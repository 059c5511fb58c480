// The client's probe, under virtual time: a platform that no longer hears us
// while its data still flows (a one-way line) takes the link down within
// probe_timeout even while only setpoints (never acknowledged) are written;
// a platform that answers stays up, also on a line that corrupts 15 % of the
// frames each way; and the probe never delays a stop, the safety word or a
// command of its own type.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "lossy_link.hpp"
#include "jaus/clearpath/client_core.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"

namespace {

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
using namespace std::chrono_literals;
using jaus::test::LossyLink;

cp::SetVelocity velocity(double v) {
  cp::SetVelocity m;
  m.translational = v;
  m.acceleration = 1.0;
  return m;
}

cp::RequestSafetyStatus safety_at(std::uint16_t hz) {
  cp::RequestSafetyStatus r;
  r.subscription = hz;
  return r;
}

// Renews motion every 100 ms for `d`, as the bridge does while a controller drives.
void drive_for(LossyLink& link, rt::Duration d, double speed = 0.5) {
  for (rt::Duration done{}; done < d; done += 100ms) {
    link.client.set_setpoint(velocity(speed), link.now());
    link.run_for(100ms);
  }
}

TEST(ClearpathClientProbe, ADeafPlatformTakesTheLinkDownWithinTheProbeTimeoutWhileItsDataFlows) {
  LossyLink link;
  std::optional<rt::TimePoint> down_at;
  std::string first_reason;
  link.client.on_state([&](cp::ConnectionState s) {
    if (s != cp::ConnectionState::down || down_at) return;
    down_at = link.now();
    first_reason = link.client.down_reason();
  });
  link.client.subscribe(safety_at(20));
  drive_for(link, 1s);
  ASSERT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_GT(link.platform().vehicle().linear_speed(), 0.3);
  // Only setpoints go, so the probe asks: about ten a second, each answered.
  EXPECT_GE(link.client.counters().probes_sent, 5u);
  EXPECT_EQ(link.client.counters().probes_answered, link.client.counters().probes_sent);

  const auto deaf_at = link.now();
  link.set_deaf(true);
  const auto data_before = link.client.counters().data_received;
  drive_for(link, 3s);
  ASSERT_TRUE(down_at);
  // Within a probe period and the probe timeout (and not before the timeout).
  const cp::ClientConfig defaults;
  EXPECT_GE(*down_at - deaf_at, defaults.probe_timeout);
  EXPECT_LE(*down_at - deaf_at, defaults.probe_period + defaults.probe_timeout + 10ms);
  EXPECT_GT(link.client.counters().data_received, data_before);  // its data still flowed meanwhile
  EXPECT_GE(link.client.counters().unheard_downs, 1u);
  // The probe found it (while only setpoints went, nothing else was waiting for an ACK).
  EXPECT_NE(first_reason.find("the platform no longer hears us: no ACK to anything for 1000 ms"), std::string::npos)
      << first_reason;
  EXPECT_NE(first_reason.find("while its data still arrives"), std::string::npos) << first_reason;
  EXPECT_GE(link.client.counters().setpoints_dropped, 1u);
  // Still deaf: every reconnect goes down again, and its data is withheld, so
  // its owner never takes it for a live platform.
  const auto data_while_deaf = link.client.counters().data_received;
  link.run_for(5s);
  EXPECT_EQ(link.client.counters().data_received, data_while_deaf);
  EXPECT_GT(link.client.counters().data_withheld, 0u);
  EXPECT_GT(link.client.counters().unheard_downs, 1u);
  // Its own watchdog stopped it.
  EXPECT_TRUE(link.platform().vehicle().watchdog_expired());
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);

  // It hears again: the reconnect path brings the link back, data is
  // delivered again, and nothing moves until a new setpoint.
  link.set_deaf(false);
  link.run_for(5s);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_GT(link.client.counters().data_received, data_while_deaf);
  EXPECT_EQ(link.platform().vehicle().linear_speed(), 0.0);
  drive_for(link, 1s);
  EXPECT_GT(link.platform().vehicle().linear_speed(), 0.3);
}

TEST(ClearpathClientProbe, AnAnsweringPlatformStaysUpAndIsProbedOnlyWhileNothingElseIsAcknowledged) {
  LossyLink link;
  link.client.subscribe(safety_at(20));
  drive_for(link, 10s);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_EQ(link.client.counters().reconnects, 0u);
  EXPECT_EQ(link.client.counters().unheard_downs, 0u);
  // At most one a probe period (about 100 in 10 s), every one answered.
  const auto probes = link.client.counters().probes_sent;
  EXPECT_GE(probes, 80u);
  EXPECT_LE(probes, 101u);
  EXPECT_EQ(link.client.counters().probes_answered, probes);

  // Commands acknowledged at least once a probe period: no probe is needed.
  for (int i = 0; i < 40; ++i) {
    link.client.send(cp::RequestPlatformName{});
    link.run_for(50ms);
  }
  EXPECT_EQ(link.client.counters().probes_sent, probes);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
}

TEST(ClearpathClientProbe, ProbingCanBeTurnedOff) {
  LossyLink::Options options;
  options.client.probe_period = 0ms;
  LossyLink link(options);
  link.client.subscribe(safety_at(20));
  drive_for(link, 1s);
  link.set_deaf(true);
  drive_for(link, 3s);
  // Without the probe, only setpoints go: nothing notices (the platform's watchdog stops it).
  EXPECT_EQ(link.client.counters().probes_sent, 0u);
  EXPECT_EQ(link.client.counters().unheard_downs, 0u);
  EXPECT_NE(link.client.state(), cp::ConnectionState::down);
}

// 15 % of the frames each way get a flipped bit (as ClearpathPlatformUdp.
// CorruptedFramesAreNeverActedOn does on real processes): lost probes and
// ACKs, never ten in a row, so the link stays up.
TEST(ClearpathClientProbe, FifteenPercentCorruptionEachWayDoesNotTakeAWorkingLinkDown) {
  for (unsigned seed : {1u, 7u, 42u}) {
    LossyLink::Options options;
    options.faults.corrupt_rate = 0.15;
    options.faults.seed = seed;
    LossyLink link(options);
    link.client.subscribe(safety_at(20));
    drive_for(link, 60s);
    EXPECT_EQ(link.client.counters().unheard_downs, 0u) << "seed " << seed << ": " << link.client.down_reason();
    EXPECT_EQ(link.client.counters().reconnects, 0u) << "seed " << seed << ": " << link.client.down_reason();
    EXPECT_GT(link.client.counters().probes_sent, 500u) << "seed " << seed;  // probed all along (about 10 a second)
    EXPECT_GT(link.client.counters().probes_sent, link.client.counters().probes_answered) << "seed " << seed;
    EXPECT_GT(link.client.parser_counters().errors(), 0u) << "seed " << seed;  // corruption did happen
  }
}

// The client alone: frames taken one by one, ACKs made by hand.
std::vector<std::uint8_t> ack_frame(std::uint16_t type, std::uint32_t timestamp) {
  std::vector<std::uint8_t> frame;
  EXPECT_TRUE(cp::append_encoded(frame, cp::Envelope{{cp::kDefaultVersion, timestamp, 0, type}, cp::Ack{0}}));
  return frame;
}

cp::Frame decoded(const std::vector<std::uint8_t>& bytes) {
  auto frame = cp::decode_frame(bytes);
  EXPECT_TRUE(frame);
  return frame ? *frame : cp::Frame{};
}

TEST(ClearpathClientProbe, TheProbeGoesAfterAStopAndTheSafetyWord) {
  cp::ClientCore client;
  const rt::TimePoint t0{};
  client.reconnect_started(t0);
  client.on_connected(t0);
  while (!client.take_frame(t0).empty()) {}  // the cancels of a connection
  const auto t1 = t0 + 150ms;                // a probe is due
  client.stop_setpoint(velocity(0), t1);
  client.send(cp::SetSafetySystem{sim::kSafetyEmergencyStop});
  EXPECT_EQ(decoded(client.take_frame(t1)).header.type, cp::SetVelocity::kType);
  EXPECT_EQ(decoded(client.take_frame(t1)).header.type, cp::SetSafetySystem::kType);
  const auto probe = decoded(client.take_frame(t1));
  EXPECT_EQ(probe.header.type, cp::RequestEcho::kType);
  EXPECT_EQ(probe.header.flags & cp::kFlagSuppressAck, 0);  // it asks for an ACK
  EXPECT_TRUE(client.take_frame(t1).empty());
  EXPECT_EQ(client.counters().probes_sent, 1u);
}

TEST(ClearpathClientProbe, TheProbeTakesNoTurnOfTheApplicationsRequestOfItsType) {
  cp::ClientCore client;
  const rt::TimePoint t0{};
  client.reconnect_started(t0);
  client.on_connected(t0);
  while (!client.take_frame(t0).empty()) {}
  const auto t1 = t0 + 150ms;
  const auto probe = decoded(client.take_frame(t1));
  ASSERT_EQ(probe.header.type, cp::RequestEcho::kType);
  // The application's own Request Echo goes at once, though the probe awaits its ACK...
  std::vector<cp::CommandOutcome> outcomes;
  client.send(cp::RequestEcho{}, [&](const cp::CommandOutcome& o) { outcomes.push_back(o); });
  const auto own = decoded(client.take_frame(t1));
  ASSERT_EQ(own.header.type, cp::RequestEcho::kType);
  EXPECT_NE(own.header.timestamp, probe.header.timestamp);
  // ...and the probe's ACK does not finish it; its own does.
  client.on_bytes(ack_frame(cp::RequestEcho::kType, probe.header.timestamp), t1 + 5ms);
  EXPECT_TRUE(outcomes.empty());
  EXPECT_EQ(client.counters().probes_answered, 1u);
  client.on_bytes(ack_frame(cp::RequestEcho::kType, own.header.timestamp), t1 + 6ms);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].ok());
  EXPECT_EQ(client.counters().acks_unmatched, 0u);
}

}  // namespace
