// The options both waypoint drivers take (components 45 and 46), after the
// MobilityDriver's (kMobilityDriverOptionKeys).
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "jaus/components/guidance/pursuit.hpp"
#include "jaus/components/mobility_driver.hpp"

namespace jaus::components {

struct WaypointDriverOptions {
  MobilityDriverOptions mobility;
  // lookahead_m, arrival_tolerance_m, travel_speed_mps (the default travel
  // speed until a Set Travel Speed), max_deceleration_mps2.
  guidance::PursuitConfig pursuit;
  std::size_t max_waypoints = 1000;
};

// kMobilityDriverOptionKeys followed by the waypoint drivers' own keys.
const std::vector<std::string_view>& waypoint_driver_option_keys();
Expected<WaypointDriverOptions> waypoint_driver_options(const rt::KindOptions& options);

}  // namespace jaus::components
