#include "jaus/components/sensor_component.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace jaus::components {

namespace {
// Staleness is polled this often while stale (stale_after / 4), never faster.
constexpr int kChecksPerStalePeriod = 4;
constexpr rt::Duration kMinimumCheckPeriod = std::chrono::milliseconds(10);

std::string seconds_text(rt::Duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", std::chrono::duration<double>(d).count());
  return text;
}
}  // namespace

// As Report Time builds its time stamp (component.cpp, Query Time).
TimeStamp time_stamp_of(rt::UtcTime utc) {
  using namespace std::chrono;
  const auto day = floor<days>(utc);
  const year_month_day date{sys_days{day}};
  const hh_mm_ss time{floor<milliseconds>(utc - day)};
  return TimeStamp{static_cast<std::uint16_t>(time.subseconds().count()),
                   static_cast<std::uint8_t>(time.seconds().count()),
                   static_cast<std::uint8_t>(time.minutes().count()),
                   static_cast<std::uint8_t>(time.hours().count()),
                   static_cast<std::uint8_t>(static_cast<unsigned>(date.day()))};
}

SensorComponent::SensorComponent(rt::ComponentConfig config, rt::Environment env, PoseSource& source,
                                 SensorOptions options)
    : Component(std::move(config), std::move(env)), source_(source), options_(options) {}

SensorComponent::~SensorComponent() {
  if (watch_timer_ != rt::kNoTimer) env().scheduler.cancel(watch_timer_);
}

bool SensorComponent::initialize() {
  // Without a fresh sample yet (a receiver without a fix, a platform not
  // heard from) the sensor waits in Initialize, the RA's state for it, and
  // the watch ends the wait at the first fresh sample; never a failed
  // initialisation, which would wait for an operator's Reset. Once Ready the
  // watch goes on from state_changed.
  const auto sample = source_.sample();
  const rt::TimePoint now = env().clock.now();
  if (!sample || now - sample->taken_at >= options_.stale_after) {
    wait_for_hardware("a fresh sample from its pose source");
    arm_watch(now + check_period());
  }
  return true;
}

void SensorComponent::state_changed(rt::PrimaryStatus, rt::PrimaryStatus after) {
  // Entering Ready or Standby, or returning from Emergency to a failure this
  // watch declared: the source is looked at now, not at the next check.
  if (after == rt::PrimaryStatus::ready || after == rt::PrimaryStatus::standby ||
      (after == rt::PrimaryStatus::failure && failure_declared()))
    check_source();
  if (after == rt::PrimaryStatus::shutdown && watch_timer_ != rt::kNoTimer) {
    env().scheduler.cancel(watch_timer_);  // a shut-down component watches nothing
    watch_timer_ = rt::kNoTimer;
  }
}

rt::Duration SensorComponent::check_period() const {
  return std::max(options_.stale_after / kChecksPerStalePeriod, kMinimumCheckPeriod);
}

void SensorComponent::arm_watch(rt::TimePoint when) {
  if (watch_timer_ != rt::kNoTimer) env().scheduler.cancel(watch_timer_);
  watch_timer_ = env().scheduler.call_at(when, [this] { check_source(); });
}

void SensorComponent::check_source() {
  if (watch_timer_ != rt::kNoTimer) env().scheduler.cancel(watch_timer_);
  watch_timer_ = rt::kNoTimer;
  if (state() == rt::PrimaryStatus::shutdown) return;  // cancelled on Shutdown; never acts after it

  const rt::TimePoint now = env().clock.now();
  const auto sample = source_.sample();
  const rt::Duration age = sample ? now - sample->taken_at : rt::Duration::max();
  stale_ = age >= options_.stale_after;
  if (waiting_for_hardware()) {
    if (stale_) arm_watch(now + check_period());
    else hardware_ready();  // -> Ready, whose state_changed looks at the source again
    return;
  }
  if (stale_) {
    // A no-op unless Ready or Standby (already failed, or in Emergency: checked again next period).
    declare_failure(sample ? "pose source stale: last sample " + seconds_text(age) + " s old"
                           : std::string("pose source stale: no sample yet"));
    arm_watch(now + check_period());
    return;
  }
  clear_failure("pose source fresh again");  // a no-op unless this watch declared the failure
  // Still failed (the failure waits in Emergency): poll until it clears.
  if (failure_declared()) {
    arm_watch(now + check_period());
    return;
  }
  // Fresh: nothing can turn stale before the newest sample does (a sample
  // claiming to be from the future is checked again after stale_after).
  arm_watch(std::min(sample->taken_at, now) + options_.stale_after);
}

Expected<SensorOptions> sensor_options(const rt::KindOptions& options) {
  SensorOptions o;
  const auto stale = rt::seconds_option(options, "stale_after_s", 0, 60, o.stale_after, /*min_exclusive=*/true);
  if (!stale) return unexpected(stale.error());
  o.stale_after = *stale;
  return o;
}

}  // namespace jaus::components
