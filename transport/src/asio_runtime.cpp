#include "jaus/transport/asio_runtime.hpp"

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
  timer->async_wait([this, id, fn = std::move(fn)](const boost::system::error_code& ec) {
    if (ec) return;  // cancelled: the timer is already gone
    timers_.erase(id);
    fn();
  });
  timers_.emplace(id, std::move(timer));
  return id;
}

void AsioRuntime::cancel(rt::TimerId id) {
  const auto it = timers_.find(id);
  if (it == timers_.end()) return;
  it->second->cancel();
  timers_.erase(it);
}

}  // namespace jaus::transport
