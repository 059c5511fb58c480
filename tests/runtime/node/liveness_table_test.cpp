#include "jaus/node/liveness_table.hpp"

#include <gtest/gtest.h>

#include "jaus/base/virtual_time.hpp"

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

const Address kNodeManager{1, 1, 1, 1};
const Address kDriver{1, 1, 33, 1};
const Address kCamera{1, 2, 37, 1};
const Address kOcu{2, 1, 40, 1};

std::vector<Address> addresses(const std::vector<LivenessEntry>& entries) {
  std::vector<Address> out;
  for (const auto& entry : entries) out.push_back(entry.address);
  return out;
}

TEST(LivenessTable, HearingAComponentMakesItsNodeAndSubsystemKnown) {
  LivenessTable table;
  const auto first = table.heard(kDriver, {});
  EXPECT_TRUE(first.recorded);
  EXPECT_TRUE(first.new_subsystem);
  EXPECT_TRUE(first.new_node);
  EXPECT_TRUE(first.new_component);
  const auto sibling = table.heard(kNodeManager, {});
  EXPECT_FALSE(sibling.new_subsystem);
  EXPECT_FALSE(sibling.new_node);
  EXPECT_TRUE(sibling.new_component);
  const auto again = table.heard(kDriver, {});
  EXPECT_TRUE(again.recorded);
  EXPECT_FALSE(again.new_component);

  EXPECT_EQ(addresses(table.known(LivenessLevel::subsystem)), (std::vector<Address>{{1, 0, 0, 0}}));
  EXPECT_EQ(addresses(table.known(LivenessLevel::node)), (std::vector<Address>{{1, 1, 0, 0}}));
  EXPECT_EQ(addresses(table.known(LivenessLevel::component)), (std::vector<Address>{kNodeManager, kDriver}));
  EXPECT_TRUE(table.find_component(kDriver));
  EXPECT_TRUE(table.find_node(kDriver));
  EXPECT_TRUE(table.find_subsystem(kDriver));
  EXPECT_FALSE(table.find_component(kCamera));
  EXPECT_FALSE(table.find_node(kCamera));
  EXPECT_FALSE(table.find_component(Address{1, 1, 0, 0}));  // a node key is no component
  EXPECT_EQ(table.size(), 4u);
}

TEST(LivenessTable, InvalidSourcesAreNotRecorded) {
  LivenessTable table;
  EXPECT_FALSE(table.heard(Address{1, 1, 0, 1}, {}).recorded);
  EXPECT_FALSE(table.heard(Address{1, 255, 1, 1}, {}).recorded);
  EXPECT_EQ(table.counters().invalid_sources, 2u);
  EXPECT_EQ(table.size(), 0u);
}

TEST(LivenessTable, ComponentsExpireAfter3sAndNodesAfter5sOfSilence) {
  rt::VirtualTime time;
  LivenessTable table;
  table.heard(kDriver, time.now());
  table.heard(kNodeManager, time.now());
  time.advance(2s);
  table.heard(kNodeManager, time.now());  // heartbeat: the node manager and its node live on
  EXPECT_EQ(table.next_deadline(), time.now() + 1s);

  time.advance(999ms);
  EXPECT_TRUE(table.expire(time.now()).empty());
  time.advance(1ms);  // t = 3 s: the driver has been silent for 3 s
  const auto gone = table.expire(time.now());
  ASSERT_EQ(gone.size(), 1u);
  EXPECT_EQ(gone[0].address, kDriver);
  EXPECT_EQ(gone[0].level, LivenessLevel::component);
  EXPECT_EQ(gone[0].first_heard, rt::TimePoint{});
  EXPECT_EQ(gone[0].last_heard, rt::TimePoint{});
  EXPECT_TRUE(table.find_component(kNodeManager));
  EXPECT_TRUE(table.find_node(kDriver));

  // Heartbeats every second keep the node manager, its node and subsystem.
  for (int i = 0; i < 10; ++i) {
    time.advance(1s);
    table.heard(kNodeManager, time.now());
    EXPECT_TRUE(table.expire(time.now()).empty());
  }
  EXPECT_EQ(table.size(), 3u);
  EXPECT_EQ(table.counters().expired, 1u);
}

TEST(LivenessTable, ASilentNodeTakesItsComponentsAlongBottomUp) {
  rt::VirtualTime time;
  LivenessTable table({.component_timeout = 10s, .node_timeout = 5s, .subsystem_timeout = 5s});
  table.heard(kDriver, time.now());
  table.heard(kCamera, time.now());
  table.heard(kOcu, time.now());
  time.advance(4s);
  table.heard(kOcu, time.now());
  time.advance(1s);  // t = 5 s: subsystem 1 is silent; the components' own 10 s have not run out
  const auto gone = table.expire(time.now());
  EXPECT_EQ(addresses(gone), (std::vector<Address>{kDriver, kCamera, {1, 1, 0, 0}, {1, 2, 0, 0}, {1, 0, 0, 0}}));
  EXPECT_EQ(addresses(table.known(LivenessLevel::component)), (std::vector<Address>{kOcu}));
  EXPECT_EQ(table.size(), 3u);
}

TEST(LivenessTable, ASubsystemHeardAgainAfterExpiryIsNewAgain) {
  rt::VirtualTime time;
  LivenessTable table;
  table.heard(kOcu, time.now());
  time.advance(5s);
  EXPECT_EQ(table.expire(time.now()).size(), 3u);
  EXPECT_FALSE(table.next_deadline());
  const auto back = table.heard(kOcu, time.now());
  EXPECT_TRUE(back.new_subsystem);
  EXPECT_EQ(table.find_subsystem(kOcu)->first_heard, time.now());
}

TEST(LivenessTable, WhenFullNewcomersWaitButKnownPeersAreRefreshed) {
  rt::VirtualTime time;
  LivenessTable table({.max_entries = 4});
  table.heard(kDriver, time.now());        // 3 entries
  table.heard(kNodeManager, time.now());   // 4
  const auto refused = table.heard(kOcu, time.now());
  EXPECT_FALSE(refused.recorded);
  EXPECT_FALSE(refused.new_subsystem);
  EXPECT_EQ(table.counters().rejected_full, 1u);
  // A new component on a known node needs one entry more: refused as well,
  // but its node and subsystem are still refreshed by it.
  time.advance(4s);
  EXPECT_FALSE(table.heard(Address{1, 1, 35, 1}, time.now()).recorded);
  EXPECT_EQ(table.find_node(kDriver)->last_heard, time.now());
  EXPECT_EQ(table.size(), 4u);
  // Once the silent components expire there is room again.
  EXPECT_EQ(table.expire(time.now()).size(), 2u);
  EXPECT_TRUE(table.heard(Address{1, 1, 35, 1}, time.now()).recorded);
}

}  // namespace
}  // namespace jaus::node
