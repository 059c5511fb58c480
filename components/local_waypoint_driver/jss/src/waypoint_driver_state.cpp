#include "waypoint_driver_state.hpp"

#include "jaus/components_jss/local_waypoint_driver_jss.hpp"
#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/scaling.hpp"
#include "kit_names.hpp"

namespace jaus::components_jss {


msg::SetLocalWaypoint local_waypoint_to_ra(const jss::msg::SetLocalWaypoint& jss, std::uint16_t number) {
  // One body, read in each dialect: the RA side gets the list position as
  // its number, the values inside its ranges, and no tolerances (RA has none).
  msg::SetLocalWaypoint ra{};
  ra.waypoint_number = number;
  ra.x_m = scaling::local_xy_to_ra(jss.x_m);
  ra.y_m = scaling::local_xy_to_ra(jss.y_m);
  ra.z_m = scaling::local_z_to_ra(jss.z_m);
  ra.roll_rad = scaling::angle_to_ra(jss.roll_rad);
  ra.pitch_rad = scaling::angle_to_ra(jss.pitch_rad);
  ra.yaw_rad = scaling::angle_to_ra(jss.yaw_rad);
  return ra;
}

WaypointDrivers::~WaypointDrivers() {
  // The node's scheduler outlives the face; the face's port may be half gone by now.
  if (scheduler_ != nullptr && timer_ != rt::kNoTimer) scheduler_->cancel(timer_);
}

WaypointDriverState& WaypointDrivers::state(const Address& ra_driver) {
  return states_.try_emplace(ra_driver, kMaxListElements).first->second;
}

const components::LocalWaypointDriver* WaypointDrivers::driver(FacePort& port, const Address& ra_driver) {
  return dynamic_cast<const components::LocalWaypointDriver*>(port.node().find(ra_driver));
}

bool WaypointDrivers::ready(FacePort& port, const Address& ra_driver) {
  const auto* d = driver(port, ra_driver);
  return d != nullptr && d->state() == rt::PrimaryStatus::ready;
}

void WaypointDrivers::load(FacePort& port, const JssInbound& m, std::span<const jss::msg::SetLocalWaypoint> waypoints,
                           double speed_mps, bool start, kit::TranslatorLog& log) {
  auto& s = state(m.ra_component);
  // Standby first: a list and a speed above zero given to a Ready RA driver
  // start it on their own (its RA start rule 2), and a route of the old list
  // would run until the Standby. Loaded in Standby, only the Resume starts.
  if (start) kit::send_ra(port, m, msg::Standby{}, log);
  for (std::size_t i = 0; i < waypoints.size(); ++i)
    kit::send_ra(port, m, local_waypoint_to_ra(waypoints[i], static_cast<std::uint16_t>(i)), log);
  kit::send_ra(port, m, msg::SetTravelSpeed{{scaling::travel_speed_to_ra(speed_mps)}}, log);
  if (start) {
    if (const auto* d = driver(port, m.ra_component)) s.expected_route_starts = d->waypoint_counters().routes_started + 1;
    kit::send_ra(port, m, msg::Resume{}, log);
  }
  s.speed_mps = start ? scaling::travel_speed_to_jss(speed_mps) : 0.0;
  s.speed_by = m.origin;
  s.speed_standing = m.standing;
  if (s.speed_mps > 0) watch(port);
}

void WaypointDrivers::set_speed(FacePort& port, const JssInbound& m, double speed_mps, kit::TranslatorLog& log) {
  auto& s = state(m.ra_component);
  kit::send_ra(port, m, msg::SetTravelSpeed{{scaling::travel_speed_to_ra(speed_mps)}}, log);
  s.speed_mps = scaling::travel_speed_to_jss(speed_mps);
  s.speed_by = m.origin;
  s.speed_standing = m.standing;
  if (const auto* d = driver(port, m.ra_component)) {
    // A speed set while the route runs belongs to that run.
    s.expected_route_starts = std::max(s.expected_route_starts, d->waypoint_counters().routes_started);
  }
  if (s.speed_mps > 0) watch(port);
}

std::uint16_t WaypointDrivers::active_element(FacePort& port, const Address& ra_driver) {
  const auto* d = driver(port, ra_driver);
  const auto& s = state(ra_driver);
  // Not driving: halted (Standby, Emergency, control of the primitive driver
  // lost) and not restarted; Clear Emergency returns to Ready without driving.
  if (d == nullptr || d->state() != rt::PrimaryStatus::ready || !d->driving() || d->route_finished()) return 0;
  if (s.loaded != WaypointDriverState::Loaded::element_list) return 0;
  // The RA list is no longer the one we loaded (an RA client loaded another).
  if (d->waypoints().size() != s.route_uids.size()) return 0;
  const std::size_t active = d->active_waypoint();
  return active < s.route_uids.size() ? s.route_uids[active] : 0;
}

std::optional<jss::msg::SetLocalWaypoint> WaypointDrivers::current_waypoint(FacePort& port,
                                                                            const Address& ra_driver) {
  const auto& s = state(ra_driver);
  if (s.loaded == WaypointDriverState::Loaded::single_waypoint) return s.waypoint;
  const std::uint16_t uid = active_element(port, ra_driver);
  if (uid == 0) return std::nullopt;
  const ListElement* element = s.elements.find(uid);
  if (element == nullptr) return std::nullopt;
  auto waypoint = jss::decode_contents<jss::msg::SetLocalWaypoint>(element->data);
  if (!waypoint) return std::nullopt;
  return *waypoint;
}

double WaypointDrivers::travel_speed(FacePort& port, const Address& ra_driver) {
  const auto& s = state(ra_driver);
  // Left Ready since the speed was set, even if the check's timer has not run yet: 0.
  if (!ready(port, ra_driver) || left_ready(port, ra_driver, s)) return 0.0;
  return s.speed_mps;
}

void WaypointDrivers::heard(FacePort& port, const JssInbound& m, kit::TranslatorLog& log) {
  if (m.origin.event_id || !kit::client_controls(port, m)) return;
  kit::send_ra(port, m, msg::QueryTravelSpeed{}, log);
}

bool WaypointDrivers::is_heard_answer(const RaOutbound& m) {
  return m.header.command_code == msg::ReportTravelSpeed::code &&
         m.header.source.component == component_id::kLocalWaypointDriver && !m.to.event_id;
}

bool WaypointDrivers::left_ready(FacePort& port, const Address& ra_driver, const WaypointDriverState& s) {
  const auto* d = driver(port, ra_driver);
  if (d == nullptr || d->state() != rt::PrimaryStatus::ready) return true;
  // Another Resume (Standby -> Ready) than ours: the component left Ready in between.
  return d->waypoint_counters().routes_started > s.expected_route_starts;
}

void WaypointDrivers::watch(FacePort& port) {
  port_ = &port;
  scheduler_ = &port.scheduler();
  if (timer_ != rt::kNoTimer) return;
  timer_ = scheduler_->call_at(port.clock().now() + kLeaveReadyCheckPeriod, [this] {
    timer_ = rt::kNoTimer;
    check_left_ready();
  });
}

void WaypointDrivers::check_left_ready() {
  bool any_speed = false;
  for (auto& [address, s] : states_) {
    if (!(s.speed_mps > 0)) continue;
    if (!left_ready(*port_, address, s)) {
      any_speed = true;
      continue;
    }
    s.speed_mps = 0;
    // The RA driver keeps its speed through Standby and Resume; JSS does not.
    if (s.speed_by && kit::client_controls(*port_, address, s.speed_by->client)) {
      auto payload = kit::encode_ra(msg::SetTravelSpeed{{0.0}});
      if (payload) port_->send_ra(*s.speed_by, address, msg::SetTravelSpeed::code, *payload, s.speed_standing);
    }
  }
  if (any_speed) watch(*port_);
}

}  // namespace jaus::components_jss
