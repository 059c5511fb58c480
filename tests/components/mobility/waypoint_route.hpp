// What the waypoint driver tests share: a vehicle node hosting both waypoint
// drivers (drive_node.hpp), an operator that loads a route the RA's way
// (control of the driver, Standby, the waypoints, Resume), and a recorder of
// how the vehicle drove it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "drive_node.hpp"
#include "jaus/components/global_waypoint_driver.hpp"
#include "jaus/components/local_frame.hpp"
#include "jaus/components/local_waypoint_driver.hpp"

namespace jaus::test {

inline const Address kGlobalWaypointDriver{1, 1, 45, 1};
inline const Address kLocalWaypointDriver{1, 1, 46, 1};

struct Point {
  double x_m = 0, y_m = 0;  // north, east in the vehicle's local frame
};

inline double distance(const Point& a, const Point& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

// From `p` to the segment a-b.
inline double distance_to_segment(const Point& p, const Point& a, const Point& b) {
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
  const double length2 = dx * dx + dy * dy;
  if (length2 < 1e-12) return distance(p, a);
  const double t = std::clamp(((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / length2, 0.0, 1.0);
  return distance(p, Point{a.x_m + t * dx, a.y_m + t * dy});
}

inline DriveNodeOptions waypoint_node_options(PlatformUnderTest platform, components::Steering steering,
                                              std::map<std::string, std::string> options = {}) {
  return DriveNodeOptions{.platform = platform,
                          .steering = steering,
                          .drivers = {"global_waypoint_driver", "local_waypoint_driver"},
                          .driver_options = std::move(options)};
}

// Each component's state, for a failure message ("which one is not Ready").
inline std::string component_states(DriveNode& node) {
  std::string text;
  for (const rt::Component* c : node.host().node().local_components())
    text += c->name() + " " + c->address().to_string() + ": " + std::string(rt::to_string(c->state())) + "; ";
  return text;
}

class WaypointOperator {
 public:
  explicit WaypointOperator(DriveNode& node) : node_(node) {}

  components::GlobalWaypointDriver& global_driver() {
    return node_.component<components::GlobalWaypointDriver>(kGlobalWaypointDriver);
  }
  components::LocalWaypointDriver& local_driver() {
    return node_.component<components::LocalWaypointDriver>(kLocalWaypointDriver);
  }
  Point position() {
    const auto p = *node_.pose().local_position;
    return {p.x_m, p.y_m};
  }

  void send_local(const std::vector<Point>& points, std::uint16_t first_number = 0) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      msg::SetLocalWaypoint w;
      w.waypoint_number = static_cast<std::uint16_t>(first_number + i);
      w.x_m = points[i].x_m;
      w.y_m = points[i].y_m;
      node_.send(kLocalWaypointDriver, w);
    }
    node_.run_for(std::chrono::milliseconds(20));
  }
  // The points of the vehicle's local frame as latitude and longitude.
  void send_global(const std::vector<Point>& points) {
    const components::LocalFrame frame(node_.host().config().vehicle.start);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto geo = frame.to_geo(components::LocalPosition{points[i].x_m, points[i].y_m, 0});
      msg::SetGlobalWaypoint w;
      w.waypoint_number = static_cast<std::uint16_t>(i);
      w.latitude_deg = geo.latitude_deg;
      w.longitude_deg = geo.longitude_deg;
      node_.send(kGlobalWaypointDriver, w);
    }
    node_.run_for(std::chrono::milliseconds(20));
  }
  void send_travel_speed(const Address& driver, double mps) {
    node_.send(driver, msg::SetTravelSpeed{{mps}});
    node_.run_for(std::chrono::milliseconds(20));
  }
  // Control of `driver` and Standby: ready to load and Resume.
  bool prepare(const Address& driver) {
    if (!node_.take_control(driver)) return false;
    node_.send(driver, msg::Standby{});
    return node_.run_until([&] { return node_.state_of(driver) == rt::PrimaryStatus::standby; }, 1s);
  }
  bool resume(const Address& driver) {
    node_.send(driver, msg::Resume{});
    return node_.run_until([&] { return node_.state_of(driver) == rt::PrimaryStatus::ready; }, 1s);
  }
  bool standby(const Address& driver) {
    node_.send(driver, msg::Standby{});
    return node_.run_until([&] { return node_.state_of(driver) == rt::PrimaryStatus::standby; }, 1s);
  }

 private:
  DriveNode& node_;
};

// How a route was driven, sampled every `period` of virtual time: the
// closest the vehicle came to each waypoint while it was the active one,
// the order they became active, the distance from the leg being driven
// (cross-track) and the top speed.
struct RouteRecord {
  std::vector<double> closest_m;
  std::vector<double> reached_at_s;  // when each waypoint stopped being the active one (or the route finished)
  std::vector<std::size_t> order;    // the active waypoints in the order they were seen
  double cross_track_sum_m = 0, cross_track_max_m = 0;
  std::size_t samples = 0;
  double top_speed_mps = 0;
  double cross_track_mean_m() const { return samples ? cross_track_sum_m / static_cast<double>(samples) : 0; }
};

template <class Driver>
RouteRecord drive_route(DriveNode& node, WaypointOperator& op, Driver& driver, const std::vector<Point>& route,
                        rt::Duration limit, rt::Duration period = std::chrono::milliseconds(50)) {
  RouteRecord r;
  r.closest_m.assign(route.size(), std::numeric_limits<double>::infinity());
  r.reached_at_s.assign(route.size(), -1);
  const Point start = op.position();
  const auto t0 = node.time().now();
  const auto now_s = [&] { return std::chrono::duration<double>(node.time().now() - t0).count(); };
  std::size_t last_active = route.size();
  const auto deadline = node.time().now() + limit;
  while (node.time().now() < deadline) {
    const bool driving = driver.driving();
    const std::size_t active = std::min(driver.active_waypoint(), route.size() - 1);
    const Point here = op.position();
    if (active != last_active) {
      r.order.push_back(active);
      for (std::size_t i = 0; i < active; ++i)
        if (r.reached_at_s[i] < 0) r.reached_at_s[i] = now_s();
      last_active = active;
    }
    for (std::size_t i = 0; i <= active; ++i) r.closest_m[i] = std::min(r.closest_m[i], distance(here, route[i]));
    if (driving) {
      const Point from = active == 0 ? start : route[active - 1];
      const double off = distance_to_segment(here, from, route[active]);
      r.cross_track_sum_m += off;
      r.cross_track_max_m = std::max(r.cross_track_max_m, off);
      ++r.samples;
      r.top_speed_mps = std::max(r.top_speed_mps, node.speed_mps());
    }
    if (driver.route_finished() && !driving) break;
    node.run_for(period);
  }
  if (driver.route_finished()) {
    for (auto& t : r.reached_at_s)
      if (t < 0) t = now_s();
  }
  return r;
}

}  // namespace jaus::test
