// Control arbitration and controller liveness under virtual time.
#include "harness.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

// The full matrix: the component's own authority is 5.
//   state of control x requester (same / other) x authority (lower / equal / higher).
struct ControlCase {
  const char* name;
  std::optional<std::uint8_t> held_by_a;  // authority A holds control with, if controlled
  Address requester;
  std::uint8_t authority;
  std::uint8_t expected_response;         // Confirm Component Control response code
  Address expected_controller;            // or empty when none
  bool reject_to_a;                       // A receives Reject Component Control
};

const Address kNobody{};

class ControlMatrix : public ComponentTest, public ::testing::WithParamInterface<ControlCase> {};

TEST_P(ControlMatrix, Decides) {
  const auto& c = GetParam();
  if (c.held_by_a) {
    ASSERT_EQ(request_control(kOcuA, *c.held_by_a), 0);
  }
  const auto response = request_control(c.requester, c.authority);
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(*response, c.expected_response);
  const auto& controller = driver->control().controller();
  EXPECT_EQ(controller ? controller->address : kNobody, c.expected_controller);
  EXPECT_EQ(outbox.count<msg::RejectComponentControl>(), c.reject_to_a ? 1u : 0u);
  if (c.reject_to_a) {
    EXPECT_EQ(outbox.to<msg::RejectComponentControl>(kOcuA).size(), 1u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ControlMatrix,
    ::testing::Values(
        ControlCase{"uncontrolled_lower", std::nullopt, kOcuA, 4, 2, kNobody, false},
        ControlCase{"uncontrolled_equal", std::nullopt, kOcuA, 5, 0, kOcuA, false},
        ControlCase{"uncontrolled_higher", std::nullopt, kOcuA, 6, 0, kOcuA, false},
        ControlCase{"same_requester_lower", 10, kOcuA, 7, 0, kOcuA, false},
        ControlCase{"same_requester_equal", 10, kOcuA, 10, 0, kOcuA, false},
        ControlCase{"same_requester_higher", 10, kOcuA, 12, 0, kOcuA, false},
        ControlCase{"other_lower", 10, kOcuB, 9, 2, kOcuA, false},
        ControlCase{"other_equal", 10, kOcuB, 10, 2, kOcuA, false},
        ControlCase{"other_higher", 10, kOcuB, 11, 0, kOcuB, true}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST_F(ComponentTest, SameRequesterUpdatesItsAuthority) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  ASSERT_EQ(request_control(kOcuA, 7), 0);
  EXPECT_EQ(driver->control().controller()->authority, 7);
  EXPECT_EQ(request_control(kOcuB, 8), 0);  // now higher than A's updated authority
}

TEST_F(ComponentTest, RefusalCanBeSentAsReject) {
  make(5, 3s, /*reject=*/true);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  outbox.clear();
  deliver(kOcuB, msg::RequestComponentControl{{3}});
  EXPECT_TRUE(outbox.to<msg::ConfirmComponentControl>(kOcuB).empty());
  EXPECT_EQ(outbox.to<msg::RejectComponentControl>(kOcuB).size(), 1u);
}

TEST_F(ComponentTest, ReleaseByTheControllerReleasesAndStops) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  drive(kOcuA, 40);
  ASSERT_TRUE(driver->moving);
  deliver(kOcuB, msg::ReleaseComponentControl{});  // not the controller: ignored
  EXPECT_TRUE(driver->control().is_controller(kOcuA));
  EXPECT_TRUE(logged("Release Component Control from 3.1.40.1 ignored"));
  EXPECT_TRUE(driver->moving);
  deliver(kOcuA, msg::ReleaseComponentControl{});
  EXPECT_FALSE(driver->control().controller());
  EXPECT_FALSE(driver->moving);
}

TEST_F(ComponentTest, TakeoverStopsWhatTheOldControllerCommanded) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  drive(kOcuA, 40);
  ASSERT_EQ(request_control(kOcuB, 20), 0);
  EXPECT_FALSE(driver->moving);
  drive(kOcuA, 40);  // the displaced controller can no longer command
  EXPECT_EQ(driver->executed.size(), 1u);
  drive(kOcuB, 10);
  EXPECT_EQ(driver->executed.size(), 2u);
}

TEST_F(ComponentTest, NoCommandFromANonControllerEverExecutes) {
  const Address others[] = {kOcuB, kOcuC, Address{2, 1, 40, 2}, Address{255, 255, 255, 255}};
  // Uncontrolled, controlled by A, after A released: only A while controlling executes.
  for (const auto& other : others) drive(other, 10);
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  for (const auto& other : others) drive(other, 10);
  for (const auto& other : others) deliver(other, msg::Shutdown{});
  for (const auto& other : others) deliver(other, msg::Reset{});
  for (const auto& other : others) deliver(other, msg::SetComponentAuthority{{200}});
  drive(kOcuA, 10);
  deliver(kOcuA, msg::ReleaseComponentControl{});
  for (const auto& other : others) drive(other, 10);
  drive(kOcuA, 10);
  EXPECT_EQ(driver->executed.size(), 1u);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_EQ(driver->control().own_authority(), 5);
  EXPECT_EQ(driver->counters().refused_not_controller, 4u * 6u + 1u);
  // Logs are rate limited: one line per reason and window, not one per command.
  std::size_t refusal_lines = 0;
  for (const auto& l : logs) refusal_lines += l.find("not executed") != std::string::npos;
  EXPECT_LE(refusal_lines, 2u);
}

// A flood of forged senders is one reason: its first line, then one summary
// line per 10 s window with the count left out, also once the flood stops;
// the component keeps no table of senders to grow.
TEST_F(ComponentTest, RefusalsFromAFloodOfSendersAreOneLineAWindowWithACount) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  logs.clear();
  auto forged = [](int i) {
    return Address{static_cast<std::uint8_t>(10 + i % 200), static_cast<std::uint8_t>(1 + (i / 200) % 250), 40, 1};
  };
  auto refusal_lines = [&] {
    std::vector<std::string> lines;
    for (const auto& l : logs)
      if (l.find("not executed") != std::string::npos) lines.push_back(l);
    return lines;
  };
  for (int second = 0; second < 3; ++second) {  // 3,000 in the first 3 s of a window
    for (int i = 0; i < 1000; ++i) drive(forged(i), 10);
    time.advance(std::chrono::seconds(1));
  }
  EXPECT_EQ(refusal_lines().size(), 1u);
  time.advance(std::chrono::seconds(7));  // the window ends: its count is written although the flood paused
  auto lines = refusal_lines();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].find("more like this"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("left out in the last 10 s: 2999 x commands from a non-controller not executed"),
            std::string::npos)
      << lines[1];
  for (int second = 0; second < 10; ++second) {  // the flood goes on: one summary for the next window
    for (int i = 0; i < 100; ++i) drive(forged(i), 10);
    time.advance(std::chrono::seconds(1));
  }
  lines = refusal_lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[2].find("left out in the last 10 s: 1000 x commands from a non-controller"), std::string::npos)
      << lines[2];
  time.advance(std::chrono::seconds(30));  // quiet: nothing more to say
  EXPECT_EQ(refusal_lines().size(), 3u);
  drive(forged(7), 10);  // much later: a line of its own again
  lines = refusal_lines();
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[3].find("more like this"), std::string::npos) << lines[3];
  EXPECT_EQ(driver->counters().refused_not_controller, 4001u);
}

TEST_F(ComponentTest, SilentControllerLosesControlAndThePlatformStops) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  drive(kOcuA, 60);
  ASSERT_TRUE(driver->moving);
  outbox.clear();
  time.advance(2900ms);
  EXPECT_TRUE(driver->control().is_controller(kOcuA));
  // It asked the controller for a sign of life meanwhile (every timeout / 3).
  EXPECT_GE(outbox.to<msg::QueryComponentStatus>(kOcuA).size(), 2u);
  time.advance(1100ms);
  EXPECT_FALSE(driver->control().controller());
  EXPECT_FALSE(driver->moving);
  EXPECT_EQ(outbox.to<msg::RejectComponentControl>(kOcuA).size(), 1u);
  EXPECT_TRUE(logged("controller silent for"));
  drive(kOcuA, 60);
  EXPECT_EQ(driver->executed.size(), 1u);
}

// Control goes as soon as the controller has been silent for longer than
// controller_timeout (3 s), not at the next of its checks (every timeout / 3),
// which could be up to a second later (tests/network's partition on real
// processes).
TEST_F(ComponentTest, ControlEndsAsSoonAsTheSilenceOutlastsTheTimeout) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  time.advance(700ms);
  drive(kOcuA, 60);  // heard at 0.7 s: off the checks' 1 s grid
  ASSERT_TRUE(driver->control().is_controller(kOcuA));
  time.advance(3000ms);  // exactly the timeout: not longer
  EXPECT_TRUE(driver->control().is_controller(kOcuA));
  time.advance(1ms);
  EXPECT_FALSE(driver->control().controller());
  EXPECT_FALSE(driver->moving);
}

TEST_F(ComponentTest, AnsweringControllerKeepsControl) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  for (int i = 0; i < 30; ++i) {
    time.advance(900ms);
    // The controller answers the liveness query (any message counts).
    msg::ReportComponentStatus alive;
    deliver(kOcuA, alive);
  }
  EXPECT_TRUE(driver->control().is_controller(kOcuA));
}

TEST_F(ComponentTest, ZeroTimeoutDisablesTheLivenessCheck) {
  make(5, rt::Duration::zero());
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  outbox.clear();
  time.advance(std::chrono::minutes(10));
  EXPECT_TRUE(driver->control().is_controller(kOcuA));
  EXPECT_EQ(outbox.count<msg::QueryComponentStatus>(), 0u);
  EXPECT_EQ(time.pending(), 0u);
}

}  // namespace
}  // namespace jaus::test
