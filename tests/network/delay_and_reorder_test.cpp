// The in-process OCU reaches veh1 only through a delay line (delay_line.hpp)
// in the `ocu` namespace: every datagram waits 40 ms + uniform(0, 80) ms each
// way, so datagrams sent less than 80 ms apart overtake each other, and 5 %
// are dropped each way. Over it: a 15 s control hold with effort at 10 Hz;
// 30 rounds of Set and Clear Emergency sent to arrive; and the safety case of
// reordering: a Resume and then a Standby, each ACKed, must end in Standby
// even when retransmitted copies of the Resume arrive after the Standby (the
// node drops a copy of a command it already handled).
#include <cstdlib>

#include "delay_line_test.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/transport/framing.hpp"
#include "network_test.hpp"
#include "ocu_helpers.hpp"

namespace jaus::test::network {
namespace {

using jaus::msg::PrimaryStatus;
using Hold = jaus::ocu::ControlHold;

const jaus::Address kDriver{1, 1, 33, 1};
constexpr std::uint8_t kAuthority = 10;  // above the vector driver's 1
constexpr auto kHoldFor = 15s;
constexpr int kEmergencyRounds = 30;
constexpr auto kManyCopies = jaus::ocu::MustArrivePolicy::every(50ms, 10);
// Rounds of Resume then Standby until this many copies of a Resume reached
// veh1 after the later Standby (about one round in four makes one), at most
// kResumeStandbyRounds.
constexpr int kLateResumesWanted = 3;
constexpr int kResumeStandbyRounds = 40;
// Longer than the longest a datagram waits in the line (40 + 80 ms) with
// margin: copies still on their way by then are late copies.
constexpr auto kLateCopiesLand = 300ms;

class DelayAndReorder : public ThroughDelayLine {
 protected:
  // veh1 and the simulator, the delay line, and an OCU whose only peer is the line.
  void SetUp() override {
    NetworkTest::SetUp();
    if (IsSkipped() || HasFailure()) return;
    start_simulator();
    start_node(veh1_spec(Finding::alone));
    ASSERT_TRUE(wait_for_status("1.1.33.1", kVeh1, "ready", 30s)) << node(kVeh1).output();
    DelayLineOptions options;
    options.base = 40ms;
    options.jitter = 80ms;
    options.drop_probability = 0.05;
    options.seed = static_cast<std::uint32_t>(::getpid());
    options.on_delivery_to_vehicle = [this](std::span<const std::uint8_t> datagram, auto) { note_delivery(datagram); };
    start_line(std::move(options));
    if (HasFatalFailure()) return;
    open_ocu_through_line();
  }

  void print_line(const std::string& after) const {
    const auto c = line->counters();
    std::cout << "delay line after " << after << ": " << c.received << " datagrams received, " << c.forwarded
              << " forwarded, " << c.dropped << " dropped, " << c.reordered << " reordered\n";
  }
  // Lines of veh1's jausd log at level error.
  std::vector<std::string> veh1_errors() {
    std::vector<std::string> errors;
    std::istringstream lines(node(kVeh1).output());
    for (std::string line_text; std::getline(lines, line_text);)
      if (line_text.find("[error]") != std::string::npos) errors.push_back(line_text);
    return errors;
  }
  // Sent to arrive, up to three times. By default at a fixed 50 ms pace, 10
  // times in 0.5 s (at 5 % loss each way and up to 240 ms of round trip,
  // rarely all of them lost or late): copies overtaking each other in the
  // line are what these tests are about. A stop goes as jausctl sends it, at
  // the pace of the measured round trip (MustArrivePolicy::emergency()).
  jaus::ocu::ArrivalResult send_until_acked(const auto& message, std::vector<double>& ack_ms,
                                            jaus::ocu::MustArrivePolicy policy = kManyCopies) {
    jaus::ocu::ArrivalResult r;
    for (int i = 0; i < 3; ++i) {
      r = jaus::ocu::send_must_arrive(*ocu, kDriver, message, jaus::priority::kSafetyCritical, policy);
      ack_ms.push_back(milliseconds(r.elapsed));
      if (r.outcome == jaus::ocu::Arrival::acknowledged) break;
    }
    return r;
  }

  // On the line's thread: a Resume delivered after a Standby sent later
  // (higher sequence number) was delivered is a late copy the node must drop.
  void note_delivery(std::span<const std::uint8_t> datagram) {
    const auto message = jaus::transport::unframe(datagram);
    if (!message) return;
    const jaus::Header& h = message->packet.header;
    if (h.command_code == jaus::msg::Standby::code)
      latest_standby_delivered = std::max<int>(latest_standby_delivered, h.sequence);
    else if (h.command_code == jaus::msg::Resume::code && h.sequence < latest_standby_delivered)
      ++resumes_delivered_after_a_later_standby;
  }

  std::atomic<int> latest_standby_delivered{-1};
  std::atomic<int> resumes_delivered_after_a_later_standby{0};
};

TEST_F(DelayAndReorder, AHoldDrivesFor15sWithoutSpuriousLossOfControl) {
  Hold hold(*ocu, kDriver, kAuthority);
  ASSERT_TRUE(take_control(hold)) << "control of 1.1.33.1 not granted through the delay line";
  hold.send_while_held(wrench_effort(60), 100ms);
  const HeldDrive drive = hold_and_watch(hold, *simulator, kHoldFor);
  EXPECT_EQ(drive.end, Hold::End::time_up) << "the hold ended after " << drive.held_s << " s";
  ASSERT_GT(drive.counted, 80u) << "the simulator printed too few states";
  std::cout << "control through 40+0..80 ms each way, 5 % loss: held " << drive.held_s << " s, "
            << hold.sent_while_held() << " Set Wrench Effort sent, vehicle moving in " << drive.moving_percent()
            << " % of the simulator's states\n";
  print_line("the hold");
  EXPECT_GE(drive.moving_percent(), 90.0);
}

TEST_F(DelayAndReorder, SetAndClearEmergency30TimesEndsOutOfEmergency) {
  std::vector<double> set_ms;
  std::vector<double> clear_ms;
  for (int i = 0; i < kEmergencyRounds; ++i) {
    const auto set = send_until_acked(jaus::msg::SetEmergency{{1}}, set_ms, jaus::ocu::MustArrivePolicy::emergency());
    ASSERT_EQ(set.outcome, jaus::ocu::Arrival::acknowledged) << "Set Emergency " << i;
    // Set Emergency is never filtered as a copy (stopping twice is safe): its
    // retransmissions still in the line must land before the Clear.
    ocu->run_for(kLateCopiesLand);
    ASSERT_EQ(primary_status(*ocu, kDriver), PrimaryStatus::emergency) << "after Set Emergency " << i;
    const auto clear = send_until_acked(jaus::msg::ClearEmergency{{1}}, clear_ms);
    ASSERT_EQ(clear.outcome, jaus::ocu::Arrival::acknowledged) << "Clear Emergency " << i;
    ASSERT_TRUE(wait_for_primary_status(*ocu, kDriver, PrimaryStatus::ready, 5000ms)) << "after Clear Emergency " << i;
  }
  ocu->run_for(1s);  // late copies of anything
  EXPECT_EQ(primary_status(*ocu, kDriver), PrimaryStatus::ready);
  EXPECT_TRUE(veh1_errors().empty()) << "veh1 logged errors:\n" << node(kVeh1).output();
  std::cout << "Set Emergency through the delay line, " << set_ms.size() << " sends: ACK p50 " << percentile(set_ms, 50)
            << " ms, p99 " << percentile(set_ms, 99) << " ms; Clear Emergency, " << clear_ms.size() << " sends: ACK p50 "
            << percentile(clear_ms, 50) << " ms, p99 " << percentile(clear_ms, 99) << " ms\n";
  print_line("the emergencies");
  EXPECT_GT(line->counters().reordered, 0u) << "the delay line never reordered: the test proved nothing";
}

TEST_F(DelayAndReorder, AResumeRetransmittedPastALaterStandbyDoesNotAct) {
  Hold hold(*ocu, kDriver, kAuthority);
  ASSERT_TRUE(take_control(hold)) << "control of 1.1.33.1 not granted through the delay line";
  std::vector<double> resume_ms;
  std::vector<double> standby_ms;
  int resume_retransmitted = 0;
  // Once slowly: Resume does make the driver Ready, Standby takes it back.
  ASSERT_EQ(send_until_acked(jaus::msg::Resume{}, resume_ms).outcome, jaus::ocu::Arrival::acknowledged);
  ASSERT_TRUE(wait_for_primary_status(*ocu, kDriver, PrimaryStatus::ready, 3000ms));
  ASSERT_EQ(send_until_acked(jaus::msg::Standby{}, standby_ms).outcome, jaus::ocu::Arrival::acknowledged);
  ASSERT_TRUE(wait_for_primary_status(*ocu, kDriver, PrimaryStatus::standby, 3000ms));
  int rounds = 0;
  for (; rounds < kResumeStandbyRounds && resumes_delivered_after_a_later_standby < kLateResumesWanted; ++rounds) {
    const int i = rounds;
    const auto resume = send_until_acked(jaus::msg::Resume{}, resume_ms);
    ASSERT_EQ(resume.outcome, jaus::ocu::Arrival::acknowledged) << "Resume " << i;
    resume_retransmitted += resume.transmissions > 1 ? 1 : 0;
    // At once, while copies of the Resume may still be in the line.
    const auto standby = send_until_acked(jaus::msg::Standby{}, standby_ms);
    ASSERT_EQ(standby.outcome, jaus::ocu::Arrival::acknowledged) << "Standby " << i;
    const Hold::End end = hold.hold(kLateCopiesLand);  // keeps control while late copies land
    ASSERT_EQ(end, Hold::End::time_up) << "control lost in round " << i;
    ASSERT_EQ(primary_status(*ocu, kDriver), PrimaryStatus::standby) << "round " << i << ": a late Resume acted";
  }
  hold.release();
  std::cout << "Resume then Standby, " << rounds << " rounds: Resume ACK p50 " << percentile(resume_ms, 50)
            << " ms, p99 " << percentile(resume_ms, 99) << " ms (" << resume_retransmitted
            << " retransmitted); Standby ACK p50 " << percentile(standby_ms, 50) << " ms, p99 "
            << percentile(standby_ms, 99) << " ms; " << resumes_delivered_after_a_later_standby
            << " copies of a Resume reached veh1 after a later Standby (and did not act)\n";
  print_line("Resume/Standby");
}

}  // namespace
}  // namespace jaus::test::network
