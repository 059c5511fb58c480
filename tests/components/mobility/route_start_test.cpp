// The two start rules of the route drivers (issue 43, ready_start.hpp,
// docs/components.md "When a route drives"), for each kind (global/local
// waypoints, global/local path segments) on a whole vehicle node under
// virtual time:
//   1. Standby -> load -> Resume drives, as before;
//   2. in Ready, its controller's list plus its controller's Set Travel
//      Speed above zero (whichever comes last) drives: the RA
//      implementations' rule. Without a speed it waits, speed 0 stops the
//      vehicle, a non-controller's list or speed starts nothing, and after a
//      stop (Emergency, Standby, control released, the primitive driver
//      taken) nothing restarts the route but a new command of the controller.
#include <string>

#include "drive_node.hpp"
#include "jaus/components/global_path_segment_driver.hpp"
#include "jaus/components/global_waypoint_driver.hpp"
#include "jaus/components/local_frame.hpp"
#include "jaus/components/local_path_segment_driver.hpp"
#include "jaus/components/local_waypoint_driver.hpp"

namespace jaus::test {
namespace {

using components::Steering;

enum class RouteKind { global_waypoints, local_waypoints, global_path_segments, local_path_segments };

std::string route_kind_name(RouteKind k) {
  switch (k) {
    case RouteKind::global_waypoints: return "global_waypoints";
    case RouteKind::local_waypoints: return "local_waypoints";
    case RouteKind::global_path_segments: return "global_path_segments";
    case RouteKind::local_path_segments: return "local_path_segments";
  }
  return "?";
}

Address route_driver_address(RouteKind k) {
  switch (k) {
    case RouteKind::global_waypoints: return {1, 1, 45, 1};
    case RouteKind::local_waypoints: return {1, 1, 46, 1};
    case RouteKind::global_path_segments: return {1, 1, 47, 1};
    case RouteKind::local_path_segments: return {1, 1, 48, 1};
  }
  return {};
}

struct RoutePoint {
  double x_m = 0, y_m = 0;  // north, east from the vehicle's start
};

// 4 m north, then 4 m east.
const std::vector<RoutePoint> kRoute = {{4, 0}, {4, 4}};
constexpr double kSpeedMps = 0.6;

class RouteStartTest : public ::testing::TestWithParam<RouteKind> {
 protected:
  RouteStartTest()
      : node_(DriveNodeOptions{.platform = PlatformUnderTest::model,
                               .steering = Steering::differential,
                               .drivers = {"global_waypoint_driver", "local_waypoint_driver",
                                           "global_path_segment_driver", "local_path_segment_driver"}}),
        frame_(node_.host().config().vehicle.start) {
    EXPECT_TRUE(node_.wait_ready());
  }

  RouteKind kind() const { return GetParam(); }
  Address address() const { return route_driver_address(kind()); }
  bool waypoints() const { return kind() == RouteKind::global_waypoints || kind() == RouteKind::local_waypoints; }
  components::MobilityDriver& driver() { return node_.component<components::MobilityDriver>(address()); }

  bool finished() {
    if (kind() == RouteKind::global_waypoints)
      return node_.component<components::GlobalWaypointDriver>(address()).route_finished();
    if (kind() == RouteKind::local_waypoints)
      return node_.component<components::LocalWaypointDriver>(address()).route_finished();
    return node_.component<components::PathSegmentDriver>(address()).route_finished();
  }
  bool armed() {
    if (kind() == RouteKind::global_waypoints)
      return node_.component<components::GlobalWaypointDriver>(address()).armed_in_ready();
    if (kind() == RouteKind::local_waypoints)
      return node_.component<components::LocalWaypointDriver>(address()).armed_in_ready();
    return node_.component<components::PathSegmentDriver>(address()).armed_in_ready();
  }
  std::uint64_t ready_starts() {
    if (kind() == RouteKind::global_waypoints)
      return node_.component<components::GlobalWaypointDriver>(address()).waypoint_counters().ready_starts;
    if (kind() == RouteKind::local_waypoints)
      return node_.component<components::LocalWaypointDriver>(address()).waypoint_counters().ready_starts;
    return node_.component<components::PathSegmentDriver>(address()).path_counters().ready_starts;
  }
  std::size_t loaded() {
    if (kind() == RouteKind::global_waypoints)
      return node_.component<components::GlobalWaypointDriver>(address()).waypoints().size();
    if (kind() == RouteKind::local_waypoints)
      return node_.component<components::LocalWaypointDriver>(address()).waypoints().size();
    return node_.component<components::PathSegmentDriver>(address()).segment_count();
  }

  components::GeoPosition geo(const RoutePoint& p) const { return frame_.to_geo({p.x_m, p.y_m, 0}); }

  // Element `number` of this kind's list: waypoint `to`, or a straight
  // segment from `from` to `to` (P1 half way).
  void send_element(std::uint16_t number, const RoutePoint& from, const RoutePoint& to) {
    const RoutePoint mid{(from.x_m + to.x_m) / 2, (from.y_m + to.y_m) / 2};
    switch (kind()) {
      case RouteKind::local_waypoints: {
        msg::SetLocalWaypoint w;
        w.waypoint_number = number;
        w.x_m = to.x_m;
        w.y_m = to.y_m;
        node_.send(address(), w);
        break;
      }
      case RouteKind::global_waypoints: {
        msg::SetGlobalWaypoint w;
        w.waypoint_number = number;
        w.latitude_deg = geo(to).latitude_deg;
        w.longitude_deg = geo(to).longitude_deg;
        node_.send(address(), w);
        break;
      }
      case RouteKind::local_path_segments: {
        msg::SetLocalPathSegment s;
        s.path_segment_number = number;
        s.p1_x_m = mid.x_m;
        s.p1_y_m = mid.y_m;
        s.p2_x_m = to.x_m;
        s.p2_y_m = to.y_m;
        s.weighting_factor = 0;
        node_.send(address(), s);
        break;
      }
      case RouteKind::global_path_segments: {
        msg::SetGlobalPathSegment s;
        s.path_segment_number = number;
        s.p1_latitude_deg = geo(mid).latitude_deg;
        s.p1_longitude_deg = geo(mid).longitude_deg;
        s.p2_latitude_deg = geo(to).latitude_deg;
        s.p2_longitude_deg = geo(to).longitude_deg;
        s.weighting_factor = 0;
        node_.send(address(), s);
        break;
      }
    }
    node_.run_for(20ms);
  }
  // The list from the vehicle's start (elements first.. of `points`).
  void load(const std::vector<RoutePoint>& points, std::size_t first = 0) {
    for (std::size_t i = first; i < points.size(); ++i)
      send_element(static_cast<std::uint16_t>(i), i == 0 ? RoutePoint{} : points[i - 1], points[i]);
  }
  void travel_speed(double mps) {
    node_.send(address(), msg::SetTravelSpeed{{mps}});
    node_.run_for(20ms);
  }
  bool enter(rt::PrimaryStatus state) {
    return node_.run_until([&] { return node_.state_of(address()) == state; }, 1s);
  }

  RoutePoint position() {
    const auto p = *node_.pose().local_position;
    return {p.x_m, p.y_m};
  }
  double distance_to(const RoutePoint& p) { return std::hypot(position().x_m - p.x_m, position().y_m - p.y_m); }
  bool stopped() { return node_.speed_mps() < 0.01; }
  bool moving() { return node_.speed_mps() > 0.2; }
  bool drives_to_the_end() {
    return node_.run_until([&] { return finished() && !driver().driving(); }, 40s) && distance_to(kRoute.back()) < 1.0;
  }
  // Nothing moves for a while: not driving, the vehicle at rest.
  bool stays_still(rt::Duration d = 3s) {
    const RoutePoint at = position();
    node_.run_for(d);
    return !driver().driving() && stopped() && std::hypot(position().x_m - at.x_m, position().y_m - at.y_m) < 0.01;
  }

  DriveNode node_;
  components::LocalFrame frame_;
};

TEST_P(RouteStartTest, AListLoadedInReadyDrivesOnceItsControllerSetsATravelSpeed) {
  ASSERT_TRUE(node_.take_control(address()));
  ASSERT_EQ(node_.state_of(address()), rt::PrimaryStatus::ready);
  load(kRoute);
  ASSERT_EQ(loaded(), kRoute.size());
  EXPECT_TRUE(stays_still(2s));  // no travel speed set in Ready: it waits
  travel_speed(kSpeedMps);
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(drives_to_the_end());
  EXPECT_EQ(ready_starts(), 1u);
  // Finished: zero below, control released, the list kept; nothing drives again.
  EXPECT_FALSE(node_.primitive_driver().control().controller());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  EXPECT_TRUE(stays_still());
  EXPECT_EQ(loaded(), kRoute.size());
}

TEST_P(RouteStartTest, ATravelSpeedSetFirstStartsTheListAtItsFirstElement) {
  ASSERT_TRUE(node_.take_control(address()));
  travel_speed(kSpeedMps);
  EXPECT_TRUE(armed());
  EXPECT_TRUE(stays_still(1s));  // nothing to drive yet
  load(kRoute);
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(drives_to_the_end());
  EXPECT_EQ(ready_starts(), 1u);
  // Still armed after arriving: the controller's next list drives at once, and so
  // does an element appended to the finished route.
  EXPECT_TRUE(armed());
  send_element(static_cast<std::uint16_t>(kRoute.size()), kRoute.back(), {0, 4});
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(node_.run_until([&] { return finished() && !driver().driving(); }, 40s));
  EXPECT_LT(distance_to({0, 4}), 1.0);
}

TEST_P(RouteStartTest, TravelSpeedZeroStopsTheVehicleAndAnotherSpeedGoesOn) {
  ASSERT_TRUE(node_.take_control(address()));
  load(kRoute);
  travel_speed(kSpeedMps);
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 5s));
  travel_speed(0);
  EXPECT_FALSE(armed());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  const RoutePoint held = position();
  node_.run_for(3s);
  EXPECT_TRUE(stopped());
  EXPECT_LT(std::hypot(position().x_m - held.x_m, position().y_m - held.y_m), 0.01);
  travel_speed(kSpeedMps);
  EXPECT_TRUE(drives_to_the_end());
}

TEST_P(RouteStartTest, ANonControllersListAndSpeedStartNothing) {
  // Nobody controls it: the operator's list and speed are refused.
  load(kRoute);
  travel_speed(kSpeedMps);
  EXPECT_EQ(loaded(), 0u);
  EXPECT_FALSE(armed());
  EXPECT_TRUE(stays_still());
  // Its controller sets a speed, then releases control: that disarms it, so a
  // list the former controller can no longer load, and one it loads after
  // taking control again, do not start.
  ASSERT_TRUE(node_.take_control(address()));
  travel_speed(kSpeedMps);
  EXPECT_TRUE(armed());
  node_.send(address(), msg::ReleaseComponentControl{});
  ASSERT_TRUE(node_.run_until([&] { return !driver().control().controller(); }, 1s));
  EXPECT_FALSE(armed());
  load(kRoute);
  EXPECT_EQ(loaded(), 0u);
  ASSERT_TRUE(node_.take_control(address()));
  load(kRoute);
  EXPECT_EQ(loaded(), kRoute.size());
  EXPECT_TRUE(stays_still());
  EXPECT_EQ(ready_starts(), 0u);
}

TEST_P(RouteStartTest, StandbyThenLoadThenResumeDrivesAsBefore) {
  ASSERT_TRUE(node_.take_control(address()));
  node_.send(address(), msg::Standby{});
  ASSERT_TRUE(enter(rt::PrimaryStatus::standby));
  travel_speed(kSpeedMps);  // in Standby: never arms
  EXPECT_FALSE(armed());
  load(kRoute);
  EXPECT_TRUE(stays_still(1s));
  node_.send(address(), msg::Resume{});
  ASSERT_TRUE(enter(rt::PrimaryStatus::ready));
  EXPECT_TRUE(driver().driving());
  EXPECT_TRUE(drives_to_the_end());
  EXPECT_EQ(ready_starts(), 0u);
}

TEST_P(RouteStartTest, EmergencyStopsAReadyStartedRouteAndClearEmergencyDoesNotRestartIt) {
  ASSERT_TRUE(node_.take_control(address()));
  load(kRoute);
  travel_speed(kSpeedMps);
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 5s));
  node_.send(address(), msg::SetEmergency{{1}});
  ASSERT_TRUE(enter(rt::PrimaryStatus::emergency));
  EXPECT_FALSE(driver().driving());
  EXPECT_FALSE(armed());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  node_.send(address(), msg::ClearEmergency{{1}});
  ASSERT_TRUE(enter(rt::PrimaryStatus::ready));
  EXPECT_TRUE(stays_still());
  // Nor does anything the route is made of: an element appended, a replaced one.
  send_element(static_cast<std::uint16_t>(kRoute.size()), kRoute.back(), {0, 4});
  send_element(1, kRoute[0], kRoute[1]);
  EXPECT_TRUE(stays_still());
  EXPECT_EQ(ready_starts(), 1u);
  // A new command of its controller does (if it still controls it).
  if (driver().control().controller()) {
    travel_speed(kSpeedMps);
    EXPECT_TRUE(node_.run_until([&] { return moving(); }, 5s));
  }
}

TEST_P(RouteStartTest, AnOperatorTakingThePrimitiveDriverStopsAReadyStartedRouteForGood) {
  ASSERT_TRUE(node_.take_control(address()));
  load(kRoute);
  travel_speed(kSpeedMps);
  ASSERT_TRUE(node_.run_until([&] { return moving(); }, 5s));
  ASSERT_TRUE(node_.take_control(kPrimitiveDriver));  // authority 5 > the driver's 1
  EXPECT_TRUE(node_.run_until([&] { return !driver().driving(); }, 200ms));
  EXPECT_FALSE(armed());
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  node_.send(kPrimitiveDriver, msg::ReleaseComponentControl{});
  node_.run_for(100ms);
  send_element(static_cast<std::uint16_t>(kRoute.size()), kRoute.back(), {0, 4});
  EXPECT_TRUE(stays_still());
  EXPECT_EQ(ready_starts(), 1u);
}

TEST_P(RouteStartTest, ANewListWhileDrivingReplacesTheRouteAndDrivesIt) {
  ASSERT_TRUE(node_.take_control(address()));
  travel_speed(kSpeedMps);
  load({{30, 0}});
  ASSERT_TRUE(node_.run_until([&] { return position().x_m > 1.5; }, 10s));
  load(kRoute);  // element 0: a new list
  EXPECT_TRUE(driver().driving());
  EXPECT_EQ(ready_starts(), 2u);
  EXPECT_TRUE(drives_to_the_end());
}

INSTANTIATE_TEST_SUITE_P(EveryRouteDriver, RouteStartTest,
                         ::testing::Values(RouteKind::global_waypoints, RouteKind::local_waypoints,
                                           RouteKind::global_path_segments, RouteKind::local_path_segments),
                         [](const auto& p) { return route_kind_name(p.param); });

}  // namespace
}  // namespace jaus::test
