// Control of veh1's primitive driver from the `ocu` namespace with 10 % of
// the UDP datagrams on the OCU's link dropped each way
// (JAUS_NETWORK_LOSS_PERCENT=30 reruns it at 30 %): an in-process OCU holds
// the driver for 60 s sending Set Wrench Effort at 10 Hz (ControlHold::
// send_while_held) and the simulator's true state shows the vehicle moving;
// then 100 Set Emergency sent with ocu::send_must_arrive as jausctl sends a
// stop (ACK requested, retransmitted at the pace of the measured round trip
// until ACKed, MustArrivePolicy::emergency()): each is ACKed, the driver is
// then in Emergency, and the ACK times' p99 is at most 200 ms.
#include <cmath>
#include <cstdlib>

#include "jaus/ocu/must_arrive.hpp"
#include "network_test.hpp"
#include "ocu_helpers.hpp"

namespace jaus::test::network {
namespace {

using jaus::msg::PrimaryStatus;
using Hold = jaus::ocu::ControlHold;

const jaus::Address kDriver{1, 1, 33, 1};
constexpr std::uint8_t kAuthority = 10;  // above the vector and waypoint drivers' 1
constexpr auto kHoldFor = 60s;
constexpr int kEmergencies = 100;
constexpr double kEmergencyAckP99BoundMs = 200;

int loss_percent() {
  const char* text = std::getenv("JAUS_NETWORK_LOSS_PERCENT");
  return text ? std::atoi(text) : 10;
}

class ControlUnderLoss : public NetworkTest {};

TEST_F(ControlUnderLoss, AHeldDriverDrivesFor60sAndSetEmergencyIsAckedWithin200msAtP99) {
  const int loss = loss_percent();
  start_simulator();
  start_node(veh1_spec(Finding::alone));
  ASSERT_TRUE(wait_for_status("1.1.33.1", kVeh1, "ready", 30s)) << node(kVeh1).output();
  LinkLoss link(*lab, kOcu);
  auto lossy = link.set_loss(loss);
  ASSERT_TRUE(lossy) << lossy.error().message();
  auto* session = open_ocu({kVeh1});
  ASSERT_NE(session, nullptr);

  // 60 s of driving: the hold must not end early, and the wheels turn.
  {
    Hold hold(*session, kDriver, kAuthority);
    ASSERT_TRUE(take_control(hold)) << "control of 1.1.33.1 not granted at " << loss << " % loss";
    hold.send_while_held(wrench_effort(60), 100ms);
    const HeldDrive drive = hold_and_watch(hold, *simulator, kHoldFor);
    EXPECT_EQ(drive.end, Hold::End::time_up) << "the hold ended after " << drive.held_s << " s";
    ASSERT_GT(drive.counted, 400u) << "the simulator printed too few states";
    std::cout << "control at " << loss << " % loss each way: held " << drive.held_s << " s, "
              << hold.sent_while_held() << " Set Wrench Effort sent, vehicle moving in " << drive.moving_percent()
              << " % of the simulator's states\n";
    EXPECT_GE(drive.moving_percent(), loss <= 10 ? 95.0 : 80.0);
  }

  // Stopped (the release stopped it) before the emergencies.
  ASSERT_TRUE(simulator->wait_for(ClearpathSimulator::stopped, 5s));
  std::vector<double> ack_ms;  // an unacknowledged try counts with the time it gave up after
  int retransmitted = 0;
  int unacknowledged = 0;
  int clears_repeated = 0;
  for (int i = 0; i < kEmergencies; ++i) {
    const auto r = jaus::ocu::send_must_arrive(*session, kDriver, jaus::msg::SetEmergency{{1}},
                                               jaus::priority::kSafetyCritical, jaus::ocu::MustArrivePolicy::emergency());
    ack_ms.push_back(milliseconds(r.elapsed));
    retransmitted += r.transmissions > 1 ? 1 : 0;
    const bool acknowledged = r.outcome == jaus::ocu::Arrival::acknowledged;
    unacknowledged += acknowledged ? 0 : 1;
    EXPECT_TRUE(acknowledged) << "Set Emergency " << i << ": " << jaus::ocu::to_string(r.outcome) << " after "
                              << r.transmissions << " transmissions";
    const auto status = primary_status(*session, kDriver);
    if (acknowledged) {
      ASSERT_EQ(status, PrimaryStatus::emergency) << "after Set Emergency " << i;
    }
    if (status != PrimaryStatus::emergency) continue;
    // As an operator does (docs/deployment.md): clear, and clear again if it
    // was not acknowledged (each try is given up after 3 s; a loaded machine
    // can stall the OCU's process for part of that).
    bool cleared = false;
    for (int attempt = 0; attempt < 3 && !cleared; ++attempt) {
      cleared = jaus::ocu::send_must_arrive(*session, kDriver, jaus::msg::ClearEmergency{{1}},
                                            jaus::priority::kSafetyCritical)
                    .outcome == jaus::ocu::Arrival::acknowledged;
      clears_repeated += cleared ? 0 : 1;
    }
    EXPECT_TRUE(cleared) << "Clear Emergency " << i << ": not acknowledged in three tries";
    ASSERT_TRUE(wait_for_primary_status(*session, kDriver, PrimaryStatus::ready, 5000ms)) << "after Clear Emergency " << i;
  }
  const double p50 = percentile(ack_ms, 50);
  const double p99 = percentile(ack_ms, 99);
  std::cout << "Set Emergency at " << loss << " % loss each way, " << kEmergencies << " tries: ACK p50 " << p50
            << " ms, p99 " << p99 << " ms, max " << percentile(ack_ms, 100) << " ms, " << retransmitted
            << " needed a retransmission, " << unacknowledged << " never acknowledged (in 10 s); "
            << clears_repeated << " Clear Emergency sent again after 3 s unacknowledged\n";
  RecordProperty("emergency_ack_p99_ms", std::to_string(p99));
  EXPECT_LE(p99, kEmergencyAckP99BoundMs);
}

}  // namespace
}  // namespace jaus::test::network
