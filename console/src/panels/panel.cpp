#include "jaus/console/panels/panel.hpp"

#include <ctime>

namespace jaus::console {

namespace {

std::string iso_time(jaus::rt::UtcTime time) {
  const auto since = time.time_since_epoch();
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(since);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(since - seconds).count();
  const std::time_t t = seconds.count();
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[40];
  const auto n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[64];
  std::snprintf(out, sizeof out, "%.*s.%03dZ", static_cast<int>(n), text, static_cast<int>(millis));
  return out;
}

}  // namespace

void Pages::refuse(PageId page, const std::string& why) {
  ++frames_refused_;
  to_page(page, ErrorFrame{why});
}

void Pages::event(EventLevel level, const std::string& text) {
  if (log_)
    log_(level == EventLevel::info   ? jaus::rt::LogLevel::info
         : level == EventLevel::warn ? jaus::rt::LogLevel::warn
                                     : jaus::rt::LogLevel::error,
         text);
  to_all(EventFrame{iso_time(clock_.utc_now()), level, text});
}

void Periodic::start(std::chrono::milliseconds period, std::function<void()> task) {
  stop();
  period_ = period;
  task_ = std::move(task);
  running_ = true;
  arm();
}

void Periodic::stop() {
  running_ = false;
  scheduler_.cancel(timer_);
  timer_ = jaus::rt::kNoTimer;
}

void Periodic::arm() {
  timer_ = scheduler_.call_at(clock_.now() + period_, [this] {
    timer_ = jaus::rt::kNoTimer;
    task_();
    if (running_ && timer_ == jaus::rt::kNoTimer) arm();  // unless the task stopped or restarted it
  });
}

void Panel::unsubscribe_all() {
  for (auto id : subscriptions_) context_.session.component().unsubscribe(id);
  subscriptions_.clear();
}

}  // namespace jaus::console
