// Limits one kind of repeated log line (one reason, whoever causes it): a
// flood from a million forged senders is one reason, not a million lines.
// The first line of a window is written; the others are counted, and the next
// line written says how many were left out.
#pragma once

#include <cstdint>
#include <string>

#include "jaus/base/time.hpp"

namespace jaus::rt {

class RepeatLimiter {
 public:
  explicit RepeatLimiter(Duration window = std::chrono::seconds(10)) : window_(window) {}

  // Whether to write the line now. When it is, `note` is "" or, after lines
  // were left out, " [41203 more like this in the last 10 s]" to append.
  bool admit(TimePoint now, std::string& note);

  std::uint64_t suppressed_total() const { return suppressed_total_; }

 private:
  Duration window_;
  bool written_ = false;
  TimePoint last_written_{};
  std::uint64_t suppressed_ = 0;  // since the last line written
  std::uint64_t suppressed_total_ = 0;
};

}  // namespace jaus::rt
