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

TEST(AsioRuntime, UtcClockIsTheSystemClock) {
  boost::asio::io_context io;
  AsioRuntime runtime(io);
  const auto difference = runtime.utc_now() - std::chrono::system_clock::now();
  EXPECT_LT(std::chrono::abs(difference), 1s);
}

}  // namespace
}  // namespace jaus::transport
