// Limits one kind of repeated log line (one reason, whoever causes it): a
// flood from a million forged senders is one reason, not a million lines.
//
// RepeatLimiter decides, for one reason: the first `burst` lines of a window
// are written, the others counted. RepeatedLines owns the timer that writes,
// when a window ends with lines left out, one summary line for all its kinds
// ("left out in the last 10 s: 41203 x commands from a non-controller not
// executed; 12 x Clear Emergency from a non-holder refused"): a flood that
// stops still has its count written, and a flood that goes on writes one line
// per owner and window.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"

namespace jaus::rt {

inline constexpr Duration kRepeatedLogWindow = std::chrono::seconds(10);
// Lines an operator should see one by one in normal operation (state and
// control changes, service connections made and ended): a flood writes this
// many per window, then a count.
inline constexpr int kNoteworthyBurst = 10;
// Whatever the kinds, one owner writes at most this many limited lines per
// window (summaries aside): a flood touching every kind of a component is a
// few lines every 10 s, not one per kind. Noteworthy kinds (a burst above 1)
// share a budget of their own, so that refusals never hide a state change.
inline constexpr int kOwnerLinesPerWindow = 8;
inline constexpr int kOwnerNoteworthyLinesPerWindow = 20;

// The kind of a repeated line: a string literal naming it ("unsupported
// messages ignored") and how many lines of it a window writes.
struct Repeated {
  constexpr Repeated(const char* name, int lines_per_window = 1) : reason(name), burst(lines_per_window) {}
  // A name with static storage (e.g. to_string of an enumeration).
  constexpr Repeated(std::string_view name, int lines_per_window = 1) : reason(name), burst(lines_per_window) {}
  std::string_view reason;
  int burst;
};

class RepeatLimiter {
 public:
  // (The owner's RepeatedLines names the kind in its summary line.)
  explicit RepeatLimiter(Duration window = kRepeatedLogWindow, int burst = 1) : window_(window), burst_(burst) {}

  // Whether to write the line now. When it is, `note` is "" or, after lines
  // were left out and no summary said so, " [41203 more like this in the
  // last 10 s]" to append.
  bool admit(TimePoint now, std::string& note);
  // Counts a line its owner's budget left out (RepeatedLines), as admit()
  // counts those of its own window.
  void count_suppressed(TimePoint now);
  // The lines left out so far, which the caller writes in a summary; the
  // next window starts now, without a line of its own (a flood that goes on
  // is one summary per window).
  std::uint64_t take_suppressed(TimePoint now);

  TimePoint window_end() const { return window_start_ + window_; }
  std::uint64_t suppressed() const { return suppressed_; }  // in the current window
  std::uint64_t suppressed_total() const { return suppressed_total_; }

 private:
  Duration window_;
  int burst_;
  bool window_open_ = false;
  TimePoint window_start_{};
  int lines_in_window_ = 0;
  std::uint64_t suppressed_ = 0;
  std::uint64_t suppressed_total_ = 0;
};

// The lines of one owner (a component, a node, a link) that remote input can
// repeat, each with the limiter of its reason, and the one timer that writes
// their summaries. A reason is a string literal naming the kind of line
// ("unsupported messages ignored"): the number of limiters is the number of
// reasons in the code, never a number of senders. Single-threaded, like the
// runtime.
class RepeatedLines {
 public:
  RepeatedLines(Clock& clock, Scheduler& scheduler, LogFn write)
      : clock_(clock), scheduler_(scheduler), write_(std::move(write)) {}
  ~RepeatedLines();
  RepeatedLines(const RepeatedLines&) = delete;
  RepeatedLines& operator=(const RepeatedLines&) = delete;

  // Writes make_text() (built only then) if the limiter of its kind admits
  // it (the first `burst` lines of a window); otherwise counts it, and the
  // count is written when the window ends.
  template <class MakeText>
  void write(Repeated kind, LogLevel level, MakeText make_text) {
    std::string note;
    if (admit(kind, level, note)) write_(level, make_text() + note);
  }

  std::uint64_t suppressed_total() const;

 private:
  struct Entry {
    RepeatLimiter limiter;
    LogLevel level;
  };
  Entry& entry_for(Repeated kind, LogLevel level);
  bool admit(Repeated kind, LogLevel level, std::string& note);
  void arm();
  void on_timer();

  Clock& clock_;
  Scheduler& scheduler_;
  LogFn write_;
  std::map<std::string_view, Entry> entries_;
  TimerId timer_ = kNoTimer;
  TimePoint timer_at_{};
  TimePoint budget_window_start_{};
  int budget_used_ = 0;             // by kinds of one line per window
  int noteworthy_budget_used_ = 0;  // by noteworthy kinds
  bool budget_window_open_ = false;
};

}  // namespace jaus::rt
