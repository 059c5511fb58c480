// The client's queue of commands sent with ACK, under virtual time against the
// simulated platform with ACKs lost on the way back: one in flight per kind,
// latest wins, the safety word first, setpoints superseding commands of their
// type, a bounded queue, and subscriptions renewed after a reconnect.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <vector>

#include "lossy_link.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/client_core.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/fault_injector.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
using namespace std::chrono_literals;

namespace {

using LossyLink = jaus::test::LossyLink;

// Drops the ACK of the n-th frame of `type` written (0: the first).
std::function<bool(const cp::FrameHeader&)> drop_nth_ack_of(std::uint16_t type, int n) {
  return [type, n, seen = 0](const cp::FrameHeader& h) mutable { return h.type == type && seen++ == n; };
}

cp::SetVelocity velocity(double v) {
  cp::SetVelocity m;
  m.translational = v;
  m.acceleration = 1.0;
  return m;
}

std::uint16_t stop_bits(const sim::SimPlatform& p) { return p.vehicle().safety_flags() & sim::kSafetyEmergencyStop; }

}  // namespace

TEST(ClearpathClientQueue, SafetyWordLostAckNeverOvertakesTheNewerOne) {
  LossyLink link;
  link.drop_ack = drop_nth_ack_of(cp::SetSafetySystem::kType, 0);
  std::vector<cp::CommandOutcome> release, estop;
  // The dangerous order: a release whose ACK is lost, then an emergency stop.
  link.client.send(cp::SetSafetySystem{0}, [&](const cp::CommandOutcome& o) { release.push_back(o); });
  link.run_for(2ms);  // the release is written (and applied; its ACK is lost)
  link.client.send(cp::SetSafetySystem{sim::kSafetyEmergencyStop}, [&](const cp::CommandOutcome& o) { estop.push_back(o); });
  link.run_for(2s);

  ASSERT_EQ(release.size(), 1u);
  ASSERT_EQ(estop.size(), 1u);
  EXPECT_EQ(release[0].error, cp::CommandError::superseded);  // timed out with a newer word waiting: not retried
  EXPECT_TRUE(estop[0].ok());
  const auto words = link.written_of<cp::SetSafetySystem>();
  ASSERT_EQ(words.size(), 2u);
  EXPECT_EQ(words[0].flags, 0);
  EXPECT_EQ(words[1].flags, sim::kSafetyEmergencyStop);
  EXPECT_EQ(stop_bits(link.platform()), sim::kSafetyEmergencyStop);
  EXPECT_EQ(link.client.counters().commands_superseded, 1u);
}

TEST(ClearpathClientQueue, SafetyWordsUnderRandomAckLossEndWithTheLast) {
  // Words sent faster than the ACK timeout while a third of the ACKs are lost:
  // whatever is retried, no word is written after a newer one, and the last wins.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    LossyLink::Options options;
    options.faults.drop_rate = 0.3;
    options.faults.seed = seed;
    options.client.max_attempts = 20;  // losses alone never take the link down here
    LossyLink link(options);
    int finished = 0;
    for (std::uint16_t i = 1; i <= 30; ++i) {
      link.client.send(cp::SetSafetySystem{i}, [&](const cp::CommandOutcome&) { ++finished; });
      link.run_for(std::chrono::milliseconds(40 + 37 * (i % 5)));
    }
    link.run_for(10s);
    EXPECT_EQ(finished, 30) << "seed " << seed;
    const auto words = link.written_of<cp::SetSafetySystem>();
    ASSERT_FALSE(words.empty());
    for (std::size_t k = 1; k < words.size(); ++k)
      EXPECT_GE(words[k].flags, words[k - 1].flags) << "seed " << seed << ": an older word written after a newer one";
    EXPECT_EQ(words.back().flags, 30) << "seed " << seed;
    EXPECT_GT(link.acks_dropped, 0u);
  }
}

TEST(ClearpathClientQueue, GpioFloodStaysBoundedAndTheLastWins) {
  LossyLink::Options options;
  options.faults.drop_rate = 0.2;
  options.faults.seed = 7;
  options.period = 2ms;  // a slow link: one frame per 2 ms
  options.frames_per_period = 1;
  LossyLink link(options);
  link.client.send(cp::SetGpioDirection{0xFF, 0xFF});
  link.run_for(10ms);
  std::vector<int> calls(1000, 0);
  std::optional<cp::CommandOutcome> last;
  std::size_t most_waiting = 0;
  for (int i = 0; i < 1000; ++i) {
    const auto value = static_cast<std::uint32_t>(i & 0xFF);
    link.client.send(cp::SetGpioOutput{0xFF, value}, [&, i](const cp::CommandOutcome& o) {
      ++calls[static_cast<std::size_t>(i)];
      if (i == 999) last = o;
    });
    most_waiting = std::max(most_waiting, link.client.waiting_commands());
    if (i % 10 == 9) link.run_for(1ms);  // ten commands a millisecond, five times what the link writes
  }
  link.run_for(5s);

  EXPECT_LE(most_waiting, options.client.max_waiting_commands);
  EXPECT_LE(most_waiting, 3u);  // one kind: one in flight and one waiting (plus the direction)
  EXPECT_TRUE(std::all_of(calls.begin(), calls.end(), [](int n) { return n == 1; }));
  ASSERT_TRUE(last);
  EXPECT_TRUE(last->ok());
  EXPECT_EQ(link.platform().vehicle().gpio_value() & 0xFF, 999u & 0xFF);
  const auto& c = link.client.counters();
  EXPECT_GT(c.commands_superseded, 900u);
  EXPECT_EQ(c.commands_refused_full, 0u);
  EXPECT_EQ(link.client.waiting_commands(), 0u);
  // Never written after a newer one: the values written only move forward.
  const auto outputs = link.written_of<cp::SetGpioOutput>();
  EXPECT_LT(outputs.size(), 1000u);
  EXPECT_EQ(outputs.back().value, 999u & 0xFF);
}

TEST(ClearpathClientQueue, PartialCommandsReplaceOnlyWhatTheyCover) {
  LossyLink link;
  link.client.send(cp::SetGpioDirection{0x3, 0x3});
  link.run_for(5ms);
  std::vector<cp::CommandError> gpio, joints;
  link.client.send(cp::SetGpioOutput{0x1, 0x1}, [&](const auto& o) { gpio.push_back(o.error); });
  link.client.send(cp::SetGpioOutput{0x2, 0x2}, [&](const auto& o) { gpio.push_back(o.error); });
  link.client.send(cp::SetGpioOutput{0x1, 0x0}, [&](const auto& o) { gpio.push_back(o.error); });  // bit 0 only
  ASSERT_EQ(gpio.size(), 1u);
  EXPECT_EQ(gpio[0], cp::CommandError::superseded);  // the first: the third sets all it did
  cp::SetRelativeJoints a, b;
  a.joints = {{1, 0.1}};
  b.joints = {{1, 0.2}};
  link.client.send(a, [&](const auto& o) { joints.push_back(o.error); });
  link.client.send(b, [&](const auto& o) { joints.push_back(o.error); });  // relative moves add up: both go
  link.run_for(100ms);
  EXPECT_EQ(gpio, (std::vector{cp::CommandError::superseded, cp::CommandError::none, cp::CommandError::none}));
  EXPECT_EQ(joints, (std::vector{cp::CommandError::none, cp::CommandError::none}));
  EXPECT_EQ(link.platform().vehicle().gpio_value() & 0x3, 0x2u);
  EXPECT_EQ(link.written_of<cp::SetGpioOutput>().size(), 2u);
  EXPECT_EQ(link.written_of<cp::SetRelativeJoints>().size(), 2u);
  EXPECT_EQ(link.client.counters().commands_superseded, 1u);
}

TEST(ClearpathClientQueue, SafetyWordGoesBeforeSixtyQueuedCommands) {
  LossyLink::Options options;
  options.period = 5ms;  // one frame per 5 ms: sixty commands wait 300 ms
  options.frames_per_period = 1;
  LossyLink link(options);
  link.run_for(10ms);
  link.drop_ack = drop_nth_ack_of(cp::SetSafetySystem::kType, 0);
  for (int i = 0; i < 60; ++i) {
    cp::SetPanTiltZoom ptz;  // sixty kinds: nothing replaces anything
    ptz.mount = static_cast<std::uint8_t>(i);
    link.client.send(ptz);
  }
  link.run_for(20ms);
  const auto before = link.written.size();
  std::optional<cp::CommandOutcome> outcome;
  link.client.send(cp::SetSafetySystem{sim::kSafetyEmergencyStop}, [&](const cp::CommandOutcome& o) { outcome = o; });
  link.run_for(5ms);
  ASSERT_EQ(link.written.size(), before + 1);
  EXPECT_EQ(link.written.back().header.type, cp::SetSafetySystem::kType);  // the very next frame
  EXPECT_EQ(stop_bits(link.platform()), sim::kSafetyEmergencyStop);
  // Its ACK was lost: the retry goes before the commands still waiting too.
  link.run_for(cp::ClientConfig{}.ack_timeout + 5ms);
  ASSERT_TRUE(outcome);
  EXPECT_TRUE(outcome->ok());
  EXPECT_EQ(outcome->attempts, 2);
  EXPECT_GT(link.client.waiting_commands(), 1u);  // the mounts were still queued when the retry went out
  link.run_for(1s);
  EXPECT_EQ(link.written_of<cp::SetPanTiltZoom>().size(), 60u);
}

TEST(ClearpathClientQueue, StopAfterALostMotionAckIsTheLastMotion) {
  LossyLink link;
  link.drop_ack = drop_nth_ack_of(cp::SetVelocity::kType, 0);
  std::optional<cp::CommandOutcome> outcome;
  link.client.send(velocity(0.8), [&](const cp::CommandOutcome& o) { outcome = o; });
  link.run_for(2ms);  // written and applied, its ACK lost: it would be retried at 250 ms
  link.client.stop_setpoint(velocity(0), link.now());
  link.run_for(2s);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->error, cp::CommandError::superseded);
  const auto motions = link.written_of<cp::SetVelocity>();
  ASSERT_EQ(motions.size(), 2u);
  EXPECT_EQ(motions.back().translational, 0.0);
  EXPECT_EQ(link.platform().vehicle().velocity_setpoint()[0], 0.0);
}

TEST(ClearpathClientQueue, StopDropsAWaitingMotionCommand) {
  LossyLink link;
  std::optional<cp::CommandOutcome> outcome;
  link.client.send(velocity(0.8), [&](const cp::CommandOutcome& o) { outcome = o; });
  link.client.stop_setpoint(velocity(0), link.now());  // before anything is written
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->error, cp::CommandError::superseded);
  EXPECT_EQ(outcome->attempts, 0);
  link.run_for(1s);
  const auto motions = link.written_of<cp::SetVelocity>();
  ASSERT_EQ(motions.size(), 1u);
  EXPECT_EQ(motions[0].translational, 0.0);
}

TEST(ClearpathClientQueue, QueueFullIsRefusedAtOnceExceptTheSafetyWord) {
  LossyLink::Options options;
  options.client.max_waiting_commands = 4;
  LossyLink link(options);  // time does not run: nothing is written
  std::vector<cp::CommandError> errors;
  auto record = [&](const cp::CommandOutcome& o) { errors.push_back(o.error); };
  for (std::uint8_t j = 0; j < 4; ++j) link.client.send(cp::HomeJoint{j}, record);
  EXPECT_TRUE(errors.empty());
  link.client.send(cp::HomeJoint{4}, record);  // a fifth kind: refused at once
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], cp::CommandError::queue_full);
  link.client.send(cp::HomeJoint{2}, record);  // replaces a waiting one: accepted
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[1], cp::CommandError::superseded);
  cp::RequestSystemStatus status;
  status.subscription = 1;
  link.client.subscribe(status, record);  // refused, and not kept for a reconnect
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[2], cp::CommandError::queue_full);
  link.client.send(cp::SetSafetySystem{sim::kSafetyEmergencyStop}, record);  // always accepted
  EXPECT_EQ(errors.size(), 3u);
  EXPECT_EQ(link.client.waiting_commands(), 5u);
  EXPECT_EQ(link.client.counters().commands_refused_full, 2u);

  link.run_for(100ms);
  EXPECT_EQ(errors.size(), 8u);  // the four joints and the safety word answered
  EXPECT_EQ(stop_bits(link.platform()), sim::kSafetyEmergencyStop);
  EXPECT_EQ(link.written.front().header.type, cp::SetSafetySystem::kType);
  EXPECT_EQ(link.platform().subscription_count(), 0u);
}

TEST(ClearpathClientQueue, EverySubscriptionIsRenewedAfterAReconnectEvenWithAFullQueue) {
  LossyLink::Options options;
  options.client.max_waiting_commands = 8;
  LossyLink link(options);
  cp::RequestSystemStatus status;
  status.subscription = 10;
  cp::RequestPowerStatus power;
  power.subscription = 5;
  cp::RequestPanTiltZoom mount0, mount1;
  mount0.subscription = 5;
  mount1.mount = 1;
  mount1.subscription = 5;
  for (const cp::AnyMessage& r : {cp::AnyMessage{status}, cp::AnyMessage{power}, cp::AnyMessage{mount0}, cp::AnyMessage{mount1}})
    link.client.subscribe(r);
  link.run_for(500ms);
  EXPECT_EQ(link.platform().subscription_count(), 4u);

  link.set_plugged(false);  // silence: the link goes down, reopening fails
  link.run_for(1500ms);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::down);
  // Meanwhile the application fills the queue.
  int refused = 0;
  for (std::uint8_t j = 0; j < 20; ++j)
    link.client.send(cp::HomeJoint{j}, [&](const cp::CommandOutcome& o) { refused += o.error == cp::CommandError::queue_full; });
  EXPECT_EQ(refused, 12);
  const auto written_before = link.written.size();
  link.set_plugged(true);
  link.run_for(3s);

  EXPECT_NE(link.client.state(), cp::ConnectionState::down);
  EXPECT_GE(link.client.counters().reconnects, 1u);
  // Cancels first (one per request type, without ACK), then every subscription again.
  std::vector<cp::Frame> after(link.written.begin() + static_cast<std::ptrdiff_t>(written_before), link.written.end());
  std::size_t cancels = 0, first_request = after.size(), last_cancel = 0;
  std::vector<std::pair<std::uint16_t, std::uint16_t>> renewed;  // (type, subscription)
  for (std::size_t k = 0; k < after.size(); ++k) {
    const auto e = cp::decode(after[k], cp::Direction::to_platform);
    ASSERT_TRUE(e);
    std::optional<std::uint16_t> rate;
    cp::visit([&](const auto& m) { if constexpr (requires { m.subscription; }) rate = m.subscription; }, e->message);
    if (!rate || after[k].header.type == cp::RequestEcho::kType) continue;  // not a request, or the client's probe
    if (*rate == cp::kCancelSubscription) {
      ++cancels;
      last_cancel = k;
    } else {
      first_request = std::min(first_request, k);
      renewed.emplace_back(after[k].header.type, *rate);
    }
  }
  EXPECT_GT(cancels, 20u);
  EXPECT_LT(last_cancel, first_request);
  EXPECT_EQ(renewed.size(), 4u);
  EXPECT_EQ(std::count_if(renewed.begin(), renewed.end(), [](const auto& r) { return r.first == cp::RequestPanTiltZoom::kType; }),
            2);  // both mounts: kinds differ by mount
  EXPECT_EQ(link.platform().subscription_count(), 4u);
}

TEST(ClearpathClientQueue, UnsubscribeGoesEvenWhenTheQueueIsFull) {
  LossyLink::Options options;
  options.client.max_waiting_commands = 2;
  LossyLink link(options);
  cp::RequestSystemStatus status;
  status.subscription = 10;
  link.client.subscribe(status);
  link.run_for(100ms);
  ASSERT_EQ(link.platform().subscription_count(), 1u);
  link.set_plugged(false);  // nothing answered: two commands stay in flight
  link.client.send(cp::HomeJoint{0});
  link.client.send(cp::HomeJoint{1});
  link.run_for(5ms);
  ASSERT_EQ(link.client.waiting_commands(), 2u);
  link.client.unsubscribe(cp::RequestSystemStatus::kType);
  link.set_plugged(true);
  link.run_for(100ms);
  EXPECT_EQ(link.platform().subscription_count(), 0u);
}

TEST(ClearpathClientQueue, ASingleReplyDoesNotReplaceASubscription) {
  LossyLink link;
  cp::RequestSystemStatus every, once;
  every.subscription = 10;
  link.client.subscribe(every);
  link.client.send(once);  // the same kind, but it leaves the subscription alone
  link.run_for(100ms);
  EXPECT_EQ(link.platform().subscription_count(), 1u);
  EXPECT_EQ(link.client.counters().commands_superseded, 0u);
}

// What an unanswered command means. A request whose every attempt lost its
// ACK while the platform answers other commands (a noisy line) finishes
// no_ack on a live link, and a subscription is asked again later; with no
// ACK to anything since its first send, the platform does not hear us and
// the link goes down.
TEST(ClearpathClientQueue, ARequestUnansweredWhileOthersAreAnsweredLeavesTheLinkUpAndIsAskedAgain) {
  LossyLink link;
  int power_acks_seen = 0;
  link.drop_ack = [&](const cp::FrameHeader& h) {
    return h.type == cp::RequestPowerStatus::kType && power_acks_seen++ < 4;  // the ACKs of its four attempts
  };
  std::vector<cp::CommandOutcome> outcomes;
  cp::RequestPowerStatus power;
  power.subscription = 5;
  link.client.subscribe(power, [&](const cp::CommandOutcome& o) { outcomes.push_back(o); });
  for (int i = 0; i < 12; ++i) {  // meanwhile the platform answers other requests
    link.client.send(cp::RequestPlatformName{});
    link.run_for(100ms);
  }
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].error, cp::CommandError::no_ack);
  EXPECT_EQ(outcomes[0].attempts, 4);
  EXPECT_NE(link.client.state(), cp::ConnectionState::down);
  EXPECT_EQ(link.client.counters().reconnects, 0u);
  EXPECT_EQ(link.client.counters().commands_unanswered, 1u);
  EXPECT_EQ(link.client.counters().subscriptions_rerequested, 0u);  // not before resubscribe_delay

  link.run_for(1s);
  EXPECT_EQ(link.client.counters().subscriptions_rerequested, 1u);
  // Four attempts, then the fifth request (the connection's first frame of this type was its cancel).
  const auto requests = link.written_of<cp::RequestPowerStatus>();
  const auto at_five_hz = std::count_if(requests.begin(), requests.end(), [](const auto& r) { return r.subscription == 5; });
  EXPECT_EQ(at_five_hz, 5);
  EXPECT_EQ(requests.back().subscription, 5);
  EXPECT_EQ(link.client.waiting_commands(), 0u);  // the fifth was answered
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
  EXPECT_EQ(link.platform().subscription_count(), 1u);
}

TEST(ClearpathClientQueue, TheApplicationsOwnNewerRequestStandsInsteadOfTheClientsReRequest) {
  LossyLink link;
  int power_acks_seen = 0;
  link.drop_ack = [&](const cp::FrameHeader& h) {
    return h.type == cp::RequestPowerStatus::kType && power_acks_seen++ < 4;
  };
  cp::RequestPowerStatus power;
  power.subscription = 5;
  bool unanswered = false;
  link.client.subscribe(power, [&](const cp::CommandOutcome& o) {
    if (o.error != cp::CommandError::no_ack) return;
    unanswered = true;
    cp::RequestPowerStatus faster;  // the application asks again itself, at another rate
    faster.subscription = 10;
    link.client.subscribe(faster);
  });
  for (int i = 0; i < 25 && !unanswered; ++i) {
    link.client.send(cp::RequestPlatformName{});
    link.run_for(100ms);
  }
  ASSERT_TRUE(unanswered);
  link.run_for(2s);
  EXPECT_EQ(link.client.counters().subscriptions_rerequested, 0u);
  const auto requests = link.written_of<cp::RequestPowerStatus>();
  ASSERT_FALSE(requests.empty());
  EXPECT_EQ(requests.back().subscription, 10);
  EXPECT_EQ(std::count_if(requests.begin(), requests.end(), [](const auto& r) { return r.subscription == 10; }), 1);
  EXPECT_EQ(link.client.state(), cp::ConnectionState::connected);
}

TEST(ClearpathClientQueue, AGivenUpSubscriptionIsNotAskedAgain) {
  LossyLink link;
  link.drop_ack = [](const cp::FrameHeader& h) { return h.type == cp::RequestPowerStatus::kType; };
  cp::RequestPowerStatus power;
  power.subscription = 5;
  link.client.subscribe(power, [&](const cp::CommandOutcome& o) {
    if (o.error == cp::CommandError::no_ack) link.client.unsubscribe(cp::RequestPowerStatus::kType);
  });
  for (int i = 0; i < 30; ++i) {
    link.client.send(cp::RequestPlatformName{});
    link.run_for(100ms);
  }
  EXPECT_EQ(link.client.counters().subscriptions_rerequested, 0u);
  EXPECT_NE(link.client.state(), cp::ConnectionState::down);
  const auto requests = link.written_of<cp::RequestPowerStatus>();
  ASSERT_FALSE(requests.empty());
  EXPECT_EQ(requests.back().subscription, cp::kCancelSubscription);
}

TEST(ClearpathClientQueue, ACommandUnansweredWhileNothingIsAnsweredTakesTheLinkDown) {
  LossyLink link;
  link.drop_ack = [](const cp::FrameHeader&) { return true; };  // data flows, no ACK comes back
  cp::RequestSafetyStatus safety;
  safety.subscription = 20;
  std::vector<cp::CommandOutcome> outcomes;
  link.client.subscribe(safety, [&](const cp::CommandOutcome& o) { outcomes.push_back(o); });
  std::vector<cp::ConnectionState> states;
  link.client.on_state([&](cp::ConnectionState s) { states.push_back(s); });
  for (int i = 0; i < 12; ++i) {  // motion renewed meanwhile
    link.client.set_setpoint(velocity(0.5), link.now());
    link.run_for(100ms);
  }
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].error, cp::CommandError::no_ack);
  EXPECT_EQ(outcomes[0].attempts, 4);
  EXPECT_GT(link.client.counters().data_received, 0u);  // the request was applied, only the ACKs were lost
  // Down at the fourth timeout: the setpoint stream ended there, and a reconnect re-arms none.
  ASSERT_FALSE(states.empty());
  EXPECT_NE(std::find(states.begin(), states.end(), cp::ConnectionState::down), states.end());
  EXPECT_EQ(link.client.counters().setpoints_dropped, 1u);
  EXPECT_EQ(link.client.counters().subscriptions_rerequested, 0u);
}
