#include "jaus/transport/asio_runtime.hpp"

#include <boost/asio/post.hpp>

namespace jaus::transport {

AsioRuntime::~AsioRuntime() {
  for (auto& [id, timer] : timers_) timer->cancel();
}

rt::TimePoint AsioRuntime::now() const {
  return std::chrono::time_point_cast<rt::Duration>(std::chrono::steady_clock::now());
}

rt::UtcTime AsioRuntime::utc_now() const {
  return std::chrono::time_point_cast<rt::Duration>(std::chrono::system_clock::now());
}

rt::TimerId AsioRuntime::call_at(rt::TimePoint when, std::function<void()> fn) {
  const rt::TimerId id = ++last_id_;
  auto timer = std::make_unique<boost::asio::steady_timer>(io_);
  timer->expires_at(std::chrono::time_point_cast<std::chrono::steady_clock::duration>(when));
  timer->async_wait([this, id, alive = std::weak_ptr<const char>(alive_),
                     fn = std::move(fn)](const boost::system::error_code& ec) {
    // The runtime may be gone (its handlers outlive it in the io_context).
    if (ec || alive.expired()) return;
    // A timer that had expired when cancel() was called still completes
    // without an error (its handler was already queued, e.g. behind another
    // due in the same batch that removed a component): only a timer still
    // in the table may run. Safety timers rely on a cancel being final.
    const auto it = timers_.find(id);
    if (it == timers_.end()) return;
    timers_.erase(it);
    fn();
  });
  timers_.emplace(id, std::move(timer));
  return id;
}

void AsioRuntime::post(std::function<void()> fn) { boost::asio::post(io_, std::move(fn)); }

void AsioRuntime::cancel(rt::TimerId id) {
  const auto it = timers_.find(id);
  if (it == timers_.end()) return;
  it->second->cancel();
  timers_.erase(it);
}

}  // namespace jaus::transport
