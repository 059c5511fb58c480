// What the face keeps per RA local waypoint driver for its JSS services
// (Local Waypoint Driver, List Manager, Local Waypoint List Driver: one JSS
// component, one access control), docs/jss.md "Mobility services", and how it loads the
// RA driver. RA has no list manager, no tolerances, no active element report
// and its travel speed survives leaving Ready; so:
//   - the element list, the single waypoint as set (tolerances included) and
//     the JSS travel speed are kept here; the RA driver holds what executes;
//   - a route is loaded the RA way, all as the client's alias (the RA rules
//     decide): to start it, Standby, then Set Local Waypoint 0..n-1 (0 starts
//     a new RA list), Set Travel Speed, then Resume (in Standby nothing starts
//     before the Resume: a Ready RA driver would start a list on its speed);
//   - the active element is the RA driver's active waypoint (read in
//     process), mapped back to its element UID; 0 when nothing executes;
//   - JSS resets the travel speed to 0 whenever the component leaves Ready:
//     while a speed is set, the face looks at the RA driver every 100 ms and,
//     once it left Ready (or another Resume restarted the route), sends RA
//     Set Travel Speed 0 as the client that set the speed, if it still
//     controls the driver. That only ever slows the vehicle: nothing here
//     resumes, clears an emergency or moves by itself.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "jaus/components/local_waypoint_driver.hpp"
#include "jaus/jss_face/translator_kit.hpp"
#include "list_manager_elements.hpp"

namespace jaus::components_jss {

// Elements kept per driver: the RA waypoint driver's default max_waypoints.
inline constexpr std::size_t kMaxListElements = 1000;
inline constexpr rt::Duration kLeaveReadyCheckPeriod = std::chrono::milliseconds(100);

struct WaypointDriverState {
  explicit WaypointDriverState(std::size_t capacity) : elements(capacity) {}
  ListElements elements;
  // What the RA driver was last loaded with by a JSS client.
  enum class Loaded { nothing, single_waypoint, element_list };
  Loaded loaded = Loaded::nothing;
  std::optional<jss::msg::SetLocalWaypoint> waypoint;  // the single waypoint as set
  std::vector<std::uint16_t> route_uids;  // the element UID of each RA waypoint number
  double speed_mps = 0;                   // JSS travel speed; 0 outside Ready
  std::optional<jss_face::ReplyTo> speed_by;  // the client that set it
  rt::SenderStanding speed_standing = rt::SenderStanding::trusted;
  std::uint64_t expected_route_starts = 0;  // the RA driver's routes_started after our last start
};

class WaypointDrivers {
 public:
  WaypointDrivers() = default;
  ~WaypointDrivers();
  WaypointDrivers(const WaypointDrivers&) = delete;
  WaypointDrivers& operator=(const WaypointDrivers&) = delete;

  // The state of one of our RA waypoint drivers (made on first use: at most
  // one per local component the face delivers messages for).
  WaypointDriverState& state(const Address& ra_driver);
  // The RA driver, read in process (nullptr: not a local waypoint driver).
  static const components::LocalWaypointDriver* driver(jss_face::FacePort& port, const Address& ra_driver);
  static bool ready(jss_face::FacePort& port, const Address& ra_driver);

  // Loads `waypoints` as RA waypoints 0..n-1 and the travel speed, as the
  // client that sent `m`; `start`: then Standby + Resume (the driver is Ready).
  void load(jss_face::FacePort& port, const jss_face::JssInbound& m,
            std::span<const jss::msg::SetLocalWaypoint> waypoints, double speed_mps, bool start,
            jss_face::kit::TranslatorLog& log);
  // Changes the travel speed only.
  void set_speed(jss_face::FacePort& port, const jss_face::JssInbound& m, double speed_mps,
                 jss_face::kit::TranslatorLog& log);

  // The element UID the RA driver executes; 0 when nothing does (no list of
  // ours loaded, route finished, driver not Ready).
  std::uint16_t active_element(jss_face::FacePort& port, const Address& ra_driver);
  // The waypoint driven to (or last set): Report Local Waypoint's answer.
  std::optional<jss::msg::SetLocalWaypoint> current_waypoint(jss_face::FacePort& port, const Address& ra_driver);
  // JSS travel speed: 0 unless the driver is Ready.
  double travel_speed(jss_face::FacePort& port, const Address& ra_driver);

  // A message the face answers itself (list manager, active element, travel
  // speed, local waypoint) reaches no RA component, yet RA counts any
  // traffic from the controller as proof it is alive: so the controlling
  // client's message is shown to the RA driver as RA Query Travel Speed
  // from its alias, whose answer the waypoint translator drops. A client
  // that polls the list driver keeps control as one polling a pose sensor
  // does. Nothing for other senders or for events' queries.
  static void heard(jss_face::FacePort& port, const jss_face::JssInbound& m, jss_face::kit::TranslatorLog& log);
  // That query's answer (RA Report Travel Speed from the driver to an alias).
  static bool is_heard_answer(const jss_face::RaOutbound& m);

 private:
  void watch(jss_face::FacePort& port);
  void check_left_ready();
  bool left_ready(jss_face::FacePort& port, const Address& ra_driver, const WaypointDriverState& s);

  std::map<Address, WaypointDriverState> states_;
  jss_face::FacePort* port_ = nullptr;  // the face's, for the check's timer
  rt::Scheduler* scheduler_ = nullptr;
  rt::TimerId timer_ = rt::kNoTimer;
};

}  // namespace jaus::components_jss
