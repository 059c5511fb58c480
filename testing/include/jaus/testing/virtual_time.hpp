// Letting virtual time pass in tests: until a condition holds or for a
// while, one step at a time, so that a test acts on what has happened (a
// reply in, a state reached) at the virtual time it happened, give or take a
// step, and never waits on the real clock.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>

#include "jaus/base/virtual_time.hpp"

namespace jaus::testing {

// What is due within a step runs in time order; the condition is looked at
// between steps.
inline constexpr rt::Duration kDefaultStep = std::chrono::milliseconds(1);

// Runs what is due now, then lets `time` pass until `done()` or `limit` has
// passed. True when `done()` (looked at first: no time passes if it holds).
inline bool run_until(rt::VirtualTime& time, const std::function<bool()>& done, rt::Duration limit,
                      rt::Duration step = kDefaultStep) {
  const rt::TimePoint deadline = time.now() + limit;
  time.run_ready();
  for (;;) {
    if (done()) return true;
    if (time.now() >= deadline) return false;
    time.advance(std::min(step, deadline - time.now()));
  }
}

// Lets `time` pass by `duration`, running everything due meanwhile.
inline void run_for(rt::VirtualTime& time, rt::Duration duration) { time.advance(duration); }

// A wait function for code that waits for its own conditions (an
// ocu::OcuSession's SessionEnvironment::wait): runs what is due now, then
// lets at most one step pass, never beyond `until`.
inline std::function<void(rt::TimePoint)> stepper(rt::VirtualTime& time, rt::Duration step = kDefaultStep) {
  return [&time, step](rt::TimePoint until) {
    time.run_ready();
    if (time.now() < until) time.advance(std::min(step, until - time.now()));
  };
}

}  // namespace jaus::testing
