#include "jaus/transport/asio_runtime.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

#include "handler_memory.hpp"

namespace jaus::transport {

AsioRuntime::AsioRuntime(boost::asio::io_context& io)
    : io_(io),
      timer_(io),
      // The timer's wait and those it aborted that have not run yet.
      wait_memory_(std::make_shared<detail::HandlerMemory>(4, 256)),
      // Posted work (a node's drain after each burst of datagrams): a few at once.
      post_memory_(std::make_shared<detail::HandlerMemory>(8, 256)) {
  due_.reserve(64);  // a node's usual timers without growing
}

AsioRuntime::~AsioRuntime() { timer_.cancel(); }

rt::TimePoint AsioRuntime::now() const {
  return std::chrono::time_point_cast<rt::Duration>(std::chrono::steady_clock::now());
}

rt::UtcTime AsioRuntime::utc_now() const {
  return std::chrono::time_point_cast<rt::Duration>(std::chrono::system_clock::now());
}

rt::TimerId AsioRuntime::call_at(rt::TimePoint when, rt::Callback fn) {
  const rt::TimerId id = ++last_id_;
  due_.push_back(Due{when, id, std::move(fn)});
  std::push_heap(due_.begin(), due_.end(), later);
  if (!running_ && when < armed_for_) arm();
  return id;
}

void AsioRuntime::cancel(rt::TimerId id) {
  // A removed entry never runs, even when its deadline has passed and the
  // batch it is due in is being run (a component removed by an earlier
  // callback of that batch cancels its timers): safety timers rely on a
  // cancel being final. A cancelled earliest deadline leaves the Asio timer
  // set; it finds nothing due and sets itself for the next one.
  const auto it = std::find_if(due_.begin(), due_.end(), [id](const Due& d) { return d.id == id; });
  if (it == due_.end()) return;
  due_.erase(it);
  std::make_heap(due_.begin(), due_.end(), later);
}

void AsioRuntime::post(rt::Callback fn) { boost::asio::post(io_, detail::with_memory(post_memory_, std::move(fn))); }

void AsioRuntime::arm() {
  if (due_.empty() || due_.front().when == armed_for_) return;
  armed_for_ = due_.front().when;
  timer_.expires_at(std::chrono::time_point_cast<std::chrono::steady_clock::duration>(armed_for_));
  // Setting the expiry aborts the previous wait (its handler sees
  // operation_aborted). One that had already completed still runs: it finds
  // nothing due, or runs what is.
  timer_.async_wait(detail::with_memory(
      wait_memory_, [this, alive = std::weak_ptr<const char>(alive_)](const boost::system::error_code& ec) {
        // The runtime may be gone (its handlers outlive it in the io_context).
        if (ec || alive.expired()) return;
        run_due();
      }));
}

void AsioRuntime::run_due() {
  armed_for_ = rt::TimePoint::max();
  // The Asio timer is set once, after the batch, for the earliest deadline
  // left (also when a callback throws: the loop's owner may run on).
  running_ = true;
  struct SetAfterTheBatch {
    AsioRuntime& runtime;
    ~SetAfterTheBatch() {
      runtime.running_ = false;
      runtime.arm();
    }
  } set_after{*this};
  // What is due at this moment runs; what the callbacks set for now or
  // earlier runs in the next batch, after the io_context's other handlers
  // (a callback that reschedules itself at once cannot starve the sockets).
  const rt::TimePoint moment = now();
  while (!due_.empty() && due_.front().when <= moment) {
    std::pop_heap(due_.begin(), due_.end(), later);
    rt::Callback fn = std::move(due_.back().fn);
    due_.pop_back();
    fn();  // may set or cancel timers, this one's successors included
  }
}

}  // namespace jaus::transport
