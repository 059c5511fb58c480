// Control over a lossy link, under virtual time (issue 32): an OCU holds
// control of the primitive driver for 60 s at 10 % and at 30 % loss each
// way, streaming Set Wrench Effort at 10 Hz: it never loses control (the
// driver's controller stays the OCU every moment), the efforts arrive, and
// the release at the end is acknowledged. A plain hold, nothing streamed,
// keeps control through its keepalives; a lost request is sent again.
#include <cstdio>

#include "jaus/ocu/control_hold.hpp"
#include "lossy_fixture.hpp"

namespace jausctl::test {
namespace {

class LossyControlTest : public LossyOcuTest {
 protected:
  TargetOptions target_options() const override {
    TargetOptions options;
    options.primitive_driver = true;  // controller timeout 3 s, as jausd's default
    return options;
  }

  static ocu::PreparedMessage forward() {
    const auto message = ocu::prepare_message(
        ocu::Json::parse(R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":20}})"),
        jaus::wire::Dialect::ra);
    EXPECT_TRUE(message) << message.error().message();
    return *message;
  }

  bool controlled_by(const jaus::Address& ocu) const {
    const auto& c = target->driver().control().controller();
    return c && c->address == ocu;
  }

  // Every 10 ms from now until `until`: counts the moments the driver's
  // controller is not `ocu` (a control lost, however briefly).
  void watch_control(const jaus::Address& ocu, jaus::rt::TimePoint until) {
    if (time.now() >= until) return;
    if (!controlled_by(ocu)) ++moments_not_controlled;
    time.call_at(time.now() + 10ms, [this, ocu, until] { watch_control(ocu, until); });
  }

  struct Held {
    ocu::ControlHold::End end = ocu::ControlHold::End::interrupted;
    std::uint64_t sent = 0;
    std::uint64_t arrived = 0;
    std::uint64_t command_timeouts = 0;
    std::uint64_t keepalives = 0;
    ocu::ArrivalResult released;
  };

  // Requests control and holds it for 60 s at `loss` each way, streaming
  // efforts at 10 Hz when `stream`.
  Held hold_for_a_minute(double loss, std::uint64_t seed, bool stream) {
    Held h;
    auto ocu = open_lossy_ocu(7);
    EXPECT_TRUE(ocu);
    if (!ocu) return h;
    lose(loss, loss, seed);
    ocu::ControlHold control(*ocu, kDriver, 7);
    if (stream) control.send_while_held(forward(), 100ms);
    const auto requested = control.request(2s);
    EXPECT_EQ(requested.outcome, ocu::ControlHold::Outcome::granted)
        << ocu::control_request_text(requested, kDriver, 7, ocu->self());
    const auto arrived_before = target->efforts_arrived();
    watch_control(ocu->self(), time.now() + 60s);
    h.end = control.hold(60s);
    h.sent = control.sent_while_held();
    h.arrived = target->efforts_arrived() - arrived_before;
    h.command_timeouts = target->driver().driver_counters().command_timeouts;
    h.keepalives = control.keepalives_sent();
    h.released = control.release();
    EXPECT_TRUE(run_until([&] { return !target->driver().control().controller(); }));
    return h;
  }

  static void print(const char* what, const Held& h) {
    std::printf("%s: %llu efforts sent, %llu arrived, %llu command timeouts, %llu keepalives; release %s after %u "
                "transmissions\n",
                what, static_cast<unsigned long long>(h.sent), static_cast<unsigned long long>(h.arrived),
                static_cast<unsigned long long>(h.command_timeouts), static_cast<unsigned long long>(h.keepalives),
                std::string(ocu::to_string(h.released.outcome)).c_str(), h.released.transmissions);
  }

  int moments_not_controlled = 0;
};

TEST_F(LossyControlTest, AMinuteOfDrivingAtTenPercentLossEachWayKeepsControl) {
  const auto h = hold_for_a_minute(0.10, 60, true);
  print("10 % loss each way", h);
  EXPECT_EQ(h.end, ocu::ControlHold::End::time_up);
  EXPECT_EQ(moments_not_controlled, 0);
  EXPECT_GE(h.sent, 595u);                  // 10 Hz for 60 s
  EXPECT_GE(h.arrived * 100, h.sent * 85);  // about 90 % of them
  EXPECT_EQ(h.released.outcome, ocu::Arrival::acknowledged);
}

TEST_F(LossyControlTest, AMinuteOfDrivingAtThirtyPercentLossEachWayKeepsControl) {
  const auto h = hold_for_a_minute(0.30, 61, true);
  print("30 % loss each way", h);
  EXPECT_EQ(h.end, ocu::ControlHold::End::time_up);
  EXPECT_EQ(moments_not_controlled, 0);
  EXPECT_GE(h.sent, 595u);
  EXPECT_GE(h.arrived * 100, h.sent * 60);  // about 70 % of them
  EXPECT_EQ(h.released.outcome, ocu::Arrival::acknowledged);
}

TEST_F(LossyControlTest, APlainHoldAtThirtyPercentLossKeepsControlThroughItsKeepalives) {
  const auto h = hold_for_a_minute(0.30, 62, false);
  print("30 % loss each way, nothing streamed", h);
  EXPECT_EQ(h.end, ocu::ControlHold::End::time_up);
  EXPECT_EQ(moments_not_controlled, 0);
  EXPECT_GE(h.keepalives, 170u);  // every 250 ms, but where a control check (every 1 s) went
  EXPECT_EQ(h.released.outcome, ocu::Arrival::acknowledged);
}

TEST_F(LossyControlTest, WhileStreamingNoKeepaliveIsNeeded) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kDriver, 7);
  control.send_while_held(forward(), 100ms);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  EXPECT_EQ(control.hold(5s), ocu::ControlHold::End::time_up);
  EXPECT_GE(control.sent_while_held(), 45u);
  // At most while waiting for the first Ready report: the efforts go every 100 ms.
  EXPECT_LE(control.keepalives_sent(), 1u);
  control.release();
}

TEST_F(LossyControlTest, ALostRequestIsSentAgain) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kDriver, 7);
  cut_for(300ms);  // the request at 0 and its repeat at 250 ms are lost
  const auto start = time.now();
  const auto requested = control.request(1s);
  EXPECT_EQ(requested.outcome, ocu::ControlHold::Outcome::granted);
  EXPECT_EQ(time.now() - start, 2 * ocu::kQueryResendPeriod + 2 * kOneWay);
  EXPECT_TRUE(controlled_by(ocu->self()));
  control.release();
}

TEST_F(LossyControlTest, ALostReleaseIsSentAgainAfterAStopRequestToo) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kDriver, 7);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  time.call_at(time.now() + 1s, [&] { ocu->request_stop(); });
  EXPECT_EQ(control.hold(30s), ocu::ControlHold::End::interrupted);
  cut_for(120ms);  // lost at 0 and 100 ms; the third goes 200 ms later (the wait doubles)
  const auto released = control.release();
  EXPECT_EQ(released.outcome, ocu::Arrival::acknowledged);
  EXPECT_EQ(released.transmissions, 3u);
  EXPECT_FALSE(target->driver().control().controller());
}

TEST_F(LossyControlTest, TheKeepaliveEndsWithTheHold) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kDriver, 7);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  EXPECT_EQ(control.hold(2s), ocu::ControlHold::End::time_up);
  const auto keepalives = control.keepalives_sent();
  EXPECT_GE(keepalives, 7u);
  // Held no more (not released either): the component's controller timeout
  // ends it, since nothing keeps it alive now but the answers to its queries.
  jaus::testing::run_for(time, 2s);
  EXPECT_EQ(control.keepalives_sent(), keepalives);
}

// A partition longer than the controller timeout: the component drops the
// OCU and its Reject is lost. After healing the hold learns it from its
// control check instead of streaming refused commands on.
TEST_F(LossyControlTest, AControlDroppedWhoseRejectWasLostEndsTheHoldAfterHealing) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlHold control(*ocu, kDriver, 7);
  control.send_while_held(forward(), 100ms);
  ASSERT_EQ(control.request(1s).outcome, ocu::ControlHold::Outcome::granted);
  EXPECT_EQ(control.hold(2s), ocu::ControlHold::End::time_up);
  cut_for(4500ms);
  const auto cut_at = time.now();
  EXPECT_EQ(control.hold(30s), ocu::ControlHold::End::rejected);
  EXPECT_LE(time.now() - cut_at, 4500ms + ocu::ControlHold::kControlCheck + 2 * kOneWay);
  ASSERT_TRUE(control.control_elsewhere());
  EXPECT_FALSE(control.control_elsewhere()->controller.is_valid());  // nobody
  EXPECT_FALSE(target->driver().control().controller());
}

TEST_F(LossyControlTest, JausctlControlSaysSoWhenTheRejectWasLost) {
  auto ocu = open_lossy_ocu(7);
  ASSERT_TRUE(ocu);
  ocu::ControlOptions options;
  options.target = kDriver;
  options.authority = 7;
  options.hold_for = 30s;
  options.send = forward();
  once([&] { return target->efforts_arrived() >= 5; }, [&] { cut_for(4500ms); });
  EXPECT_EQ(ocu::run_control(*ocu, options, io()), kExitFailure);
  EXPECT_NE(err.str().find(": the component dropped it (its Reject Component Control never arrived); it has no "
                           "controller now\n"),
            std::string::npos)
      << err.str();
}

}  // namespace
}  // namespace jausctl::test
