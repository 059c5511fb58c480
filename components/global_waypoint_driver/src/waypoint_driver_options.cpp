#include "jaus/components/waypoint_driver_options.hpp"

#include <cmath>

namespace jaus::components {

const std::vector<std::string_view>& waypoint_driver_option_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k = kMobilityDriverOptionKeys;
    for (std::string_view own : {"lookahead_m", "arrival_tolerance_m", "travel_speed_mps", "max_deceleration_mps2",
                                 "max_waypoints"})
      k.push_back(own);
    return k;
  }();
  return keys;
}

Expected<WaypointDriverOptions> waypoint_driver_options(const rt::KindOptions& options) {
  WaypointDriverOptions o;
  auto mobility = mobility_driver_options(options);
  if (!mobility) return unexpected(mobility.error());
  o.mobility = *mobility;
  struct Number {
    std::string_view key;
    double min, max;
    double* value;
  };
  // Set Travel Speed may say 0 (hold still); as the default, 0 would make
  // every route stand still. Above the vehicle's max speed the max is driven.
  const Number numbers[] = {
      {"lookahead_m", 0, 100, &o.pursuit.lookahead_m},
      {"arrival_tolerance_m", 0, 100, &o.pursuit.arrival_tolerance_m},
      {"travel_speed_mps", 0, 100, &o.pursuit.travel_speed_mps},
      {"max_deceleration_mps2", 0, 100, &o.pursuit.max_deceleration_mps2},
  };
  for (const auto& n : numbers) {
    const auto v = rt::number_option(options, n.key, n.min, n.max, *n.value, /*min_exclusive=*/true);
    if (!v) return unexpected(v.error());
    *n.value = *v;
  }
  const auto max = rt::number_option(options, "max_waypoints", 1, 65535, static_cast<double>(o.max_waypoints));
  if (!max) return unexpected(max.error());
  if (*max != std::floor(*max)) return unexpected(rt::option_error(options, "max_waypoints", "a whole number 1..65535"));
  o.max_waypoints = static_cast<std::size_t>(*max);
  return o;
}

}  // namespace jaus::components
