// Time as the runtime sees it: injected, never read from the system here.
// Production code drives the runtime from a Boost.Asio executor (transport/);
// tests drive it from VirtualTime, so every timing rule runs deterministically.
#pragma once

#include <chrono>
#include <cstdint>

#include "jaus/base/callback.hpp"

namespace jaus::rt {

using Duration = std::chrono::nanoseconds;

// Monotonic time since an arbitrary origin (the runtime's start).
using TimePoint = std::chrono::time_point<std::chrono::steady_clock, Duration>;

using UtcTime = std::chrono::time_point<std::chrono::system_clock, Duration>;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual TimePoint now() const = 0;
  // Wall-clock UTC, for Report Time and time stamps.
  virtual UtcTime utc_now() const = 0;
};

using TimerId = std::uint64_t;
inline constexpr TimerId kNoTimer = 0;

// Runs callbacks at given times on the runtime's single thread of execution.
// A Callback keeps a small capture (`this`, a key, a weak_ptr) in place: a
// timer set or work posted per message allocates nothing.
class Scheduler {
 public:
  virtual ~Scheduler() = default;
  // Calls `fn` once at `when` (or as soon as possible if `when` has passed).
  virtual TimerId call_at(TimePoint when, Callback fn) = 0;
  // Cancels a pending call; a no-op for ids that already ran or were cancelled.
  virtual void cancel(TimerId id) = 0;
  // Calls `fn` soon, after the current handler, without arming a timer: for
  // work each incoming message triggers (a node draining its queue), where a
  // timer per message would cost a system call. Cannot be cancelled: `fn`
  // must check that what it works on still exists.
  virtual void post(Callback fn) { call_at(TimePoint::min(), std::move(fn)); }
};

}  // namespace jaus::rt
