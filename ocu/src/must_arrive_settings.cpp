#include "jaus/ocu/must_arrive_settings.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>

#include "jaus/ocu/must_arrive_options.hpp"

#include "jaus/base/error.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;

std::string setting_duration_text(rt::Duration d) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
  return ms % 1000 == 0 ? std::to_string(ms / 1000) + " s" : std::to_string(ms) + " ms";
}

Expected<void> setting_within(const char* name, rt::Duration value, rt::Duration least, rt::Duration most) {
  if (value >= least && value <= most) return {};
  return unexpected(make_error(ErrorCode::invalid_argument,
                               std::string(name) + " " + setting_duration_text(value) + " is out of range " +
                                   setting_duration_text(least) + ".." + setting_duration_text(most)));
}

}  // namespace

Expected<void> MustArriveSettings::check() const {
  for (const auto& r : {setting_within("give-up-after", give_up_after, 100ms, 1h),
                        setting_within("stop-give-up-after", stop_give_up_after, 100ms, 1h),
                        setting_within("resend-at-most", resend_at_most, 1ms, 60s),
                        setting_within("stop-resend-at-most", stop_resend_at_most, 1ms, 60s),
                        setting_within("rto-min", round_trip.min_timeout, 1ms, 60s),
                        setting_within("rto-max", round_trip.max_timeout, 1ms, 60s)})
    if (!r) return r;
  const auto& rto = round_trip;
  if (rto.max_timeout < rto.min_timeout)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "rto-max (" + setting_duration_text(rto.max_timeout) + ") is below rto-min (" +
                                     setting_duration_text(rto.min_timeout) + ")"));
  if (rto.initial_timeout < rto.min_timeout || rto.initial_timeout > rto.max_timeout)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "the first retransmission timeout (" + setting_duration_text(rto.initial_timeout) +
                                     ") is outside rto-min..rto-max (" + setting_duration_text(rto.min_timeout) + ".." +
                                     setting_duration_text(rto.max_timeout) + ")"));
  return {};
}

Expected<MustArriveSettings> parse_must_arrive(const MustArriveText& text) {
  MustArriveSettings settings;
  const std::pair<const char*, std::pair<const std::string*, rt::Duration*>> flags[] = {
      {"--give-up-after", {&text.give_up_after, &settings.give_up_after}},
      {"--resend-at-most", {&text.resend_at_most, &settings.resend_at_most}},
      {"--stop-give-up-after", {&text.stop_give_up_after, &settings.stop_give_up_after}},
      {"--stop-resend-at-most", {&text.stop_resend_at_most, &settings.stop_resend_at_most}},
      {"--rto-min", {&text.rto_min, &settings.round_trip.min_timeout}},
      {"--rto-max", {&text.rto_max, &settings.round_trip.max_timeout}},
  };
  for (const auto& [flag, value] : flags) {
    const std::string& written = *value.first;
    if (written.empty()) continue;
    double seconds = 0;
    const auto [end, ec] = std::from_chars(written.data(), written.data() + written.size(), seconds);
    if (ec != std::errc{} || end != written.data() + written.size() || !std::isfinite(seconds) || seconds <= 0 ||
        seconds > 86400)
      return unexpected(make_error(ErrorCode::invalid_argument,
                                   std::string(flag) + ": bad duration '" + written + "': expected seconds, more than 0"));
    *value.second = std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(seconds));
  }
  auto& rto = settings.round_trip;
  rto.initial_timeout = std::clamp(rto.initial_timeout, rto.min_timeout, std::max(rto.min_timeout, rto.max_timeout));
  if (auto checked = settings.check(); !checked) return unexpected(checked.error());
  return settings;
}

}  // namespace jaus::ocu
