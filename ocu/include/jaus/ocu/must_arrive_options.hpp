// The must-arrive settings (must_arrive_settings.hpp) on a command line,
// the same in jausctl and jaus-console: --give-up-after, --resend-at-most,
// --stop-give-up-after, --stop-resend-at-most, --rto-min, --rto-max, each in
// seconds. add_must_arrive_options() takes any CLI11 app (a template, so the
// library itself does not depend on CLI11); parse_must_arrive() turns what
// was written into settings, or one line naming the flag that is wrong.
#pragma once

#include <chrono>
#include <sstream>
#include <string>

#include "jaus/base/expected.hpp"
#include "jaus/ocu/must_arrive_settings.hpp"

namespace jaus::ocu {

// As written; empty: the default.
struct MustArriveText {
  std::string give_up_after;
  std::string resend_at_most;
  std::string stop_give_up_after;
  std::string stop_resend_at_most;
  std::string rto_min;
  std::string rto_max;
};

// Each a number of seconds (more than 0), then the settings' ranges
// (MustArriveSettings::check); the first retransmission timeout is the
// default's, moved within --rto-min..--rto-max. invalid_argument otherwise.
Expected<MustArriveSettings> parse_must_arrive(const MustArriveText& text);

inline constexpr const char* kMustArriveGroup =
    "Commands that must arrive (ACK requested, sent again at the pace of the measured round trip)";

template <class App>
void add_must_arrive_options(App* app, MustArriveText& text) {
  const MustArriveSettings defaults;
  const auto add = [&](const char* name, std::string& value, const char* what, rt::Duration fallback) {
    std::ostringstream seconds;  // 3, 0.1, 0.05
    seconds << std::chrono::duration<double>(fallback).count();
    app->add_option(name, value, what)->type_name("SECONDS")->default_str(seconds.str())->group(kMustArriveGroup);
  };
  add("--give-up-after", text.give_up_after, "a command is given up this long after its first send",
      defaults.give_up_after);
  add("--resend-at-most", text.resend_at_most, "a command is sent again at least this often",
      defaults.resend_at_most);
  add("--stop-give-up-after", text.stop_give_up_after,
      "a stop (Set Emergency, Standby, Shutdown): given up this long after its first send",
      defaults.stop_give_up_after);
  add("--stop-resend-at-most", text.stop_resend_at_most, "a stop is sent again at least this often",
      defaults.stop_resend_at_most);
  add("--rto-min", text.rto_min, "the retransmission timeout's least value", defaults.round_trip.min_timeout);
  add("--rto-max", text.rto_max, "the retransmission timeout's greatest value", defaults.round_trip.max_timeout);
}

}  // namespace jaus::ocu
