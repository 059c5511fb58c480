// The rate at which reports arrive, measured by `jausctl subscribe`: over
// windows (printed every few seconds) and over the whole run. Sans-I/O: the
// caller passes the time.
#pragma once

#include <cstdint>
#include <string>

#include "jaus/base/time.hpp"

namespace jaus::ocu {

class RateMeter {
 public:
  struct Summary {
    std::uint64_t count = 0;
    jaus::rt::Duration span{};
    double hz = 0;
  };

  explicit RateMeter(jaus::rt::TimePoint start) : window_start_(start) {}

  void tick(jaus::rt::TimePoint now);
  // Reports since the previous window, over the window's length; starts a new window.
  Summary take_window(jaus::rt::TimePoint now);
  // Every report: the mean rate between the first and the last (a rate needs two).
  Summary total() const;
  std::uint64_t count() const { return count_; }

 private:
  jaus::rt::TimePoint window_start_;
  std::uint64_t window_count_ = 0;
  std::uint64_t count_ = 0;
  jaus::rt::TimePoint first_{};
  jaus::rt::TimePoint last_{};
};

// "25 reports in 5.0 s (5.00 Hz)"
std::string summary_text(const RateMeter::Summary& summary);

}  // namespace jaus::ocu
