// One emergency latch shared by several components (emergency_scope:
// vehicle), the local clear, and components that come and go while it holds.
#include <algorithm>
#include <iterator>
#include <random>
#include <vector>

#include "harness.hpp"

namespace jaus::test {
namespace {

using S = msg::PrimaryStatus;

const Address kArm{1, 1, 49, 1};

class SharedEmergencyTest : public ::testing::Test {
 protected:
  std::unique_ptr<TestDriver> make(const Address& at) {
    rt::ComponentConfig config;
    config.name = "component";
    config.address = at;
    auto c = std::make_unique<TestDriver>(
        config, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); }});
    c->share_emergency(latch);
    c->start();
    return c;
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  rt::EmergencyLatch latch;  // outlives the components, as the host's does
};

TEST_F(SharedEmergencyTest, SetEmergencyToOneHoldsEveryMemberAndItsHolderClearsItFromAny) {
  auto driver = make(kDriver);
  auto arm = make(kArm);
  deliver_to(*driver, time, kOcuA, msg::SetEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_EQ(arm->state(), S::emergency);
  EXPECT_FALSE(arm->stops.empty());  // the arm was brought to rest too
  deliver_to(*arm, time, kOcuB, msg::ClearEmergency{});  // holds nothing
  EXPECT_EQ(driver->state(), S::emergency);
  deliver_to(*arm, time, kOcuA, msg::ClearEmergency{});  // the holder, from the other member
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(arm->state(), S::ready);
}

TEST_F(SharedEmergencyTest, EachMemberReturnsToTheStateTheEmergencyInterrupted) {
  auto driver = make(kDriver);
  auto arm = make(kArm);
  deliver_to(*arm, time, kOcuA, msg::Standby{});
  deliver_to(*driver, time, kOcuA, msg::SetEmergency{});
  deliver_to(*driver, time, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(arm->state(), S::standby);
  EXPECT_EQ(driver->state(), S::ready);
}

// Issue 27, failure 4: a member shut down and destroyed while the latch holds;
// every later change reaches only the members alive (sanitizers watch this).
TEST_F(SharedEmergencyTest, AMemberShutDownAndDestroyedIsNeverCalledAgain) {
  auto driver = make(kDriver);
  auto arm = make(kArm);
  deliver_to(*arm, time, kOcuA, msg::RequestComponentControl{{255}});
  deliver_to(*arm, time, kOcuA, msg::Shutdown{});
  ASSERT_EQ(arm->state(), S::shutdown);
  latch.hold_local("e-stop pressed");
  EXPECT_EQ(arm->state(), S::shutdown);  // a shut-down component follows nothing
  arm.reset();
  latch.release_local("e-stop pressed");
  deliver_to(*driver, time, kOcuB, msg::SetEmergency{});
  deliver_to(*driver, time, kOcuB, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
}

TEST_F(SharedEmergencyTest, TheLocalClearReleasesHoldersGoneForGoodButNotTheHardware) {
  auto driver = make(kDriver);
  for (int i = 0; i < 70; ++i) deliver_to(*driver, time, Address{static_cast<std::uint8_t>(10 + i), 1, 40, 1}, msg::SetEmergency{});
  latch.hold_local("e-stop pressed");
  EXPECT_EQ(latch.clear_jaus_holders(), rt::EmergencyLatch::kMaxHolders + 1);  // the recorded, and the overflow
  EXPECT_EQ(driver->state(), S::emergency);  // the hardware's hold is the hardware's
  latch.release_local("e-stop pressed");
  EXPECT_EQ(driver->state(), S::ready);
}

// The host persists holds and restores them before the components start.
TEST_F(SharedEmergencyTest, HoldsRestoredBeforeStartPutEveryMemberInEmergencyAtOnce) {
  latch.restore({kOcuA}, false);
  auto driver = make(kDriver);
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_FALSE(driver->stops.empty());
  deliver_to(*driver, time, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
}

// An observer that adds a hold while a clear is going on (the host, waiting
// for the platform to confirm its emergency flag clear): the members never
// leave Emergency in between.
TEST_F(SharedEmergencyTest, AnObserversHoldIsInPlaceBeforeTheMembersFollow) {
  auto driver = make(kDriver);
  std::vector<S> seen;
  driver->on_state_change([&](S, S after) { seen.push_back(after); });
  bool was_held = false;
  latch.observe([&](const rt::EmergencyLatch& l) {
    if (was_held && !l.held_by_jaus()) latch.hold_local("flag not yet seen clear");
    was_held = l.held_by_jaus();
  });
  deliver_to(*driver, time, kOcuA, msg::SetEmergency{});
  deliver_to(*driver, time, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_EQ(seen, std::vector<S>{S::emergency});  // no Ready in between
  latch.release_local("flag not yet seen clear");
  EXPECT_EQ(driver->state(), S::ready);
}

// The node asks the latch, for every route a flood touches, whether it holds
// state for a node (a lookup, not a walk): the same answer as Address::covers
// over every holder, for IDs with 0 at any level.
TEST(EmergencyLatchHolders, HeldByAnyUnderAnswersAsCoversOverEveryHolder) {
  rt::EmergencyLatch latch;
  EXPECT_FALSE(latch.held_by_any_under(Address{3, 0, 0, 0}));
  const std::vector<Address> holders = {{3, 2, 40, 1}, {3, 4, 1, 1}, {5, 1, 40, 1}, {250, 1, 40, 1}};
  for (const auto& holder : holders) latch.set(holder);
  EXPECT_TRUE(latch.held_by_any_under(Address{3, 2, 0, 0}));
  EXPECT_TRUE(latch.held_by_any_under(Address{3, 0, 0, 0}));
  EXPECT_TRUE(latch.held_by_any_under(Address{3, 2, 40, 1}));
  EXPECT_FALSE(latch.held_by_any_under(Address{3, 2, 40, 2}));
  EXPECT_FALSE(latch.held_by_any_under(Address{3, 3, 0, 0}));
  EXPECT_FALSE(latch.held_by_any_under(Address{4, 0, 0, 0}));
  EXPECT_TRUE(latch.held_by_any_under(Address{5, 0, 9, 9}));  // 0 at the node: the whole subsystem
  std::mt19937 random(7);
  const std::uint8_t octets[] = {0, 1, 2, 3, 4, 5, 40, 250};
  auto octet = [&] { return octets[random() % std::size(octets)]; };
  for (int i = 0; i < 2000; ++i) {
    const Address where{octet(), octet(), octet(), octet()};
    const bool covered = std::any_of(holders.begin(), holders.end(), [&](const Address& h) { return where.covers(h); });
    EXPECT_EQ(latch.held_by_any_under(where), covered) << where.to_string();
  }
}

}  // namespace
}  // namespace jaus::test
