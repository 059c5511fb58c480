// The Asio-backed runtime: callbacks run in time order on the io_context's
// thread, cancelled ones never run. Real time, so only order and presence
// are asserted, never durations.
#include <gtest/gtest.h>

#include "jaus/transport/asio_runtime.hpp"

namespace jaus::transport {
namespace {

using namespace std::chrono_literals;

TEST(AsioRuntime, RunsCallbacksInTimeOrderAndHonoursCancel) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  std::vector<int> order;
  const auto start = runtime.now();
  runtime.call_at(start + 30ms, [&] { order.push_back(3); });
  runtime.call_at(start + 10ms, [&] { order.push_back(1); });
  const auto cancelled = runtime.call_at(start + 20ms, [&] { order.push_back(2); });
  runtime.call_at(start + 20ms, [&] { order.push_back(22); });
  runtime.cancel(cancelled);
  runtime.cancel(rt::TimerId{999});  // unknown ids are a no-op
  io.run();
  EXPECT_EQ(order, (std::vector<int>{1, 22, 3}));
  EXPECT_GE(runtime.now() - start, 30ms);
  EXPECT_EQ(runtime.pending(), 0u);
}

// Two timers already due when the loop runs complete in one batch; the first
// removes the owner of the second (as removing a component does), which
// cancels it. The second must not run: its owner is gone.
TEST(AsioRuntime, ATimerCancelledInTheBatchItIsDueInNeverRuns) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  struct Owner {  // stands in for a component: cancels its timer when destroyed
    AsioRuntime& runtime;
    rt::TimerId timer = rt::kNoTimer;
    std::vector<int> seen;
    ~Owner() { runtime.cancel(timer); }
  };
  std::unique_ptr<Owner> owner(new Owner{runtime, rt::kNoTimer, {}});
  int owner_callbacks = 0;
  const auto start = runtime.now();
  runtime.call_at(start - 2s, [&] { owner.reset(); });
  owner->timer = runtime.call_at(start - 1s, [&, o = owner.get()] {
    ++owner_callbacks;
    o->seen.push_back(1);  // a use after free under ASan, had it run
  });
  io.run();
  EXPECT_EQ(owner, nullptr);
  EXPECT_EQ(owner_callbacks, 0);
  EXPECT_EQ(runtime.pending(), 0u);
}

TEST(AsioRuntime, PostRunsSoonWithoutArmingATimer) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  std::vector<int> order;
  runtime.call_at(runtime.now() - 1s, [&] {
    runtime.post([&] { order.push_back(2); });
    order.push_back(1);  // a posted call runs after the current handler
  });
  runtime.post([&] { order.push_back(0); });
  EXPECT_EQ(runtime.pending(), 1u);  // the timer only
  io.run();
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2}));
}

TEST(AsioRuntime, PastTimesRunAtOnceAndCallbacksMayReschedule) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  int runs = 0;
  std::function<void()> tick = [&] {
    if (++runs < 5) runtime.call_at(runtime.now(), tick);
  };
  runtime.call_at(runtime.now() - 1s, tick);
  io.run();
  EXPECT_EQ(runs, 5);
}

// Every timer shares one Asio timer, set for the earliest deadline: one set
// later for an earlier time still runs first, and a thousand set and partly
// cancelled run in time order, the cancelled ones never.
TEST(AsioRuntime, ManyTimersShareOneAsioTimerAndRunInTimeOrder) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  const auto start = runtime.now();
  std::vector<int> ran;
  std::vector<rt::TimerId> ids;
  for (int i = 999; i >= 0; --i)  // set latest first: each one moves the earliest deadline
    ids.push_back(runtime.call_at(start + std::chrono::microseconds(20 * i), [&ran, i] { ran.push_back(i); }));
  for (std::size_t k = 0; k < ids.size(); k += 3) runtime.cancel(ids[k]);  // i = 999, 996, ...
  EXPECT_EQ(runtime.pending(), 666u);
  io.run();
  std::vector<int> expected;
  for (int i = 0; i < 1000; ++i)
    if ((999 - i) % 3 != 0) expected.push_back(i);
  EXPECT_EQ(ran, expected);
  EXPECT_EQ(runtime.pending(), 0u);
}

TEST(AsioRuntime, ATimerSetForSoonerThanTheEarliestRunsFirst) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  std::vector<int> order;
  const auto start = runtime.now();
  runtime.call_at(start + 40ms, [&] { order.push_back(2); });
  runtime.call_at(start + 5ms, [&] {
    order.push_back(1);
    runtime.call_at(runtime.now(), [&] { order.push_back(11); });  // sooner than the one left
  });
  io.run();
  EXPECT_EQ(order, (std::vector<int>{1, 11, 2}));
}

// A callback that throws ends io.run() (the host then stops in order); the
// timers left still run when the loop runs again.
TEST(AsioRuntime, TimersLeftAfterACallbackThrewStillRun) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  const auto start = runtime.now();
  bool later_ran = false;
  runtime.call_at(start, [] { throw std::runtime_error("a fault"); });
  runtime.call_at(start + 10ms, [&] { later_ran = true; });
  EXPECT_THROW(io.run(), std::runtime_error);
  io.restart();
  io.run();
  EXPECT_TRUE(later_ran);
}

// Work posted and timers set on a runtime that is gone never run, and the
// io_context frees what they hold when it runs or is destroyed.
TEST(AsioRuntime, CallbacksOfADestroyedRuntimeNeverRun) {
  boost::asio::io_context io;
  int runs = 0;
  auto token = std::make_shared<int>(0);
  {
    AsioRuntime runtime(io);
    runtime.call_at(runtime.now(), [&runs, token] { ++runs; });
    runtime.post([&runs, token] { ++runs; });  // posted work checks its own owner; this one has none
  }
  io.run();
  EXPECT_EQ(runs, 1);  // the post: posted work is the caller's to guard
  EXPECT_EQ(token.use_count(), 1);
}

TEST(AsioRuntime, UtcClockIsTheSystemClock) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  const auto difference = runtime.utc_now() - std::chrono::system_clock::now();
  EXPECT_LT(std::chrono::abs(difference), 1s);
}

}  // namespace
}  // namespace jaus::transport
