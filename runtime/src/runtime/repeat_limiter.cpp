#include "jaus/runtime/repeat_limiter.hpp"

#include <cmath>

namespace jaus::rt {

bool RepeatLimiter::admit(TimePoint now, std::string& note) {
  note.clear();
  if (written_ && now - last_written_ < window_) {
    ++suppressed_;
    ++suppressed_total_;
    return false;
  }
  if (suppressed_ > 0) {
    const auto seconds = std::lround(std::chrono::duration<double>(now - last_written_).count());
    note = " [" + std::to_string(suppressed_) + " more like this in the last " + std::to_string(seconds) + " s]";
  }
  suppressed_ = 0;
  written_ = true;
  last_written_ = now;
  return true;
}

}  // namespace jaus::rt
