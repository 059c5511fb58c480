#include "jaus/components/frame_worker.hpp"

#include <algorithm>
#include <utility>

namespace jaus::components {

// ---- ScheduledFrameWorker ---------------------------------------------------------

ScheduledFrameWorker::ScheduledFrameWorker(rt::Scheduler& scheduler, const rt::Clock& clock, std::size_t capacity,
                                           rt::Duration delay)
    : scheduler_(scheduler), clock_(clock), capacity_(std::max<std::size_t>(capacity, 1)), delay_(delay) {}

ScheduledFrameWorker::~ScheduledFrameWorker() {
  for (const Job& job : jobs_) scheduler_.cancel(job.timer);
}

bool ScheduledFrameWorker::submit(CaptureJob work, Done done) {
  if (jobs_.size() >= capacity_) {
    ++refused_;
    return false;
  }
  // The timer runs whichever job is first: jobs complete in order even when
  // the delay changed between them.
  const rt::TimerId timer = scheduler_.call_at(clock_.now() + delay_, [this] { run_next(); });
  jobs_.push_back(Job{timer, std::move(work), std::move(done)});
  return true;
}

void ScheduledFrameWorker::run_next() {
  if (jobs_.empty()) return;
  Job job = std::move(jobs_.front());
  jobs_.pop_front();
  ++ran_;
  // Off the queue first: `done` may submit the next job.
  job.done(job.work());
}

// ---- ThreadFrameWorker ------------------------------------------------------------

ThreadFrameWorker::ThreadFrameWorker(Post post, std::size_t capacity)
    : post_(std::move(post)), capacity_(std::max<std::size_t>(capacity, 1)), thread_([this] { run(); }) {}

ThreadFrameWorker::~ThreadFrameWorker() { stop(); }

bool ThreadFrameWorker::submit(CaptureJob work, Done done) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || queue_.size() + (running_job_ ? 1 : 0) >= capacity_) return false;
    queue_.push_back(Job{std::move(work), std::move(done)});
  }
  wake_.notify_one();
  return true;
}

void ThreadFrameWorker::stop() {
  std::deque<Job> dropped;  // destroyed outside the lock (their captures may be large)
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    dropped.swap(queue_);
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

bool ThreadFrameWorker::stopping() const {
  std::lock_guard lock(mutex_);
  return stopping_;
}

std::size_t ThreadFrameWorker::pending() const {
  std::lock_guard lock(mutex_);
  return queue_.size() + (running_job_ ? 1 : 0);
}

void ThreadFrameWorker::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    Job job = std::move(queue_.front());
    queue_.pop_front();
    running_job_ = true;
    lock.unlock();
    Expected<Image> result = job.work();
    lock.lock();
    running_job_ = false;
    if (stopping_) return;  // stop() is joining: the result is dropped with the queue
    lock.unlock();
    // Posted unlocked: stop() cannot return before this has (it joins), so
    // nothing is posted after it.
    post_([done = std::move(job.done), result = std::move(result)]() mutable { done(std::move(result)); });
    lock.lock();
  }
}

}  // namespace jaus::components
