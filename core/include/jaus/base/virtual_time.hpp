// A clock and scheduler that move only when told to: the test harness for
// every timing rule of the runtime (controller liveness, SC rates, timeouts).
#pragma once

#include <map>
#include <utility>

#include "jaus/base/time.hpp"

namespace jaus::rt {

class VirtualTime final : public Clock, public Scheduler {
 public:
  explicit VirtualTime(UtcTime utc_origin = UtcTime{}) : utc_origin_(utc_origin) {}

  TimePoint now() const override { return now_; }
  UtcTime utc_now() const override { return utc_origin_ + now_.time_since_epoch(); }

  TimerId call_at(TimePoint when, Callback fn) override {
    const TimerId id = ++last_id_;
    // Ordered by time, then by scheduling order: equal times run FIFO.
    queue_.emplace(Key{when < now_ ? now_ : when, id}, std::move(fn));
    return id;
  }

  void cancel(TimerId id) override {
    for (auto it = queue_.begin(); it != queue_.end(); ++it)
      if (it->first.id == id) {
        queue_.erase(it);
        return;
      }
  }

  // Runs every call due up to `until`, in time order, moving the clock to
  // each call's time; calls scheduled meanwhile run too if due. Returns how
  // many ran.
  std::size_t run_until(TimePoint until) {
    std::size_t ran = 0;
    while (!queue_.empty() && queue_.begin()->first.when <= until) {
      auto node = queue_.extract(queue_.begin());
      now_ = node.key().when;
      node.mapped()();
      ++ran;
    }
    if (now_ < until) now_ = until;
    return ran;
  }
  std::size_t advance(Duration d) { return run_until(now_ + d); }
  // Runs what is due now (posted work) without moving the clock.
  std::size_t run_ready() { return run_until(now_); }

  std::size_t pending() const { return queue_.size(); }

 private:
  struct Key {
    TimePoint when;
    TimerId id;
    bool operator<(const Key& o) const { return when != o.when ? when < o.when : id < o.id; }
  };
  TimePoint now_{};
  UtcTime utc_origin_;
  TimerId last_id_ = kNoTimer;
  std::map<Key, Callback> queue_;
};

}  // namespace jaus::rt
