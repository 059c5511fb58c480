// The waypoint drivers' options (waypoint_driver_options.hpp): defaults,
// ranges, and the errors naming the key, as jausd --check-config shows them.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "jaus/components/global_waypoint_driver_kind.hpp"
#include "jaus/components/local_waypoint_driver_kind.hpp"
#include "jaus/components/waypoint_driver_options.hpp"

namespace jaus::components {
namespace {

Expected<WaypointDriverOptions> read(const std::map<std::string, std::string>& values) {
  return waypoint_driver_options(rt::KindOptions{"global_waypoint_driver", values});
}

TEST(WaypointDriverOptions, Defaults) {
  const auto o = read({});
  ASSERT_TRUE(o);
  EXPECT_EQ(o->pursuit.lookahead_m, 1.0);
  EXPECT_EQ(o->pursuit.arrival_tolerance_m, 0.5);
  EXPECT_EQ(o->pursuit.travel_speed_mps, 0.5);
  EXPECT_EQ(o->max_waypoints, 1000u);
  EXPECT_EQ(o->mobility.command_rate_hz, 20);
}

TEST(WaypointDriverOptions, ReadsEveryKey) {
  const auto o = read({{"lookahead_m", "2"},
                       {"arrival_tolerance_m", "0.25"},
                       {"travel_speed_mps", "1.5"},
                       {"max_deceleration_mps2", "0.8"},
                       {"max_waypoints", "20"},
                       {"command_rate_hz", "10"}});
  ASSERT_TRUE(o) << o.error().message();
  EXPECT_EQ(o->pursuit.lookahead_m, 2);
  EXPECT_EQ(o->pursuit.arrival_tolerance_m, 0.25);
  EXPECT_EQ(o->pursuit.travel_speed_mps, 1.5);
  EXPECT_EQ(o->pursuit.max_deceleration_mps2, 0.8);
  EXPECT_EQ(o->max_waypoints, 20u);
  EXPECT_EQ(o->mobility.command_rate_hz, 10);
}

TEST(WaypointDriverOptions, RefusesWhatIsOutOfRangeNamingTheKey) {
  for (const auto& [key, value] : std::map<std::string, std::string>{{"lookahead_m", "0"},
                                                                     {"arrival_tolerance_m", "-1"},
                                                                     {"travel_speed_mps", "0"},
                                                                     {"max_deceleration_mps2", "x"},
                                                                     {"max_waypoints", "0"},
                                                                     {"primitive_driver", "1.1.33"}}) {
    const auto o = read({{key, value}});
    ASSERT_FALSE(o) << key << "=" << value;
    EXPECT_NE(o.error().message().find(key), std::string::npos) << o.error().message();
  }
  const auto fraction = read({{"max_waypoints", "2.5"}});
  ASSERT_FALSE(fraction);
  EXPECT_NE(fraction.error().message().find("whole number"), std::string::npos) << fraction.error().message();
}

TEST(WaypointDriverKinds, DescribeThemselves) {
  const auto& global = global_waypoint_driver_kind();
  const auto& local = local_waypoint_driver_kind();
  EXPECT_EQ(global.name, "global_waypoint_driver");
  EXPECT_EQ(global.default_id, 45);
  EXPECT_EQ(local.name, "local_waypoint_driver");
  EXPECT_EQ(local.default_id, 46);
  for (const auto* kind : {&global, &local}) {
    EXPECT_TRUE(kind->moves_hardware);
    EXPECT_FALSE(kind->one_per_node);
    EXPECT_EQ(kind->needs, std::vector<std::string_view>{PoseSource::kInterface});
    EXPECT_EQ(kind->options, waypoint_driver_option_keys());
    EXPECT_TRUE(kind->check(rt::KindOptions{kind->name, {}}));
  }
}

}  // namespace
}  // namespace jaus::components
