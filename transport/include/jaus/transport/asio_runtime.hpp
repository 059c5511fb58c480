// The runtime's clock and scheduler on a Boost.Asio io_context: what a real
// node runs on (tests use rt::VirtualTime instead). Single-threaded: every
// callback runs on the thread that runs the io_context.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <map>
#include <memory>

#include "jaus/base/time.hpp"

namespace jaus::transport {

class AsioRuntime final : public rt::Clock, public rt::Scheduler {
 public:
  explicit AsioRuntime(boost::asio::io_context& io) : io_(io) {}
  ~AsioRuntime() override;

  rt::TimePoint now() const override;
  rt::UtcTime utc_now() const override;
  rt::TimerId call_at(rt::TimePoint when, std::function<void()> fn) override;
  void cancel(rt::TimerId id) override;
  void post(std::function<void()> fn) override;

  std::size_t pending() const { return timers_.size(); }

 private:
  boost::asio::io_context& io_;
  rt::TimerId last_id_ = rt::kNoTimer;
  std::map<rt::TimerId, std::unique_ptr<boost::asio::steady_timer>> timers_;
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);  // expires with the runtime
};

}  // namespace jaus::transport
