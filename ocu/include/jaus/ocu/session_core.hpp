// What the operator-unit sessions of both dialects share (OcuSession: RA on
// the node's transport; JssSession: SAE JAUS over AS5669A): the listeners of
// what arrives for the operator unit, waiting for a first reply (resending a
// query meanwhile, over loss), the run loop on UDP or in an attached
// environment, and the stop request. A session is a SessionCore of its
// message type, whose source() and code() say who sent it and what it is;
// tools and the conformance runner written over SessionCore serve both.
//
// Single-threaded: everything runs on the thread that calls run_until(), but
// request_stop(), which may come from any thread (a signal handler too): a
// waiting run_until() sees it within kRunSlice on UDP, at once from the loop.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

// A query lost on the way (or its reply) is sent again after this long: well
// above a round trip on a radio link, well below the 1 s default timeout.
inline constexpr rt::Duration kQueryResendPeriod = std::chrono::milliseconds(250);

// timeout: "no reply from 1.1.33.1 within 1 s" (an RA address or a JSS ID).
template <class Id>
Error no_reply_error(const Id& from, rt::Duration timeout) {
  return make_error(ErrorCode::timeout, "no reply from " + from.to_string() + " within " + seconds_text(timeout));
}

template <class M>
class SessionCore {
 public:
  using Message = M;
  using Listener = std::function<void(const Message&)>;
  using ListenerId = std::uint64_t;

  // At most this long for clean-up after a stop was requested: a Ctrl-C never needs a second one.
  static constexpr rt::Duration kLongestCleanup = std::chrono::seconds(1);
  // A loop on UDP wakes at least this often to look at its deadline and the stop request.
  static constexpr rt::Duration kRunSlice = std::chrono::milliseconds(100);

  SessionCore(const SessionCore&) = delete;
  SessionCore& operator=(const SessionCore&) = delete;

  rt::Clock& clock() { return *clock_; }
  // Timers on the session's clock (they fire while run_until() runs).
  rt::Scheduler& scheduler() { return *scheduler_; }
  // Opened on UDP (open()) rather than attached; what runs it there (another
  // session opened on it runs whenever this one does), null when attached.
  bool on_udp() const { return io_ != nullptr; }
  boost::asio::io_context* io_context() { return io_; }

  // Every message for the operator unit (or a broadcast it matches), as the session delivers it.
  ListenerId listen(Listener listener) {
    listeners_.emplace(++last_id_, std::move(listener));
    return last_id_;
  }
  void unlisten(ListenerId id) { listeners_.erase(id); }

  // Runs the io_context (or lets the environment's time pass) until `done()`,
  // `limit` has passed or a stop is requested. True when `done()`.
  bool run_until(const std::function<bool()>& done, rt::Duration limit) { return run(done, limit, false); }
  void run_for(rt::Duration limit) {
    run_until([] { return false; }, limit);
  }
  // The same after a stop was requested, for clean-up that must be heard (a
  // release retransmitted until answered), at most kLongestCleanup.
  bool run_cleanup_until(const std::function<bool()>& done, rt::Duration limit) {
    return run(done, std::min(limit, kLongestCleanup), true);
  }
  // Interrupts what the session waits for, now and later (commands then
  // clean up: release control, end subscriptions). From any thread.
  void request_stop() { interrupted_.store(true, std::memory_order_relaxed); }
  void interrupt() { request_stop(); }
  bool interrupted() const { return interrupted_.load(std::memory_order_relaxed); }

  // Calls `send` now and again every `resend_every` (it or its answer was
  // lost) until `done()`, `limit` has passed or, unless `through_stop`
  // (clean-up), a stop was requested. True when `done()`.
  bool resend_until(const std::function<void()>& send, const std::function<bool()>& done, rt::Duration limit,
                    rt::Duration resend_every = kQueryResendPeriod, bool through_stop = false) {
    const auto period = std::max<rt::Duration>(resend_every, std::chrono::milliseconds(1));
    const auto deadline = clock().now() + limit;
    send();
    for (;;) {
      const auto now = clock().now();
      if (now >= deadline) return done();
      const auto slice = std::min(period, deadline - now);
      if (through_stop ? run_cleanup_until(done, slice) : run_until(done, slice)) return true;
      if ((!through_stop && interrupted()) || clock().now() >= deadline) return done();
      send();  // a second answer to a query is ignored
    }
  }

  // The first message from `from` (wildcards match any) with one of `codes`
  // (any when empty), `send` called now and every `resend_every` until it
  // comes (none: only waits). Errors: timeout ("no reply from 1.1.33.1
  // within 1 s"), interrupted.
  template <class Id>
  Expected<Message> await_reply_resending(const Id& from, std::vector<std::uint16_t> codes, rt::Duration timeout,
                                          const std::function<void()>& send,
                                          rt::Duration resend_every = kQueryResendPeriod) {
    std::optional<Message> reply;
    const ListenerId id = listen([&](const Message& m) {
      if (reply || !from.matches(m.source())) return;
      if (!codes.empty() && std::find(codes.begin(), codes.end(), m.code()) == codes.end()) return;
      reply = m;
    });
    const auto got = [&] { return reply.has_value(); };
    if (send) {
      resend_until(send, got, timeout, resend_every);
    } else {
      run_until(got, timeout);
    }
    unlisten(id);
    if (reply) return std::move(*reply);
    if (interrupted()) return unexpected(make_error(ErrorCode::interrupted, "interrupted"));
    return unexpected(no_reply_error(from, timeout));
  }
  template <class Id>
  Expected<Message> await_reply(const Id& from, std::vector<std::uint16_t> codes, rt::Duration timeout) {
    return await_reply_resending(from, std::move(codes), timeout, {});
  }

 protected:
  SessionCore() = default;
  ~SessionCore() = default;

  // What the loop runs on: on UDP the io_context `io` (one handler at a
  // time); attached (io null), `wait` lets the environment's time pass up to
  // a deadline (jaus::testing::stepper for virtual time).
  void run_on(rt::Clock& clock, rt::Scheduler& scheduler, boost::asio::io_context* io,
              std::function<void(rt::TimePoint until)> wait) {
    clock_ = &clock;
    scheduler_ = &scheduler;
    io_ = io;
    wait_ = std::move(wait);
  }
  // Hands `message` to every listener (they may unlisten themselves, or others, meanwhile).
  void deliver(const Message& message) {
    std::vector<ListenerId> ids;
    for (const auto& [id, l] : listeners_) ids.push_back(id);
    for (const auto id : ids)
      if (const auto it = listeners_.find(id); it != listeners_.end()) it->second(message);
  }
  // An id for a derived session's own lists (OcuSession's watchers), unique among the listeners'.
  ListenerId next_listener_id() { return ++last_id_; }

 private:
  bool run(const std::function<bool()>& done, rt::Duration limit, bool through_stop) {
    const auto deadline = clock().now() + limit;
    for (;;) {
      if (done()) return true;
      if (!through_stop && interrupted()) return false;
      const auto now = clock().now();
      if (now >= deadline) return false;
      if (io_ == nullptr) {
        wait_(deadline);
        continue;
      }
      if (io_->stopped()) io_->restart();
      io_->run_one_for(std::min(deadline - now, kRunSlice));
    }
  }

  rt::Clock* clock_ = nullptr;
  rt::Scheduler* scheduler_ = nullptr;
  boost::asio::io_context* io_ = nullptr;
  std::function<void(rt::TimePoint)> wait_;
  std::atomic<bool> interrupted_ = false;
  ListenerId last_id_ = 0;
  std::map<ListenerId, Listener> listeners_;
};

}  // namespace jaus::ocu
