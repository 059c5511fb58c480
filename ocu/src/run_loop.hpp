// The loop both dialects' sessions run (OcuSession::run_until and
// run_cleanup_until, JssSession's the same): until done() holds, `limit` has
// passed or, unless `through_interrupt` (a cleanup that still runs after
// Ctrl-C), the session is interrupted. On UDP it runs the io_context one
// handler at a time, waking at least every kRunSlice to look at the deadline;
// an attached session lets its environment's time pass instead (`wait`).
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>

#include <boost/asio/io_context.hpp>

#include "jaus/base/time.hpp"

namespace jaus::ocu::detail {

inline constexpr rt::Duration kRunSlice = std::chrono::milliseconds(100);

struct RunLoop {
  rt::Clock& clock;
  boost::asio::io_context* io;  // null: attached
  const std::function<void(rt::TimePoint until)>& wait;
  std::function<bool()> interrupted;
};

inline bool run_session(const RunLoop& loop, const std::function<bool()>& done, rt::Duration limit,
                        bool through_interrupt) {
  const auto deadline = loop.clock.now() + limit;
  for (;;) {
    if (done()) return true;
    if (!through_interrupt && loop.interrupted()) return false;
    const auto now = loop.clock.now();
    if (now >= deadline) return false;
    if (loop.io == nullptr) {
      loop.wait(deadline);
      continue;
    }
    if (loop.io->stopped()) loop.io->restart();
    loop.io->run_one_for(std::min(deadline - now, kRunSlice));
  }
}

}  // namespace jaus::ocu::detail
