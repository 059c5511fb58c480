#include "jaus/runtime/repeat_limiter.hpp"

#include <algorithm>
#include <cmath>

namespace jaus::rt {
namespace {
std::string seconds_text(Duration d) { return std::to_string(std::lround(std::chrono::duration<double>(d).count())); }
}  // namespace

bool RepeatLimiter::admit(TimePoint now, std::string& note) {
  note.clear();
  if (window_open_ && now - window_start_ < window_) {
    if (lines_in_window_ < burst_) {
      ++lines_in_window_;
      return true;
    }
    ++suppressed_;
    ++suppressed_total_;
    return false;
  }
  if (suppressed_ > 0)  // left out in the window that just ended, before its summary was written
    note =
        " [" + std::to_string(suppressed_) + " more like this in the last " + seconds_text(now - window_start_) + " s]";
  suppressed_ = 0;
  window_open_ = true;
  window_start_ = now;
  lines_in_window_ = 1;
  return true;
}

void RepeatLimiter::count_suppressed(TimePoint now) {
  if (!window_open_ || now - window_start_ >= window_) {  // a window of its own, already full
    window_open_ = true;
    window_start_ = now;
    lines_in_window_ = burst_;
  }
  ++suppressed_;
  ++suppressed_total_;
}

std::uint64_t RepeatLimiter::take_suppressed(TimePoint now) {
  const std::uint64_t left_out = suppressed_;
  suppressed_ = 0;
  window_open_ = true;
  window_start_ = now;
  lines_in_window_ = burst_;
  return left_out;
}

RepeatedLines::~RepeatedLines() {
  if (timer_ != kNoTimer) scheduler_.cancel(timer_);
}

RepeatedLines::Entry& RepeatedLines::entry_for(Repeated kind, LogLevel level) {
  auto it = entries_.find(kind.reason);
  if (it == entries_.end())
    it =
        entries_
            .emplace(kind.reason, Entry{RepeatLimiter(kRepeatedLogWindow, kind.burst), level})
            .first;
  return it->second;
}

bool RepeatedLines::admit(Repeated kind, LogLevel level, std::string& note) {
  Entry& entry = entry_for(kind, level);
  const TimePoint now = clock_.now();
  if (!budget_window_open_ || now - budget_window_start_ >= kRepeatedLogWindow) {
    budget_window_open_ = true;
    budget_window_start_ = now;
    budget_used_ = 0;
    noteworthy_budget_used_ = 0;
  }
  const bool noteworthy = kind.burst > 1;
  int& used = noteworthy ? noteworthy_budget_used_ : budget_used_;
  const int budget = noteworthy ? kOwnerNoteworthyLinesPerWindow : kOwnerLinesPerWindow;
  bool admitted = false;
  if (used < budget) {
    admitted = entry.limiter.admit(now, note);
    if (admitted) ++used;
  } else {
    entry.limiter.count_suppressed(now);
  }
  if (!admitted && entry.limiter.suppressed() == 1) arm();
  return admitted;
}

std::uint64_t RepeatedLines::suppressed_total() const {
  std::uint64_t total = 0;
  for (const auto& [reason, entry] : entries_) total += entry.limiter.suppressed_total();
  return total;
}

void RepeatedLines::arm() {
  TimePoint earliest = TimePoint::max();
  for (const auto& [reason, entry] : entries_)
    if (entry.limiter.suppressed() > 0) earliest = std::min(earliest, entry.limiter.window_end());
  if (earliest == TimePoint::max()) return;
  if (timer_ != kNoTimer && timer_at_ <= earliest) return;
  // With no timer pending, timer_at_ is when the last one fired: an owner
  // writes at most one summary (per level) per window, whatever its kinds'
  // windows.
  if (timer_ == kNoTimer && timer_at_ != TimePoint{}) earliest = std::max(earliest, timer_at_ + kRepeatedLogWindow);
  if (timer_ != kNoTimer) scheduler_.cancel(timer_);
  timer_at_ = earliest;
  timer_ = scheduler_.call_at(earliest, [this] {
    timer_ = kNoTimer;
    on_timer();
  });
}

void RepeatedLines::on_timer() {
  // One line per level for every kind with lines left out, whether or not
  // its own window has ended: after it, the windows of an owner run together.
  const TimePoint now = clock_.now();
  std::map<LogLevel, std::string> by_level;
  for (auto& [reason, entry] : entries_) {
    if (entry.limiter.suppressed() == 0) continue;
    std::string& line = by_level[entry.level];
    line +=
        (line.empty() ? "" : "; ") + std::to_string(entry.limiter.take_suppressed(now)) + " x " + std::string(reason);
  }
  const auto window_s = std::chrono::duration_cast<std::chrono::seconds>(kRepeatedLogWindow).count();
  for (const auto& [level, line] : by_level)
    write_(level, "left out in the last " + std::to_string(window_s) + " s: " + line);
  arm();
}

}  // namespace jaus::rt
