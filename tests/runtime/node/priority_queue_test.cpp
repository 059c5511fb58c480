#include "jaus/node/priority_queue.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace jaus::node {
namespace {

std::vector<std::string> drain(PriorityQueue<std::string>& queue) {
  std::vector<std::string> out;
  while (auto item = queue.pop()) out.push_back(*item);
  return out;
}

TEST(PriorityQueue, SafetyCriticalFirstThenHigherFirstThenFifo) {
  PriorityQueue<std::string> queue;
  queue.push(6, "report a");
  queue.push(11, "high");
  queue.push(6, "report b");
  queue.push(12, "stop");
  queue.push(0, "low");
  queue.push(15, "emergency");
  queue.push(12, "stop again");
  EXPECT_EQ(queue.next_priority(), 15);
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"emergency", "stop", "stop again", "high", "report a",
                                                     "report b", "low"}));
  EXPECT_TRUE(queue.empty());
  EXPECT_FALSE(queue.pop());
  EXPECT_FALSE(queue.next_priority());
}

TEST(PriorityQueue, SafetyCriticalOvertakesEverythingAlreadyQueued) {
  PriorityQueue<std::string> queue;
  for (int i = 0; i < 5; ++i) queue.push(11, "high " + std::to_string(i));
  queue.push(12, "stop");
  EXPECT_EQ(queue.pop(), "stop");
}

TEST(PriorityQueue, PrioritiesAbove15CountAs15) {
  PriorityQueue<std::string> queue;
  queue.push(15, "first");
  queue.push(200, "second");
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"first", "second"}));
}

TEST(PriorityQueue, WhenFullTheOldestOfTheLowestPriorityMakesRoom) {
  PriorityQueue<std::string> queue({.capacity = 3});
  queue.push(6, "old report");
  queue.push(6, "new report");
  queue.push(11, "high");
  const auto result = queue.push(12, "stop");
  EXPECT_TRUE(result.accepted);
  ASSERT_TRUE(result.dropped);
  EXPECT_EQ(*result.dropped, "old report");
  EXPECT_EQ(result.dropped_priority, 6);
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(queue.counters().dropped, 1u);
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"stop", "high", "new report"}));
}

TEST(PriorityQueue, BetweenEqualsTheNewerWins) {
  PriorityQueue<std::string> queue({.capacity = 2});
  queue.push(6, "a");
  queue.push(6, "b");
  const auto result = queue.push(6, "c");
  EXPECT_TRUE(result.accepted);
  EXPECT_EQ(result.dropped, "a");
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"b", "c"}));
}

TEST(PriorityQueue, ALowerMessageNeverDisplacesAHigherOne) {
  PriorityQueue<std::string> queue({.capacity = 2});
  queue.push(12, "stop");
  queue.push(13, "stop harder");
  const auto result = queue.push(6, "report");
  EXPECT_FALSE(result.accepted);
  EXPECT_EQ(result.dropped, "report");  // handed back so the caller can NAK it
  EXPECT_EQ(queue.counters().dropped, 1u);
  EXPECT_EQ(queue.counters().dropped_safety_critical, 0u);
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"stop harder", "stop"}));
}

TEST(PriorityQueue, SafetyCriticalDisplacesOnlySafetyCriticalWhenNothingLowerIsLeft) {
  PriorityQueue<std::string> queue({.capacity = 2});
  queue.push(12, "stop 1");
  queue.push(14, "stop 2");
  const auto result = queue.push(12, "stop 3");
  EXPECT_TRUE(result.accepted);
  EXPECT_EQ(result.dropped, "stop 1");
  EXPECT_EQ(queue.counters().dropped_safety_critical, 1u);
  EXPECT_EQ(drain(queue), (std::vector<std::string>{"stop 2", "stop 3"}));
}

TEST(PriorityQueue, StaysBoundedUnderAFlood) {
  PriorityQueue<int> queue({.capacity = 8});
  for (int i = 0; i < 1000; ++i) queue.push(static_cast<std::uint8_t>(i % 16), int{i});
  EXPECT_EQ(queue.size(), 8u);
  EXPECT_EQ(queue.counters().dropped, 992u);
  // Priority 15 fills the queue; from then on each new 15 pushes out the
  // oldest 15 and everything lower is turned away. Left: the newest eight 15s.
  std::vector<int> left;
  while (auto item = queue.pop()) left.push_back(*item);
  EXPECT_EQ(left, (std::vector<int>{879, 895, 911, 927, 943, 959, 975, 991}));
}

TEST(PriorityQueue, ZeroCapacityIsTakenAsOne) {
  PriorityQueue<int> queue({.capacity = 0});
  EXPECT_EQ(queue.capacity(), 1u);
  EXPECT_TRUE(queue.push(1, 1).accepted);
  EXPECT_EQ(queue.size(), 1u);
}

}  // namespace
}  // namespace jaus::node
