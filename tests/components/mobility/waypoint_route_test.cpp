// The "done when" for the waypoint drivers: a square of four global
// waypoints and one of local waypoints, each reached within the arrival
// tolerance in order, the route finishing with the vehicle at rest near the
// last, its driver having stopped and released the primitive driver; on
// both platforms and both drivetrains, under virtual time.
#include <cstdio>
#include <tuple>

#include "waypoint_route.hpp"

namespace jaus::test {
namespace {

using components::Steering;

// 6 m sides, clockwise (right turns), back to the start.
const std::vector<Point> kSquare = {{6, 0}, {6, 6}, {0, 6}, {0, 0}};
constexpr double kTolerance = 0.5;  // arrival_tolerance_m's default
constexpr double kTravelSpeed = 0.8;

using Vehicle = std::tuple<PlatformUnderTest, Steering>;

class WaypointSquareTest : public ::testing::TestWithParam<Vehicle> {
 protected:
  WaypointSquareTest()
      : options_(waypoint_node_options(std::get<0>(GetParam()), std::get<1>(GetParam()))),
        node_(options_),
        op_(node_) {
    EXPECT_TRUE(node_.wait_ready()) << component_states(node_);
  }

  template <class Driver>
  void expect_square_driven(Driver& driver, const Address& address, const char* what) {
    ASSERT_TRUE(op_.resume(address));
    ASSERT_TRUE(node_.run_until([&] { return driver.commanding(); }, 2s));
    const RouteRecord r = drive_route(node_, op_, driver, kSquare, 90s);
    ASSERT_TRUE(driver.route_finished()) << "active waypoint " << driver.active_waypoint();
    // In order, each within the tolerance.
    EXPECT_EQ(r.order, (std::vector<std::size_t>{0, 1, 2, 3}));
    for (std::size_t i = 0; i < kSquare.size(); ++i) EXPECT_LE(r.closest_m[i], kTolerance) << "waypoint " << i;
    // Finished: zero below, the primitive driver released, the list kept.
    EXPECT_FALSE(driver.driving());
    EXPECT_EQ(driver.mobility_counters().arrivals, 1u);
    EXPECT_EQ(driver.waypoint_counters().routes_finished, 1u);
    EXPECT_EQ(*node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent, 0);
    EXPECT_FALSE(node_.primitive_driver().control().controller());
    EXPECT_EQ(driver.waypoints().size(), 4u);
    ASSERT_TRUE(node_.run_until([&] { return node_.speed_mps() < 0.01; }, 5s));
    const double final_error = distance(op_.position(), kSquare.back());
    EXPECT_LE(final_error, 1.0);
    EXPECT_LE(r.top_speed_mps, kTravelSpeed + 0.05);
    // The numbers the report quotes.
    std::printf("[ measured ] %s %s %s: closest %.2f %.2f %.2f %.2f m; at rest %.2f m from the last; cross-track "
                "mean %.2f max %.2f m; reached at %.1f %.1f %.1f %.1f s; top speed %.2f m/s\n",
                what, platform_name(std::get<0>(GetParam())).c_str(),
                std::get<1>(GetParam()) == Steering::ackermann ? "ackermann" : "differential", r.closest_m[0],
                r.closest_m[1], r.closest_m[2], r.closest_m[3], final_error, r.cross_track_mean_m(),
                r.cross_track_max_m, r.reached_at_s[0], r.reached_at_s[1], r.reached_at_s[2], r.reached_at_s[3],
                r.top_speed_mps);
  }

  DriveNodeOptions options_;
  DriveNode node_;
  WaypointOperator op_;
};

TEST_P(WaypointSquareTest, FourGlobalWaypointsAreEachReachedInOrderAndTheRouteFinishes) {
  ASSERT_TRUE(op_.prepare(kGlobalWaypointDriver));
  op_.send_global(kSquare);
  op_.send_travel_speed(kGlobalWaypointDriver, kTravelSpeed);
  ASSERT_EQ(op_.global_driver().waypoints().size(), 4u);
  expect_square_driven(op_.global_driver(), kGlobalWaypointDriver, "global");
}

TEST_P(WaypointSquareTest, FourLocalWaypointsAreEachReachedInOrderAndTheRouteFinishes) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local(kSquare);
  op_.send_travel_speed(kLocalWaypointDriver, kTravelSpeed);
  ASSERT_EQ(op_.local_driver().waypoints().size(), 4u);
  expect_square_driven(op_.local_driver(), kLocalWaypointDriver, "local");
}

INSTANTIATE_TEST_SUITE_P(Vehicles, WaypointSquareTest,
                         ::testing::Combine(::testing::Values(PlatformUnderTest::model, PlatformUnderTest::clearpath_sim),
                                            ::testing::Values(Steering::differential, Steering::ackermann)),
                         [](const auto& instance) {
                           return platform_name(std::get<0>(instance.param)) + "_" +
                                  (std::get<1>(instance.param) == Steering::ackermann ? "ackermann" : "differential");
                         });

}  // namespace
}  // namespace jaus::test
