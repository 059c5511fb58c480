// Local Waypoint Driver 1.0 on the RA local waypoint driver, docs/jss.md
// "Local Waypoint Driver (one waypoint)" (state and loading: waypoint_driver_state.hpp):
//   Set Local Waypoint (controller, any state): kept as set (tolerances
//     included, RA has none) and loaded as a one-waypoint RA list (number 0:
//     a new list); in Ready it starts at the JSS travel speed (0 until Set
//     Travel Speed), otherwise it waits for Resume at speed 0;
//   Set Travel Speed (controller, Ready, a waypoint exists): RA Set Travel
//     Speed, rescaled (JSS 0..327.67 m/s, RA 0..10000 m/s in 0.153 m/s steps);
//   Query Local Waypoint: the waypoint as set, or the list element being
//     driven to; no answer when there is none (never made-up data);
//   Query Travel Speed: the JSS speed (0 outside Ready).
// The list driver's Travel Speed and Local Waypoint queries are these too.
#include <memory>

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/translator_kit.hpp"
#include "jaus/wire/describe.hpp"
#include "kit_names.hpp"
#include "waypoint_driver_state.hpp"
#include "waypoint_translator.hpp"

namespace jaus::components_jss {
namespace {

class LocalWaypointDriverTranslator final : public ServiceTranslator {
 public:
  explicit LocalWaypointDriverTranslator(std::shared_ptr<WaypointDrivers> drivers) : drivers_(std::move(drivers)) {}

  std::string_view name() const override { return "local waypoint driver"; }
  std::vector<ServiceUri> services(std::uint8_t ra_component_id) const override {
    if (ra_component_id != component_id::kLocalWaypointDriver) return {};
    return {ServiceUri{"urn:jaus:jss:mobility:LocalWaypointDriver", 1, 0}};
  }
  bool handles(std::uint16_t id, std::uint8_t ra_component_id) const override {
    return ra_component_id == component_id::kLocalWaypointDriver &&
           is_one_of<jss::msg::SetLocalWaypoint, jss::msg::QueryLocalWaypoint, jss::msg::SetTravelSpeed,
                     jss::msg::QueryTravelSpeed>(id);
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (m.ra_component.component != component_id::kLocalWaypointDriver) return false;
    switch (m.message_id) {
      case jss::msg::SetLocalWaypoint::code:
        set_waypoint(m, port);
        return true;
      case jss::msg::QueryLocalWaypoint::code:
        query_waypoint(m, port);
        WaypointDrivers::heard(port, m, log_);
        return true;
      case jss::msg::SetTravelSpeed::code:
        set_speed(m, port);
        return true;
      case jss::msg::QueryTravelSpeed::code: {
        jss::msg::ReportTravelSpeed report{};
        report.speed_mps = drivers_->travel_speed(port, m.ra_component);
        kit::reply_jss(port, m.origin, m.our_component, report);
        WaypointDrivers::heard(port, m, log_);
        return true;
      }
      default:
        return false;
    }
  }
  // The RA answer to the liveness query of WaypointDrivers::heard: dropped.
  bool from_ra(const RaOutbound& m, FacePort&) override { return WaypointDrivers::is_heard_answer(m); }

 private:
  void set_waypoint(const JssInbound& m, FacePort& port) {
    auto set = kit::decode_jss_body<jss::msg::SetLocalWaypoint>(m.body);
    if (!set) return kit::log_malformed(port, m, jss::msg::SetLocalWaypoint::name, set.error());
    if (!kit::client_controls(port, m)) return refused(m, port, "Set Local Waypoint", "it does not control it");
    auto& s = drivers_->state(m.ra_component);
    s.loaded = WaypointDriverState::Loaded::single_waypoint;
    s.waypoint = *set;
    s.route_uids.clear();
    const bool ready = WaypointDrivers::ready(port, m.ra_component);
    const jss::msg::SetLocalWaypoint waypoints[] = {*set};
    drivers_->load(port, m, waypoints, ready ? drivers_->travel_speed(port, m.ra_component) : 0.0, ready, log_);
  }

  void query_waypoint(const JssInbound& m, FacePort& port) {
    auto query = kit::decode_jss_body<jss::msg::QueryLocalWaypoint>(m.body);
    if (!query) return kit::log_malformed(port, m, jss::msg::QueryLocalWaypoint::name, query.error());
    auto waypoint = drivers_->current_waypoint(port, m.ra_component);
    if (!waypoint) return;  // answered only when a waypoint exists
    jss::msg::ReportLocalWaypoint report{};
    static_cast<jss::msg::SetLocalWaypoint::body_type&>(report) = *waypoint;
    wire::mask_presence(static_cast<jss::msg::SetLocalWaypoint::body_type&>(report), query->presence_vector);
    kit::reply_jss(port, m.origin, m.our_component, report);
  }

  void set_speed(const JssInbound& m, FacePort& port) {
    auto set = kit::decode_jss_body<jss::msg::SetTravelSpeed>(m.body);
    if (!set) return kit::log_malformed(port, m, jss::msg::SetTravelSpeed::name, set.error());
    if (!kit::client_controls(port, m)) return refused(m, port, "Set Travel Speed", "it does not control it");
    if (!WaypointDrivers::ready(port, m.ra_component))
      return refused(m, port, "Set Travel Speed", "the driver is not Ready");
    const auto* d = WaypointDrivers::driver(port, m.ra_component);
    if (drivers_->state(m.ra_component).loaded == WaypointDriverState::Loaded::nothing || d == nullptr ||
        d->waypoints().empty())
      return refused(m, port, "Set Travel Speed", "no waypoint is set");
    drivers_->set_speed(port, m, set->speed_mps, log_);
  }

  void refused(const JssInbound& m, FacePort& port, std::string_view what, std::string_view why) {
    log_.repeated(port, "waypoint commands not executed", rt::LogLevel::info, [&] {
      return std::string(what) + " from " + kit::who(m, port) + " not executed: " + std::string(why);
    });
  }

  std::shared_ptr<WaypointDrivers> drivers_;
  kit::TranslatorLog log_;
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_local_waypoint_driver_translator(std::shared_ptr<WaypointDrivers> drivers) {
  return std::make_unique<LocalWaypointDriverTranslator>(std::move(drivers));
}

}  // namespace jaus::components_jss
