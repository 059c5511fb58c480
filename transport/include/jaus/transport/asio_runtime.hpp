// The runtime's clock and scheduler on a Boost.Asio io_context: what a real
// node runs on (tests use rt::VirtualTime instead). Single-threaded: every
// callback runs on the thread that runs the io_context.
//
// Every timer of the runtime shares one Asio timer, set for the earliest
// deadline: setting, moving or cancelling a timer touches a vector, and the
// kernel's timer is re-armed only when the earliest deadline changes. With
// callbacks kept in place (rt::Callback), steady-state timers and posts
// allocate nothing.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <memory>
#include <vector>

#include "jaus/base/time.hpp"

namespace jaus::transport {

namespace detail {
class HandlerMemory;
}

class AsioRuntime final : public rt::Clock, public rt::Scheduler {
 public:
  explicit AsioRuntime(boost::asio::io_context& io);
  ~AsioRuntime() override;

  rt::TimePoint now() const override;
  rt::UtcTime utc_now() const override;
  rt::TimerId call_at(rt::TimePoint when, rt::Callback fn) override;
  void cancel(rt::TimerId id) override;
  void post(rt::Callback fn) override;

  std::size_t pending() const { return due_.size(); }

 private:
  struct Due {
    rt::TimePoint when;
    rt::TimerId id;
    rt::Callback fn;
  };
  // Orders the heap so that its front is the earliest (then the first set).
  static bool later(const Due& a, const Due& b) { return a.when != b.when ? a.when > b.when : a.id > b.id; }

  void run_due();
  void arm();  // sets the Asio timer for the earliest deadline, unless it is set for it

  boost::asio::io_context& io_;
  boost::asio::steady_timer timer_;
  rt::TimePoint armed_for_ = rt::TimePoint::max();  // the deadline timer_ waits for; max: none
  bool running_ = false;                            // in run_due: the timer is set after the batch
  rt::TimerId last_id_ = rt::kNoTimer;
  std::vector<Due> due_;                                // a binary heap (std::push_heap with `later`)
  std::shared_ptr<detail::HandlerMemory> wait_memory_;  // Asio's operations, without allocating
  std::shared_ptr<detail::HandlerMemory> post_memory_;
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);  // expires with the runtime
};

}  // namespace jaus::transport
