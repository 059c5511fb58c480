// The waypoint drivers' guidance, measured (prints, asserts nothing): a
// square of four waypoints (8 m sides) through the global and the local
// waypoint driver on a whole vehicle node under virtual time
// (tests/components/mobility/drive_node.hpp), both drivetrains, on the
// simulated vehicle and the in-process Clearpath platform. Per run: the
// cross-track error (the vehicle's distance from the leg it drives, sampled
// at every guidance step, 20 Hz), its mean and max; the closest approach to
// each waypoint; the time to reach each; where the vehicle came to rest.
#include <cstdio>
#include <exception>

#include "waypoint_route.hpp"

namespace {

using namespace jaus;
using namespace jaus::test;
using components::Steering;

const std::vector<Point> kSquare = {{8, 0}, {8, 8}, {0, 8}, {0, 0}};
constexpr double kTravelSpeed = 0.8;

void run(PlatformUnderTest platform, Steering steering, bool global) {
  const auto options = waypoint_node_options(platform, steering);
  DriveNode node(options);
  WaypointOperator op(node);
  if (!node.wait_ready()) {
    std::printf("%-14s %-12s %-6s not ready: %s\n", platform_name(platform).c_str(),
                steering == Steering::ackermann ? "ackermann" : "differential", global ? "global" : "local",
                component_states(node).c_str());
    return;
  }
  const Address driver_address = global ? kGlobalWaypointDriver : kLocalWaypointDriver;
  op.prepare(driver_address);
  if (global)
    op.send_global(kSquare);
  else
    op.send_local(kSquare);
  op.send_travel_speed(driver_address, kTravelSpeed);
  op.resume(driver_address);
  const RouteRecord r = global ? drive_route(node, op, op.global_driver(), kSquare, 120s)
                               : drive_route(node, op, op.local_driver(), kSquare, 120s);
  node.run_until([&] { return node.speed_mps() < 0.01; }, 5s);
  const bool finished = global ? op.global_driver().route_finished() : op.local_driver().route_finished();
  std::printf("%-14s %-12s %-6s %6.3f %6.3f   %5.1f %5.1f %5.1f %5.1f   %4.2f %4.2f %4.2f %4.2f   %5.2f %s\n",
              platform_name(platform).c_str(), steering == Steering::ackermann ? "ackermann" : "differential",
              global ? "global" : "local", r.cross_track_mean_m(), r.cross_track_max_m, r.reached_at_s[0],
              r.reached_at_s[1], r.reached_at_s[2], r.reached_at_s[3], r.closest_m[0], r.closest_m[1], r.closest_m[2],
              r.closest_m[3], distance(op.position(), kSquare.back()), finished ? "" : "(not finished)");
}

}  // namespace

int main() {
  std::printf("bench_waypoints: a square of four waypoints, 8 m sides, Set Travel Speed %.1f m/s, arrival "
              "tolerance 0.5 m, virtual time\n",
              kTravelSpeed);
  std::printf("%-14s %-12s %-6s %13s   %-23s   %-19s   %s\n", "platform", "drivetrain", "driver", "cross-track m",
              "reached waypoint at s", "closest to each m", "rest m");
  std::printf("%-14s %-12s %-6s %6s %6s   %5s %5s %5s %5s   %4s %4s %4s %4s   %5s\n", "", "", "", "mean", "max", "1",
              "2", "3", "4", "1", "2", "3", "4", "last");
  try {
    for (const auto platform : {PlatformUnderTest::model, PlatformUnderTest::clearpath_sim})
      for (const auto steering : {Steering::differential, Steering::ackermann})
        for (const bool global : {true, false}) run(platform, steering, global);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_waypoints: %s\n", e.what());
    return 1;
  }
  return 0;
}
