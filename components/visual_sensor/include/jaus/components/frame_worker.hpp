// Where the visual sensor's frames are captured and encoded: never on the
// event loop that answers Set Emergency and the controller's messages (issue
// 28). The component hands a worker a job (a CaptureJob, camera.hpp: copies
// of what it needs, nothing of the component) and a `done` that the worker
// calls back on the event loop with the result. A worker holds at most its
// capacity of jobs (queued and running): beyond, submit() refuses, so a flood
// of requests never grows it.
//
// Two workers: ScheduledFrameWorker runs jobs on the runtime's scheduler
// (tests under virtual time, and a component built without a host: its work
// is still on the loop, but after the handler, and bounded); ThreadFrameWorker
// runs them on a thread of its own, which the host makes and injects (the
// component never makes a thread).
#pragma once

#include <string_view>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/components/camera.hpp"

namespace jaus::components {

class FrameWorker {
 public:
  // Its name among what a host offers a component kind (rt::Backends).
  static constexpr std::string_view kInterface = "frame_worker";
  static constexpr std::string_view kDescription = "a frame worker";

  using Done = std::function<void(Expected<Image>)>;
  virtual ~FrameWorker() = default;
  // Runs `work` later, then `done` with its result on the event loop. False,
  // and neither runs, when the worker is full or stopped.
  virtual bool submit(CaptureJob work, Done done) = 0;
};

// Each job runs `delay` after it was submitted (0: as soon as the current
// handler returns), on the scheduler's thread, one at a time in order.
class ScheduledFrameWorker final : public FrameWorker {
 public:
  ScheduledFrameWorker(rt::Scheduler& scheduler, const rt::Clock& clock, std::size_t capacity = 4,
                       rt::Duration delay = {});
  ~ScheduledFrameWorker() override;  // cancels what is pending
  ScheduledFrameWorker(const ScheduledFrameWorker&) = delete;
  ScheduledFrameWorker& operator=(const ScheduledFrameWorker&) = delete;

  bool submit(CaptureJob work, Done done) override;
  // A slow camera (tests): jobs submitted from now on take this long.
  void set_delay(rt::Duration delay) { delay_ = delay; }
  std::size_t pending() const { return jobs_.size(); }
  std::uint64_t ran() const { return ran_; }         // jobs run: captures and encodes
  std::uint64_t refused() const { return refused_; }  // submits beyond the capacity

 private:
  struct Job {
    rt::TimerId timer;
    CaptureJob work;
    Done done;
  };
  void run_next();

  rt::Scheduler& scheduler_;
  const rt::Clock& clock_;
  std::size_t capacity_;
  rt::Duration delay_;
  std::deque<Job> jobs_;  // in submission order, each with its timer
  std::uint64_t ran_ = 0;
  std::uint64_t refused_ = 0;
};

// One thread, jobs in order. `post` must be safe to call from that thread and
// run its function on the event loop (the host's: boost::asio::post on the
// io_context); `done` runs there. stop() (and the destructor) drops what is
// queued, waits for the running job and joins: no result is posted after it
// returns. submit() and stop() are called from the event loop.
class ThreadFrameWorker final : public FrameWorker {
 public:
  using Post = std::function<void(std::function<void()>)>;
  explicit ThreadFrameWorker(Post post, std::size_t capacity = 4);
  ~ThreadFrameWorker() override;
  ThreadFrameWorker(const ThreadFrameWorker&) = delete;
  ThreadFrameWorker& operator=(const ThreadFrameWorker&) = delete;

  bool submit(CaptureJob work, Done done) override;
  void stop();
  bool stopping() const;
  std::size_t pending() const;  // queued and running

 private:
  struct Job {
    CaptureJob work;
    Done done;
  };
  void run();

  Post post_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> queue_;
  bool running_job_ = false;
  bool stopping_ = false;
  std::thread thread_;  // last: starts once everything above exists
};

}  // namespace jaus::components
