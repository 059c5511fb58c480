// The thread frame worker on a real thread: results come back through the
// post function only, the queue refuses beyond its bound, and stop() drops
// what is queued and joins without posting. No timing is asserted: waits are
// generous (a loaded 2-core machine under ASan), and order comes from
// handshakes, not sleeps.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

#include "decoded_image.hpp"
#include "harness.hpp"
#include "jaus/components/frame_worker.hpp"
#include "jaus/components/simulated_cameras.hpp"
#include "jaus/components/visual_sensor.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using namespace components;

constexpr auto kGenerous = 60s;

// The event loop of these tests: what the worker posts, run by the test's thread.
class PostedQueue {
 public:
  ThreadFrameWorker::Post post() {
    return [this](std::function<void()> fn) {
      {
        std::lock_guard lock(mutex_);
        queue_.push_back(std::move(fn));
      }
      wake_.notify_all();
    };
  }
  // Runs one posted function; false when none came in time.
  bool run_one() {
    std::unique_lock lock(mutex_);
    if (!wake_.wait_for(lock, kGenerous, [this] { return !queue_.empty(); })) return false;
    auto fn = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    fn();
    return true;
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return queue_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
};

Image image_of(std::uint8_t byte) {
  Image image;
  image.data = {byte};
  return image;
}

TEST(ThreadFrameWorker, RunsTheJobOnItsThreadAndPostsTheResultBack) {
  PostedQueue loop;
  ThreadFrameWorker worker(loop.post());
  const auto test_thread = std::this_thread::get_id();
  std::thread::id job_thread;
  std::optional<Expected<Image>> result;
  std::thread::id done_thread;
  ASSERT_TRUE(worker.submit(
      [&] {
        job_thread = std::this_thread::get_id();
        return Expected<Image>(image_of(7));
      },
      [&](Expected<Image> image) {
        done_thread = std::this_thread::get_id();
        result = std::move(image);
      }));
  ASSERT_TRUE(loop.run_one());
  ASSERT_TRUE(result && *result);
  EXPECT_EQ((*result)->data, std::vector<std::uint8_t>{7});
  EXPECT_NE(job_thread, test_thread);
  EXPECT_EQ(done_thread, test_thread);  // done only ever runs where the loop runs
}

TEST(ThreadFrameWorker, RefusesBeyondItsCapacityAndTakesJobsAgainOnceDone) {
  PostedQueue loop;
  ThreadFrameWorker worker(loop.post(), 3);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> started;
  int done = 0;
  const auto count = [&](Expected<Image>) { ++done; };
  ASSERT_TRUE(worker.submit(
      [&, released] {
        started.set_value();
        released.wait();
        return Expected<Image>(image_of(1));
      },
      count));
  ASSERT_EQ(started.get_future().wait_for(kGenerous), std::future_status::ready);  // running: counts
  EXPECT_TRUE(worker.submit([] { return Expected<Image>(image_of(2)); }, count));
  EXPECT_TRUE(worker.submit([] { return Expected<Image>(image_of(3)); }, count));
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(worker.submit([] { return Expected<Image>(image_of(4)); }, count));
  EXPECT_EQ(worker.pending(), 3u);
  release.set_value();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(loop.run_one());
  EXPECT_EQ(done, 3);
  // Room again (the last result may be posted a moment before its slot is freed: wait for it).
  for (int i = 0; i < 6000 && worker.pending() != 0; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_TRUE(worker.submit([] { return Expected<Image>(image_of(5)); }, count));
  ASSERT_TRUE(loop.run_one());
  EXPECT_EQ(done, 4);
}

TEST(ThreadFrameWorker, StopDropsWhatIsQueuedWaitsForTheRunningJobAndPostsNothing) {
  PostedQueue loop;
  ThreadFrameWorker worker(loop.post());
  std::promise<void> started;
  std::atomic<bool> release{false};
  std::atomic<int> ran{0};
  int done = 0;
  const auto count = [&](Expected<Image>) { ++done; };
  ASSERT_TRUE(worker.submit(
      [&] {
        started.set_value();
        while (!release) std::this_thread::sleep_for(1ms);
        ++ran;
        return Expected<Image>(image_of(1));
      },
      count));
  ASSERT_EQ(started.get_future().wait_for(kGenerous), std::future_status::ready);
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(worker.submit(
        [&] {
          ++ran;
          return Expected<Image>(image_of(2));
        },
        count));
  // The running job ends only once stop() has begun: stop() must wait for it.
  std::thread releaser([&] {
    while (!worker.stopping()) std::this_thread::sleep_for(1ms);
    release = true;
  });
  worker.stop();
  releaser.join();
  EXPECT_EQ(ran, 1);              // the queued three never ran
  EXPECT_EQ(loop.size(), 0u);     // and the running one's result was not posted
  EXPECT_EQ(done, 0);
  EXPECT_FALSE(worker.submit([] { return Expected<Image>(image_of(3)); }, count));
  worker.stop();  // idempotent
}

TEST(ThreadFrameWorker, TheVisualSensorGetsItsFramesFromTheThreadAndOutlivesNothing) {
  rt::VirtualTime time;
  RecordingOutbox outbox;
  outbox.clock = &time;
  PostedQueue loop;
  ThreadFrameWorker worker(loop.post());
  SimulatedCameras cameras(VisualSensorConfig{{CameraConfig{}}}, time);
  rt::ComponentConfig config;
  config.address = Address{1, 1, 37, 1};
  auto sensor = std::make_unique<VisualSensor>(config, rt::Environment{time, time, outbox}, cameras);
  sensor->use_frame_worker(worker);
  sensor->start();
  deliver_to(*sensor, time, kOcuB, msg::QueryImage{});
  EXPECT_TRUE(outbox.to<msg::ReportImage>(kOcuB).empty());  // encoding on the worker's thread
  ASSERT_TRUE(loop.run_one());                               // its result, on "the loop"
  const auto images = outbox.to<msg::ReportImage>(kOcuB);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_TRUE(decode_png(images[0].data));

  // A capture still under way when the sensor goes: its result comes back to nothing.
  time.advance(100ms);
  deliver_to(*sensor, time, kOcuC, msg::QueryImage{});
  sensor.reset();
  ASSERT_TRUE(loop.run_one());
  EXPECT_TRUE(outbox.to<msg::ReportImage>(kOcuC).empty());
}

}  // namespace
}  // namespace jaus::test
