#include "jaus/ocu/rate_meter.hpp"

#include <cstdio>

namespace jaus::ocu {

namespace {
double seconds(jaus::rt::Duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

void RateMeter::tick(jaus::rt::TimePoint now) {
  if (count_ == 0) first_ = now;
  last_ = now;
  ++count_;
  ++window_count_;
}

RateMeter::Summary RateMeter::take_window(jaus::rt::TimePoint now) {
  Summary s;
  s.count = window_count_;
  s.span = now - window_start_;
  s.hz = s.span > jaus::rt::Duration::zero() ? static_cast<double>(s.count) / seconds(s.span) : 0;
  window_start_ = now;
  window_count_ = 0;
  return s;
}

RateMeter::Summary RateMeter::total() const {
  Summary s;
  s.count = count_;
  s.span = count_ > 0 ? last_ - first_ : jaus::rt::Duration::zero();
  s.hz = count_ >= 2 && s.span > jaus::rt::Duration::zero() ? static_cast<double>(count_ - 1) / seconds(s.span) : 0;
  return s;
}

std::string summary_text(const RateMeter::Summary& summary) {
  char text[96];
  std::snprintf(text, sizeof text, "%llu report%s in %.1f s (%.2f Hz)", static_cast<unsigned long long>(summary.count),
                summary.count == 1 ? "" : "s", seconds(summary.span), summary.hz);
  return text;
}

}  // namespace jaus::ocu
