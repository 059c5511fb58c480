// The waypoint drivers' rules (docs/components.md): numbering from zero,
// echo, count, travel speed, who may load, when a route drives and what
// pauses, halts or clears it, and the safety every driver keeps; on a whole
// vehicle node under virtual time.
#include <tuple>

#include "waypoint_route.hpp"

namespace jaus::test {
namespace {

using components::Steering;

const std::vector<Point> kSquare = {{6, 0}, {6, 6}, {0, 6}, {0, 0}};
const std::vector<Point> kLongLine = {{30, 0}, {60, 0}};
// Part 3 scales Travel Speed 0..10000 m/s on an unsigned short: one step is
// 0.153 m/s, so what is echoed (and driven) is the nearest step.
constexpr double kSpeedStep = 10000.0 / 65535.0;

// The local waypoint driver on the simulated differential vehicle: what the
// two kinds share is one template, so its rules are shown on one of them
// (and the global kind's own parts below).
class WaypointDriverTest : public ::testing::Test {
 protected:
  explicit WaypointDriverTest(std::map<std::string, std::string> options = {})
      : node_(waypoint_node_options(PlatformUnderTest::model, Steering::differential, std::move(options))), op_(node_) {
    EXPECT_TRUE(node_.wait_ready()) << component_states(node_);
  }
  components::LocalWaypointDriver& driver() { return op_.local_driver(); }
  std::optional<std::uint16_t> count(const Address& a = kLocalWaypointDriver) {
    const auto r = node_.ask<msg::ReportWaypointCount>(a, msg::QueryWaypointCount{});
    if (!r) return std::nullopt;
    return r->waypoint_count;
  }
  std::optional<msg::ReportLocalWaypoint> local_waypoint(std::uint16_t n) {
    return node_.ask<msg::ReportLocalWaypoint>(kLocalWaypointDriver, msg::QueryLocalWaypoint{{n}}, 200ms);
  }
  std::optional<double> travel_speed(const Address& a = kLocalWaypointDriver) {
    const auto r = node_.ask<msg::ReportTravelSpeed>(a, msg::QueryTravelSpeed{});
    if (!r) return std::nullopt;
    return r->speed_mps;
  }
  bool stopped() { return node_.speed_mps() < 0.01; }
  double commanded_linear() {
    return *node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent;
  }

  DriveNode node_;
  WaypointOperator op_;
};

TEST_F(WaypointDriverTest, NumberingFromZeroAppendsReplacesAndRefusesAGap) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  EXPECT_EQ(count(), 0);
  op_.send_local({{1, 1}, {2, 2}, {3, 3}});
  EXPECT_EQ(count(), 3);
  // number < count replaces.
  op_.send_local({{5, 5}}, 1);
  EXPECT_EQ(count(), 3);
  auto w1 = local_waypoint(1);
  ASSERT_TRUE(w1);
  EXPECT_NEAR(w1->x_m, 5, 1e-3);
  EXPECT_NEAR(w1->y_m, 5, 1e-3);
  // number > count: a gap, refused, nothing stored.
  op_.send_local({{9, 9}}, 5);
  EXPECT_EQ(count(), 3);
  EXPECT_EQ(driver().waypoint_counters().waypoints_refused, 1u);
  // number == count appends.
  op_.send_local({{4, 4}}, 3);
  EXPECT_EQ(count(), 4);
  // number 0 starts a new list.
  op_.send_local({{7, -7}});
  EXPECT_EQ(count(), 1);
  auto w0 = local_waypoint(0);
  ASSERT_TRUE(w0);
  EXPECT_NEAR(w0->x_m, 7, 1e-3);
  EXPECT_NEAR(w0->y_m, -7, 1e-3);
  // Beyond the count: no reply, never made-up data.
  EXPECT_FALSE(local_waypoint(1));
  EXPECT_EQ(driver().waypoint_counters().queries_unanswered, 1u);
  EXPECT_EQ(driver().waypoint_counters().waypoints_loaded, 6u);
}

TEST_F(WaypointDriverTest, ReportLocalWaypointEchoesTheWaypointAsSetPresenceVectorIncluded) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  msg::SetLocalWaypoint set;
  set.waypoint_number = 0;
  set.x_m = 12.5;
  set.y_m = -3.25;
  set.z_m = 1.5;       // stored and echoed, not followed
  set.yaw_rad = 1.0;
  node_.send(kLocalWaypointDriver, set);
  node_.run_for(20ms);
  const auto report = local_waypoint(0);
  ASSERT_TRUE(report);
  EXPECT_EQ(report->waypoint_number, 0);
  EXPECT_NEAR(report->x_m, 12.5, 1e-3);
  EXPECT_NEAR(report->y_m, -3.25, 1e-3);
  ASSERT_TRUE(report->z_m);
  EXPECT_NEAR(*report->z_m, 1.5, 0.01);
  ASSERT_TRUE(report->yaw_rad);
  EXPECT_NEAR(*report->yaw_rad, 1.0, 1e-3);
  EXPECT_FALSE(report->roll_rad);
  EXPECT_FALSE(report->pitch_rad);
  // Exactly what the driver received (the same message decoded).
  EXPECT_EQ(static_cast<const msg::LocalWaypointBody&>(*report), driver().waypoints().elements()[0]);
}

TEST_F(WaypointDriverTest, ReportGlobalWaypointEchoesTheWaypointAsSet) {
  ASSERT_TRUE(op_.prepare(kGlobalWaypointDriver));
  msg::SetGlobalWaypoint set;
  set.waypoint_number = 0;
  set.latitude_deg = 45.0001;
  set.longitude_deg = -73.0002;
  set.elevation_m = 52;
  node_.send(kGlobalWaypointDriver, set);
  node_.run_for(20ms);
  const auto report = node_.ask<msg::ReportGlobalWaypoint>(kGlobalWaypointDriver, msg::QueryGlobalWaypoint{{0}});
  ASSERT_TRUE(report);
  EXPECT_NEAR(report->latitude_deg, 45.0001, 1e-6);
  EXPECT_NEAR(report->longitude_deg, -73.0002, 1e-6);
  ASSERT_TRUE(report->elevation_m);
  EXPECT_NEAR(*report->elevation_m, 52, 0.01);
  EXPECT_FALSE(report->yaw_rad);
  EXPECT_EQ(count(kGlobalWaypointDriver), 1);
  EXPECT_FALSE(node_.ask<msg::ReportGlobalWaypoint>(kGlobalWaypointDriver, msg::QueryGlobalWaypoint{{1}}, 200ms));
}

TEST_F(WaypointDriverTest, OnlyTheControllerLoadsWaypointsAndTravelSpeed) {
  op_.send_local({{1, 1}});
  op_.send_travel_speed(kLocalWaypointDriver, 0.2);
  EXPECT_EQ(count(), 0);
  EXPECT_NEAR(*travel_speed(), 0.5, kSpeedStep / 2);  // the default, travel_speed_mps
  ASSERT_TRUE(node_.take_control(kLocalWaypointDriver));
  op_.send_local({{1, 1}});
  op_.send_travel_speed(kLocalWaypointDriver, 0.2);
  EXPECT_EQ(count(), 1);
  EXPECT_NEAR(*travel_speed(), 0.2, kSpeedStep / 2);
  EXPECT_DOUBLE_EQ(*travel_speed(), driver().travel_speed_mps());
}

// Without a travel speed set in Ready (start rule 2, route_start_test.cpp),
// only Resume starts a list loaded in Ready.
TEST_F(WaypointDriverTest, LoadingInReadyWithoutATravelSpeedWaitsForResume) {
  ASSERT_TRUE(node_.take_control(kLocalWaypointDriver));
  op_.send_local({{3, 0}});
  node_.run_for(2s);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped());
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  node_.run_for(1s);
  EXPECT_FALSE(driver().driving());
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(node_.run_until([&] { return driver().route_finished() && !driver().driving(); }, 20s));
  EXPECT_EQ(driver().waypoint_counters().routes_started, 1u);
}

TEST_F(WaypointDriverTest, StandbyPausesAndResumeContinuesFromTheActiveWaypoint) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local(kSquare);
  op_.send_travel_speed(kLocalWaypointDriver, 0.8);
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return driver().active_waypoint() == 2; }, 30s));
  node_.run_for(1s);
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(commanded_linear(), 0);
  EXPECT_FALSE(node_.primitive_driver().control().controller());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  const Point paused_at = op_.position();
  node_.run_for(2s);
  EXPECT_LT(distance(op_.position(), paused_at), 0.01);
  // The list and the active waypoint are kept.
  EXPECT_EQ(driver().active_waypoint(), 2u);
  EXPECT_EQ(count(), 4);
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  EXPECT_TRUE(driver().driving());
  // It continues to waypoint 2, never back to 0 or 1.
  const RouteRecord r = drive_route(node_, op_, driver(), kSquare, 40s);
  ASSERT_TRUE(driver().route_finished());
  EXPECT_EQ(r.order.front(), 2u);
  EXPECT_LE(r.closest_m[2], 0.5);
  EXPECT_LE(r.closest_m[3], 0.5);
  EXPECT_EQ(driver().waypoint_counters().routes_started, 2u);
}

TEST_F(WaypointDriverTest, AFinishedRouteDoesNotDriveAgainUntilANewList) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{2, 0}});
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return driver().route_finished() && !driver().driving(); }, 20s));
  ASSERT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  node_.run_for(2s);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped());
  EXPECT_EQ(count(), 1);  // kept for queries
  // A new list (waypoint 0) drives again on Resume.
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  op_.send_local({{2, 2}});
  EXPECT_FALSE(driver().route_finished());
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(node_.run_until([&] { return driver().route_finished() && !driver().driving(); }, 20s));
  EXPECT_LE(distance(op_.position(), {2, 2}), 1.0);
}

TEST_F(WaypointDriverTest, ANewListWhileDrivingHaltsTheRoute) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local(kLongLine);
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return node_.speed_mps() > 0.2; }, 5s));
  op_.send_local({{-5, 0}});
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(driver().last_halt(), "new list");
  EXPECT_EQ(commanded_linear(), 0);
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  node_.run_for(2s);
  EXPECT_FALSE(driver().driving());
}

TEST_F(WaypointDriverTest, TravelSpeedIsEchoedAndLimitsTheVehicle) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{8, 0}});
  op_.send_travel_speed(kLocalWaypointDriver, 0.3);
  const double echoed = *travel_speed();
  EXPECT_NEAR(echoed, 0.3, kSpeedStep / 2);
  EXPECT_DOUBLE_EQ(echoed, driver().travel_speed_mps());  // the speed driven is the one echoed
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  const RouteRecord r = drive_route(node_, op_, driver(), {{8, 0}}, 40s);
  ASSERT_TRUE(driver().route_finished());
  EXPECT_LE(r.top_speed_mps, echoed + 0.02);
  EXPECT_GE(r.top_speed_mps, echoed - 0.05);  // and it does drive at it
  // Above the vehicle's max speed (1 m/s): the vehicle's max.
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  op_.send_local({{8, 8}});
  op_.send_travel_speed(kLocalWaypointDriver, 5);
  EXPECT_NEAR(*travel_speed(), 5, kSpeedStep / 2);  // stored as commanded
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  const RouteRecord fast = drive_route(node_, op_, driver(), {{8, 8}}, 40s);
  EXPECT_LE(fast.top_speed_mps, 1.0 + 0.02);
}

TEST_F(WaypointDriverTest, TravelSpeedZeroHoldsStillWithTheRouteRunning) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{5, 0}});
  op_.send_travel_speed(kLocalWaypointDriver, 0);
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return driver().commanding(); }, 2s));
  node_.run_for(3s);
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(stopped());
  EXPECT_LT(distance(op_.position(), {0, 0}), 0.01);
  // A travel speed again: it goes on.
  op_.send_travel_speed(kLocalWaypointDriver, 0.5);
  EXPECT_TRUE(node_.run_until([&] { return driver().route_finished() && !driver().driving(); }, 20s));
}

TEST_F(WaypointDriverTest, ResetClearsTheListAndTheTravelSpeed) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local(kSquare);
  op_.send_travel_speed(kLocalWaypointDriver, 0.2);
  node_.send(kLocalWaypointDriver, msg::Reset{});
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(kLocalWaypointDriver) == rt::PrimaryStatus::ready; }, 2s));
  EXPECT_EQ(count(), 0);
  EXPECT_NEAR(*travel_speed(), 0.5, kSpeedStep / 2);
  EXPECT_DOUBLE_EQ(driver().travel_speed_mps(), 0.5);  // the option's default again
  EXPECT_FALSE(driver().driving());
}

TEST_F(WaypointDriverTest, AReplacedWaypointIsDrivenToFromTheNextStep) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{10, 0}});
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return op_.position().x_m > 2; }, 10s));
  op_.send_local({{4, 4}}, 0);  // number 0 is a new list: it halts
  EXPECT_FALSE(driver().driving());
  ASSERT_TRUE(op_.standby(kLocalWaypointDriver));
  op_.send_local({{4, -4}}, 1);  // appended
  op_.send_local({{10, 0}}, 1);  // replaced before it is driven
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return driver().active_waypoint() == 1; }, 20s));
  op_.send_local({{4, 8}}, 1);  // replaced while it is the active one
  const RouteRecord r = drive_route(node_, op_, driver(), {{4, 4}, {4, 8}}, 30s);
  ASSERT_TRUE(driver().route_finished());
  EXPECT_LE(r.closest_m[1], 0.5);
  EXPECT_LE(distance(op_.position(), {4, 8}), 1.0);
}

// The global driver's frame has its datum where the vehicle is when the
// route starts: a route loaded after the vehicle has moved is still driven
// to the waypoints' own latitude and longitude.
TEST_F(WaypointDriverTest, AGlobalRouteIsDrivenToItsLatitudeAndLongitudeFromWhereverTheVehicleIs) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{5, 3}});
  ASSERT_TRUE(op_.resume(kLocalWaypointDriver));
  ASSERT_TRUE(node_.run_until([&] { return op_.local_driver().route_finished() && !driver().driving(); }, 20s));
  ASSERT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  ASSERT_GT(distance(op_.position(), {0, 0}), 5);
  auto& global = op_.global_driver();
  ASSERT_TRUE(op_.prepare(kGlobalWaypointDriver));
  const std::vector<Point> route = {{8, 0}, {2, -4}};  // in the vehicle's start frame
  op_.send_global(route);
  ASSERT_TRUE(op_.resume(kGlobalWaypointDriver));
  const RouteRecord r = drive_route(node_, op_, global, route, 40s);
  ASSERT_TRUE(global.route_finished());
  EXPECT_LE(r.closest_m[0], 0.5);
  EXPECT_LE(r.closest_m[1], 0.5);
}

class SmallListTest : public WaypointDriverTest {
 protected:
  SmallListTest() : WaypointDriverTest({{"max_waypoints", "3"}}) {}
};

TEST_F(SmallListTest, BeyondMaxWaypointsIsRefused) {
  ASSERT_TRUE(op_.prepare(kLocalWaypointDriver));
  op_.send_local({{1, 0}, {2, 0}, {3, 0}, {4, 0}});
  EXPECT_EQ(count(), 3);
  EXPECT_EQ(driver().waypoint_counters().waypoints_refused, 1u);
  EXPECT_FALSE(local_waypoint(3));
}

// ---- the safety every driver keeps, for each kind on both platforms ----------------

enum class Kind { global, local };
using SafetyCase = std::tuple<PlatformUnderTest, Kind>;

class WaypointSafetyTest : public ::testing::TestWithParam<SafetyCase> {
 protected:
  WaypointSafetyTest()
      : node_(waypoint_node_options(std::get<0>(GetParam()), Steering::differential)), op_(node_) {
    EXPECT_TRUE(node_.wait_ready()) << component_states(node_);
  }
  bool global() const { return std::get<1>(GetParam()) == Kind::global; }
  Address address() const { return global() ? kGlobalWaypointDriver : kLocalWaypointDriver; }
  components::MobilityDriver& driver() {
    if (global()) return op_.global_driver();
    return op_.local_driver();
  }
  std::size_t active() { return global() ? op_.global_driver().active_waypoint() : op_.local_driver().active_waypoint(); }
  // A long route, driving.
  void start_route() {
    ASSERT_TRUE(op_.prepare(address()));
    if (global())
      op_.send_global(kLongLine);
    else
      op_.send_local(kLongLine);
    ASSERT_TRUE(op_.resume(address()));
    ASSERT_TRUE(node_.run_until([&] { return node_.speed_mps() > 0.3; }, 5s));
  }
  bool stopped() { return node_.speed_mps() < 0.01; }

  DriveNode node_;
  WaypointOperator op_;
};

TEST_P(WaypointSafetyTest, AnOperatorTakingThePrimitiveDriverStopsTheRouteAndNothingRestartsIt) {
  start_route();
  ASSERT_TRUE(node_.take_control(kPrimitiveDriver));  // authority 5 > the driver's 1
  EXPECT_TRUE(node_.run_until([&] { return !driver().driving(); }, 200ms));
  EXPECT_EQ(driver().mobility_counters().control_losses, 1u);
  const auto status = node_.ask<msg::ReportComponentStatus>(address(), msg::QueryComponentStatus{});
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->secondary_status & components::mobility_status::kLostControl);
  EXPECT_FALSE(status->secondary_status & components::mobility_status::kDriving);
  // The operator's primitive driver stops the vehicle (its command timeout; nothing from the route).
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  const auto efforts = driver().mobility_counters().efforts_sent;
  node_.send(kPrimitiveDriver, msg::ReleaseComponentControl{});
  node_.run_for(3s);
  EXPECT_EQ(driver().mobility_counters().efforts_sent, efforts);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped());
  // The list and the active waypoint are kept: Standby + Resume continues.
  EXPECT_EQ(active(), 0u);
  ASSERT_TRUE(op_.standby(address()));
  ASSERT_TRUE(op_.resume(address()));
  EXPECT_TRUE(node_.run_until([&] { return node_.speed_mps() > 0.3; }, 5s));
}

TEST_P(WaypointSafetyTest, SetEmergencyOnThePrimitiveDriverStopsTheRouteAndClearEmergencyDoesNotRestartIt) {
  start_route();
  node_.send(kPrimitiveDriver, msg::SetEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return !driver().driving(); }, 200ms));
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  node_.send(kPrimitiveDriver, msg::ClearEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(kPrimitiveDriver) == rt::PrimaryStatus::ready; }, 1s));
  node_.run_for(3s);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped());
  EXPECT_FALSE(node_.primitive_driver().control().controller());
}

TEST_P(WaypointSafetyTest, StandbyOnTheDriverCommandsZeroAndStopsTheVehicle) {
  start_route();
  ASSERT_TRUE(op_.standby(address()));
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(*node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent, 0);
  EXPECT_FALSE(node_.primitive_driver().control().controller());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
}

INSTANTIATE_TEST_SUITE_P(KindsAndPlatforms, WaypointSafetyTest,
                         ::testing::Combine(::testing::Values(PlatformUnderTest::model, PlatformUnderTest::clearpath_sim),
                                            ::testing::Values(Kind::global, Kind::local)),
                         [](const auto& instance) {
                           return platform_name(std::get<0>(instance.param)) +
                                  (std::get<1>(instance.param) == Kind::global ? "_global" : "_local");
                         });

}  // namespace
}  // namespace jaus::test
