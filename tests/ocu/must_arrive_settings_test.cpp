// How hard an operator unit tries (jaus/ocu/must_arrive_settings.hpp,
// must_arrive_options.hpp): the default settings give the library's
// policies, a stop's code picks the stop's policy, and the command line's
// text is checked (each flag named in the error) before anything is sent.
#include <gtest/gtest.h>

#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/must_arrive_options.hpp"

namespace jausctl::test {
namespace {

using namespace std::chrono_literals;
using jaus::ocu::MustArrivePolicy;
using jaus::ocu::MustArriveSettings;
using jaus::ocu::MustArriveText;

void expect_same(const MustArrivePolicy& a, const MustArrivePolicy& b) {
  EXPECT_EQ(a.retransmit_after, b.retransmit_after);
  EXPECT_EQ(a.max_transmissions, b.max_transmissions);
  EXPECT_EQ(a.timing, b.timing);
  EXPECT_EQ(a.give_up_after, b.give_up_after);
  EXPECT_EQ(a.max_retransmit_after, b.max_retransmit_after);
  EXPECT_EQ(a.back_off, b.back_off);
  EXPECT_EQ(a.unmeasured_wait, b.unmeasured_wait);
}

TEST(MustArriveSettings, TheDefaultsGiveTheLibrarysPolicies) {
  const MustArriveSettings defaults;
  EXPECT_TRUE(defaults.check());
  expect_same(MustArrivePolicy::command(defaults), MustArrivePolicy{});
  expect_same(MustArrivePolicy::stop(defaults), MustArrivePolicy::emergency());
}

TEST(MustArriveSettings, AStopsCodePicksTheStopsPolicy) {
  MustArriveSettings settings;
  settings.stop_give_up_after = 30s;
  settings.give_up_after = 7s;
  for (const std::uint16_t stop : {jaus::msg::SetEmergency::code, jaus::msg::Standby::code, jaus::msg::Shutdown::code})
    EXPECT_EQ(MustArrivePolicy::for_code(stop, settings).give_up_after, 30s) << stop;
  for (const std::uint16_t command : {jaus::msg::ClearEmergency::code, jaus::msg::Resume::code})
    EXPECT_EQ(MustArrivePolicy::for_code(command, settings).give_up_after, 7s) << command;
  // Never doubled, at least every stop_resend_at_most; enough copies for the whole deadline.
  const auto stop = MustArrivePolicy::stop(settings);
  EXPECT_FALSE(stop.back_off);
  EXPECT_EQ(stop.max_retransmit_after, 100ms);
  EXPECT_GE(stop.max_transmissions, 30s / 50ms);
}

TEST(MustArriveSettings, ACommandHasCopiesEnoughForItsDeadline) {
  MustArriveSettings settings;
  settings.give_up_after = 60s;
  EXPECT_GE(MustArrivePolicy::command(settings).max_transmissions, 60u);
}

TEST(MustArriveOptions, NothingWrittenIsTheDefaults) {
  const auto parsed = jaus::ocu::parse_must_arrive(MustArriveText{});
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->give_up_after, 3s);
  EXPECT_EQ(parsed->stop_give_up_after, 10s);
  EXPECT_EQ(parsed->round_trip.initial_timeout, 100ms);
}

TEST(MustArriveOptions, ASlowLinksValues) {
  MustArriveText text;
  text.give_up_after = "20";
  text.stop_give_up_after = "60";
  text.resend_at_most = "4";
  text.rto_min = "0.5";
  text.rto_max = "8";
  const auto parsed = jaus::ocu::parse_must_arrive(text);
  ASSERT_TRUE(parsed) << parsed.error().message();
  EXPECT_EQ(parsed->give_up_after, 20s);
  EXPECT_EQ(parsed->stop_give_up_after, 60s);
  EXPECT_EQ(parsed->resend_at_most, 4s);
  EXPECT_EQ(parsed->round_trip.min_timeout, 500ms);
  EXPECT_EQ(parsed->round_trip.max_timeout, 8s);
  EXPECT_EQ(parsed->round_trip.initial_timeout, 500ms) << "the first timeout moves within the bounds";
}

TEST(MustArriveOptions, BadValuesNameTheirFlag) {
  MustArriveText text;
  text.stop_give_up_after = "ten";
  auto parsed = jaus::ocu::parse_must_arrive(text);
  ASSERT_FALSE(parsed);
  EXPECT_EQ(parsed.error().code, jaus::ErrorCode::invalid_argument);
  EXPECT_EQ(parsed.error().message(), "--stop-give-up-after: bad duration 'ten': expected seconds, more than 0");

  text = {};
  text.give_up_after = "0.05";
  parsed = jaus::ocu::parse_must_arrive(text);
  ASSERT_FALSE(parsed);
  EXPECT_EQ(parsed.error().message(), "give-up-after 50 ms is out of range 100 ms..3600 s");

  text = {};
  text.rto_min = "3";
  text.rto_max = "1";
  parsed = jaus::ocu::parse_must_arrive(text);
  ASSERT_FALSE(parsed);
  EXPECT_EQ(parsed.error().message(), "rto-max (1 s) is below rto-min (3 s)");
}

}  // namespace
}  // namespace jausctl::test
