// A partition while driving: an in-process OCU in the `ocu` namespace drives
// veh1 (Set Wrench Effort at 10 Hz, ControlHold::send_while_held), then its
// link drops everything for 3 s. The simulator's true state shows the wheels
// commanded to zero well within the controller timeout (2 s here; the
// driver's command timeout, 0.5 s, comes first), and the controller timeout
// drops control. After healing, the same careless OCU keeps holding and
// would keep sending: nothing moves for 6 s, until the operator takes
// control and commands again.
#include "network_test.hpp"
#include "ocu_helpers.hpp"

namespace jaus::test::network {
namespace {

using Hold = jaus::ocu::ControlHold;

const jaus::Address kDriver{1, 1, 33, 1};
constexpr std::uint8_t kAuthority = 10;
constexpr auto kPartition = 3s;
// veh1's control.controller_timeout_s here: control goes once the controller
// has been silent for longer than this, so a partition must outlast it. With the default 3 s a 3 s partition is at the edge (the last
// effort before the cut is up to 100 ms older than the cut): 2 s leaves a
// clear second. A shorter outage is not a loss of control: an OCU that still
// repeats its command (the operator still holds the stick) drives on after
// healing (docs/safety.md, "Loss: what must arrive").
constexpr double kControllerTimeoutSeconds = 2.0;
constexpr double kStatusPeriodSeconds = 0.1;       // clearpath-sim --status-every

const char* end_text(Hold::End end) {
  switch (end) {
    case Hold::End::time_up: return "time_up";
    case Hold::End::interrupted: return "interrupted";
    case Hold::End::rejected: return "rejected";
    case Hold::End::silent: return "silent";
    case Hold::End::not_ready: return "not_ready";
    case Hold::End::unwatched: return "unwatched";
  }
  return "?";
}

class Partition : public NetworkTest {};

TEST_F(Partition, TheVehicleStopsAndStaysStoppedAfterHealingUntilTheOperatorCommandsAgain) {
  start_simulator();
  auto veh1 = veh1_spec(Finding::alone);
  veh1.more += "control: {controller_timeout_s: " + std::to_string(kControllerTimeoutSeconds) + "}\n";
  start_node(veh1);
  ASSERT_TRUE(wait_for_status("1.1.33.1", kVeh1, "ready", 30s)) << node(kVeh1).output();
  LinkLoss link(*lab, kOcu);
  auto* session = open_ocu({kVeh1});
  ASSERT_NE(session, nullptr);

  Hold careless(*session, kDriver, kAuthority);
  ASSERT_TRUE(take_control(careless));
  careless.send_while_held(wrench_effort(60), 100ms);
  ASSERT_EQ(careless.hold(5s), Hold::End::time_up);
  ASSERT_TRUE(ClearpathSimulator::moving(*simulator->state())) << simulator->state()->dump();

  const auto states_at_partition = simulator->states().size();
  auto cut = link.partition(true);
  ASSERT_TRUE(cut) << cut.error().message();
  const Hold::End during = careless.hold(kPartition);
  auto healed = link.partition(false);
  ASSERT_TRUE(healed) << healed.error().message();
  const auto states_at_healing = simulator->states().size();

  // The first state with both wheels commanded to zero after the cut.
  const auto states = simulator->states();
  std::optional<double> stopped_after_s;
  for (std::size_t i = states_at_partition; i < states.size() && !stopped_after_s; ++i)
    if (ClearpathSimulator::stopped(states[i]))
      stopped_after_s = kStatusPeriodSeconds * static_cast<double>(i - states_at_partition + 1);
  ASSERT_TRUE(stopped_after_s) << "still commanded to move at the end of the partition";
  EXPECT_LE(*stopped_after_s, kControllerTimeoutSeconds + 0.5);

  // The careless OCU holds on after healing: nothing may move.
  // (A hold that ends sooner leaves the session running for the rest of the 6 s.)
  std::optional<Hold::End> after;
  const auto healed_at = Clock::now();
  if (during == Hold::End::time_up) after = careless.hold(6s);
  const auto watched = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - healed_at);
  if (watched < 6s) session->run_for(6s - watched);
  const auto after_healing = simulator->states();
  std::size_t moving_after = 0;
  for (std::size_t i = states_at_healing; i < after_healing.size(); ++i)
    moving_after += ClearpathSimulator::stopped(after_healing[i]) ? 0 : 1;
  std::cout << "partition of " << kPartition.count() << " s: wheels commanded to zero " << *stopped_after_s
            << " s after the cut; the careless hold during the partition: " << end_text(during)
            << ", after healing: " << (after ? end_text(*after) : "(ended before)") << "; states not stopped after healing: " << moving_after
            << " of " << after_healing.size() - states_at_healing << "\n";
  EXPECT_EQ(moving_after, 0u) << "the vehicle moved again after healing without a new command";
  careless.release();

  // The operator commands again: it drives.
  Hold again(*session, kDriver, kAuthority);
  ASSERT_TRUE(take_control(again));
  again.send_while_held(wrench_effort(60), 100ms);
  again.hold(4s);
  EXPECT_TRUE(ClearpathSimulator::moving(*simulator->state())) << simulator->state()->dump();
  again.release();
}

}  // namespace
}  // namespace jaus::test::network
