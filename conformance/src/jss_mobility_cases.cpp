// JSS mobility services (AS6009, mobility v1.0; docs/jss.md, "Mobility services"), each asked
// of a component that lists it: the primitive driver (effort only from its
// controller in Ready, zero on leaving Ready), the pose and velocity sensors
// (the requested AND available presence vector, values decoding whole), the
// local waypoint driver (echo, non-controller ignored), the list manager
// (validity rules and their codes) and the list driver (execute, active
// element). What moves moves little: 5 % effort, waypoints within a metre of
// where the vehicle stands, 0.2 m/s; every case ends with zero effort or
// Standby, its elements deleted and control released.
#include <algorithm>
#include <cmath>

#include "jss_case_support.hpp"

namespace jaus::conform {
namespace {

using namespace jss_detail;
using namespace std::chrono_literals;
namespace m = jss::msg;

std::string number(double v, int decimals = 2) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}
std::string hex16(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%04X", v);
  return text;
}

// The presence vector of a report: the u16 after its message ID.
std::uint16_t presence_of(const std::vector<std::uint8_t>& contents, std::size_t pv_bytes = 2) {
  if (contents.size() < 2 + pv_bytes) return 0;
  return pv_bytes == 1 ? contents[2] : static_cast<std::uint16_t>(contents[2] | (contents[3] << 8));
}

// --- primitive driver ---------------------------------------------------

Expected<double> reported_linear_x(JssCaseContext& c) {
  auto report = ask<m::ReportWrenchEffort>(c, m::QueryWrenchEffort{{0x0001}});
  if (!report) return unexpected(report.error());
  if (!report->propulsive_linear_effort_x_percent)
    return unexpected(make_error(ErrorCode::malformed, "Report Wrench Effort without propulsive linear X"));
  return *report->propulsive_linear_effort_x_percent;
}

m::SetWrenchEffort effort_x(double percent) {
  m::SetWrenchEffort set{};
  set.propulsive_linear_effort_x_percent = percent;
  return set;
}

// One JSS step of U16[-100..100] is 0.003 %; zero has no exact code (0.0015 % off).
constexpr double kEffortTolerance = 0.01;

CaseOutcome primitive_driver_effort(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (auto ready = bring_to(c, kReady); !ready) return skip("not made Ready: " + ready.error().message());
  std::string outcome;
  send(c, effort_x(5));
  pause(c, 100ms);
  auto driving = reported_linear_x(c);
  send(c, effort_x(0));
  pause(c, 100ms);
  auto zero = reported_linear_x(c);
  send(c, effort_x(5));
  pause(c, 100ms);
  (void)bring_to(c, kStandby);
  pause(c, 100ms);
  auto after_standby = reported_linear_x(c);
  (void)bring_to(c, kReady);
  pause(c, 200ms);
  auto after_resume = reported_linear_x(c);
  send(c, effort_x(0));
  if (*found != kReady) (void)bring_to(c, *found);
  if (!driving) return fail("Query Wrench Effort: " + driving.error().message());
  if (std::abs(*driving - 5) > kEffortTolerance) return fail("Set Wrench Effort 5 %, reported " + number(*driving, 3) + " %");
  if (!zero) return fail(zero.error().message());
  if (std::abs(*zero) > kEffortTolerance) return fail("Set Wrench Effort 0 %, reported " + number(*zero, 3) + " %");
  if (!after_standby) return fail(after_standby.error().message());
  if (std::abs(*after_standby) > kEffortTolerance)
    return fail("driving at 5 %, Standby: effort reported " + number(*after_standby, 3) + " %, not zero");
  if (!after_resume) return fail(after_resume.error().message());
  if (std::abs(*after_resume) > kEffortTolerance)
    return fail("Resume after the stop brought back " + number(*after_resume, 3) + " % (latched)");
  return pass("5 % and 0 % reported as set; Standby zeroed it and Resume did not bring it back");
}

CaseOutcome primitive_driver_non_controller_ignored(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  auto second = c.second();
  if (!second) return fail(second.error().message());
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  JssControlHeld held(c, **second, authority);
  if (!held.granted()) return skip("the second client is not granted control: " + held.what());
  send_from(c, **second, c.target(), m::Resume{});
  pause(c, 200ms);
  send_from(c, **second, c.target(), effort_x(0));
  send(c, effort_x(5));  // the runner is no controller
  pause(c, 200ms);
  auto reported = reported_linear_x(c);
  send_from(c, **second, c.target(), effort_x(0));
  if (*found == kStandby) send_from(c, **second, c.target(), m::Standby{});  // as it was found
  if (!reported) return fail(reported.error().message());
  if (std::abs(*reported) > kEffortTolerance)
    return fail("Set Wrench Effort 5 % from a non-controller: reported " + number(*reported, 3) + " %");
  return pass("Set Wrench Effort from a non-controller: effort stays " + number(*reported, 3) + " %");
}

// --- sensors ------------------------------------------------------------

// Query with each presence vector: the report's is the requested AND the
// available (all fields asked: what it has), and it decodes whole.
template <class Query, class Report>
CaseOutcome presence_and(JssCaseContext& c, std::vector<std::uint16_t> asked) {
  auto ask_pv = [&](std::uint16_t pv) -> Expected<std::pair<std::uint16_t, Report>> {
    send(c, Query{{pv}});
    auto reply = await_from(c, c.session, {Report::code});
    if (!reply) return unexpected(reply.error());
    auto report = decode<Report>(*reply);
    if (!report) return unexpected(report.error());
    return std::make_pair(presence_of(reply->contents), std::move(*report));
  };
  auto all = ask_pv(0x01FF);
  if (!all) return fail("all fields (0x01FF): " + all.error().message());
  const std::uint16_t available = all->first;
  if ((available & ~0x01FF) != 0) return fail("asked 0x01FF, reported " + hex16(available));
  std::string seen = "available " + hex16(available);
  for (const std::uint16_t pv : asked) {
    auto reply = ask_pv(pv);
    if (!reply) return fail(hex16(pv) + ": " + reply.error().message());
    if (reply->first != (pv & available))
      return fail("asked " + hex16(pv) + " of available " + hex16(available) + ", reported " + hex16(reply->first));
    seen += ", " + hex16(pv) + " -> " + hex16(reply->first);
  }
  return pass(seen);
}

CaseOutcome velocity_state_presence(JssCaseContext& c) {
  return presence_and<m::QueryVelocityState, m::ReportVelocityState>(c, {0x0140, 0x0001, 0x0000});
}
CaseOutcome local_pose_presence(JssCaseContext& c) {
  return presence_and<m::QueryLocalPose, m::ReportLocalPose>(c, {0x0043, 0x0103, 0x0000});
}
CaseOutcome global_pose_presence(JssCaseContext& c) {
  return presence_and<m::QueryGlobalPose, m::ReportGlobalPose>(c, {0x0007, 0x0143, 0x0000});
}

// Values a sensor gives are within the ranges that make sense for a vehicle (the codec keeps them in the
// JSS ranges): angles within +-pi, a position that is a number.
CaseOutcome local_pose_values(JssCaseContext& c) {
  auto report = ask<m::ReportLocalPose>(c, m::QueryLocalPose{{0x01FF}});
  if (!report) return fail(report.error().message());
  for (const auto* angle : {&report->roll_rad, &report->pitch_rad, &report->yaw_rad})
    if (*angle && std::abs(**angle) > 3.1416) return fail("an angle of " + number(**angle, 4) + " rad");
  if (report->x_m && report->y_m) return pass("x " + number(*report->x_m) + " m, y " + number(*report->y_m) + " m");
  return pass("no position fields available");
}

// --- waypoints ----------------------------------------------------------

// Where the vehicle stands, by a local pose sensor on the same node (0, 0 when there is none).
struct Spot {
  double x = 0, y = 0;
  bool known = false;
};
Spot where_vehicle_is(JssCaseContext& c) {
  if (!c.node_components) return {};
  for (const auto& other : *c.node_components) {
    if (other.id.subsystem != c.target().subsystem || other.id.node != c.target().node || !other.has("LocalPoseSensor"))
      continue;
    send_from(c, c.session, other.id, m::QueryLocalPose{{0x0003}});
    auto reply = c.session.await_reply(other.id, {m::ReportLocalPose::code}, c.reply_timeout);
    if (!reply) continue;
    auto pose = decode<m::ReportLocalPose>(*reply);
    if (pose && pose->x_m && pose->y_m) return Spot{*pose->x_m, *pose->y_m, true};
  }
  return {};
}

m::SetLocalWaypoint waypoint_at(double x, double y, std::optional<double> yaw = std::nullopt) {
  m::SetLocalWaypoint w{};
  w.x_m = x;
  w.y_m = y;
  w.yaw_rad = yaw;
  return w;
}

// Ends a waypoint case: the driver's waypoints dropped (Reset, as its controller) and control released.
void reset_driver(JssCaseContext& c, ocu::JssSession& controller, JssControlHeld& held) {
  send_from(c, controller, c.target(), m::Reset{});
  pause(c, 200ms);
  held.forget();  // Reset ends control (Reject Control 0)
  send_from(c, controller, c.target(), m::ReleaseControl{});
  pause(c, 100ms);
}

constexpr double kPositionTolerance = 0.001;  // m: well above a U32[+-100000] step (4.7e-5 m)
constexpr double kAngleTolerance = 0.001;     // rad: above a U16[+-pi] step (9.6e-5 rad)

CaseOutcome local_waypoint_echo(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  (void)bring_to(c, kStandby);  // loading never moves the vehicle in Standby
  const Spot here = where_vehicle_is(c);
  const auto set = waypoint_at(here.x + 0.5, here.y - 0.25, 0.5);
  send(c, set);
  pause(c, 200ms);
  auto report = ask<m::ReportLocalWaypoint>(c, m::QueryLocalWaypoint{{0x3F}});
  auto speed = ask<m::ReportTravelSpeed>(c, m::QueryTravelSpeed{});
  reset_driver(c, c.session, held);
  if (!report) return fail("Query Local Waypoint: " + report.error().message());
  if (std::abs(report->x_m - set.x_m) > kPositionTolerance || std::abs(report->y_m - set.y_m) > kPositionTolerance)
    return fail("set x " + number(set.x_m, 3) + ", y " + number(set.y_m, 3) + "; reported " + number(report->x_m, 3) +
                ", " + number(report->y_m, 3));
  if (!report->yaw_rad || std::abs(*report->yaw_rad - 0.5) > kAngleTolerance)
    return fail("set yaw 0.5 rad; reported " + (report->yaw_rad ? number(*report->yaw_rad, 4) : std::string("none")));
  if (!speed) return fail("Query Travel Speed: " + speed.error().message());
  return pass("Report Local Waypoint as set (x, y, yaw); Report Travel Speed " + number(speed->speed_mps) + " m/s");
}

CaseOutcome local_waypoint_non_controller_ignored(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  auto second = c.second();
  if (!second) return fail(second.error().message());
  JssControlHeld held(c, **second, authority);
  if (!held.granted()) return skip("the second client is not granted control: " + held.what());
  send_from(c, **second, c.target(), m::Standby{});
  const Spot here = where_vehicle_is(c);
  send_from(c, **second, c.target(), waypoint_at(here.x + 0.5, here.y));
  pause(c, 200ms);
  send(c, waypoint_at(here.x + 0.9, here.y + 0.9));  // the runner is no controller
  pause(c, 200ms);
  auto report = ask<m::ReportLocalWaypoint>(c, m::QueryLocalWaypoint{{0x3F}});
  reset_driver(c, **second, held);
  if (!report) return fail("Query Local Waypoint: " + report.error().message());
  if (std::abs(report->x_m - (here.x + 0.5)) > kPositionTolerance)
    return fail("a non-controller's Set Local Waypoint replaced its controller's: x " + number(report->x_m, 3));
  return pass("Set Local Waypoint from a non-controller: its controller's waypoint stays");
}

// --- list manager and list driver ---------------------------------------

m::ElementRecord element(std::uint16_t uid, std::uint16_t previous, std::uint16_t next, std::vector<std::uint8_t> data,
                       std::uint8_t format = 0) {
  m::ElementRecord e{};
  e.element_uid = uid;
  e.previous_uid = previous;
  e.next_uid = next;
  e.format = format;
  e.element_data = std::move(data);
  return e;
}

// Set Element with these elements; the Confirm (nullopt) or Reject code.
Expected<std::optional<std::uint8_t>> set_elements(JssCaseContext& c, ocu::JssSession& from, std::uint8_t request_id,
                                                   std::vector<m::ElementRecord> elements) {
  m::SetElement set{};
  set.request_id = request_id;
  set.elements = std::move(elements);
  send_from(c, from, c.target(), set);
  auto reply = await_from(c, from, {m::ConfirmElementRequest::code, m::RejectElementRequest::code});
  if (!reply) return unexpected(reply.error());
  if (reply->message_id() == m::ConfirmElementRequest::code) return std::optional<std::uint8_t>{};
  auto reject = decode<m::RejectElementRequest>(*reply);
  if (!reject) return unexpected(reject.error());
  return std::optional<std::uint8_t>{reject->response_code};
}

Expected<std::optional<std::uint8_t>> delete_elements(JssCaseContext& c, std::uint8_t request_id,
                                                      std::vector<std::uint16_t> uids) {
  m::DeleteElement del{};
  del.request_id = request_id;
  del.element_uids = std::move(uids);
  send(c, del);
  auto reply = await_from(c, c.session, {m::ConfirmElementRequest::code, m::RejectElementRequest::code});
  if (!reply) return unexpected(reply.error());
  if (reply->message_id() == m::ConfirmElementRequest::code) return std::optional<std::uint8_t>{};
  auto reject = decode<m::RejectElementRequest>(*reply);
  if (!reject) return unexpected(reject.error());
  return std::optional<std::uint8_t>{reject->response_code};
}

constexpr std::uint16_t kAllElements = 65535;

std::string verdict_text(const Expected<std::optional<std::uint8_t>>& r) {
  if (!r) return r.error().message();
  return *r ? "Reject Element Request " + std::to_string(**r) : std::string("Confirm Element Request");
}

CaseOutcome list_manager_validity(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  (void)bring_to(c, kStandby);
  const Spot here = where_vehicle_is(c);
  const auto wp1 = jss::encode_contents(waypoint_at(here.x + 0.5, here.y));
  const auto wp2 = jss::encode_contents(waypoint_at(here.x + 1.0, here.y));
  std::string outcome;
  auto expect = [&](const std::string& what, const Expected<std::optional<std::uint8_t>>& got,
                    std::optional<std::uint8_t> wanted) {
    if (!outcome.empty()) return;
    if (!got || *got != wanted)
      outcome = what + ": " + verdict_text(got) + ", not " +
                (wanted ? "Reject Element Request " + std::to_string(*wanted) : std::string("Confirm Element Request"));
  };
  expect("clearing the list (65535)", delete_elements(c, 1, {kAllElements}), std::nullopt);
  expect("UID 0", set_elements(c, c.session, 2, {element(0, 0, 0, wp1)}), 1);
  expect("previous UID 7 (none)", set_elements(c, c.session, 3, {element(1, 7, 0, wp1)}), 2);
  expect("next UID 7 (none)", set_elements(c, c.session, 4, {element(1, 0, 7, wp1)}), 3);
  expect("format 1 (user defined)", set_elements(c, c.session, 5, {element(1, 0, 0, wp1, 1)}), 4);
  expect("a Query Status as element data", set_elements(c, c.session, 6, {element(1, 0, 0, jss::encode_contents(m::QueryStatus{}))}), 4);
  expect("element 1 (head and tail)", set_elements(c, c.session, 7, {element(1, 0, 0, wp1)}), std::nullopt);
  expect("element 2 after 1", set_elements(c, c.session, 8, {element(2, 1, 0, wp2)}), std::nullopt);
  auto count = ask<m::ReportElementCount>(c, m::QueryElementCount{});
  auto list = ask<m::ReportElementList>(c, m::QueryElementList{});
  auto first = ask<m::ReportElement>(c, m::QueryElement{{std::uint16_t{1}}});
  // Another client's Set Element while the runner controls it: ignored.
  std::string other;
  if (auto second = c.second(); second) {
    auto ignored = set_elements(c, **second, 9, {element(3, 2, 0, wp2)});
    if (ignored && !*ignored) other = "a non-controller's Set Element was confirmed";
    auto after = ask<m::ReportElementCount>(c, m::QueryElementCount{});
    if (after && count && after->element_count != count->element_count) other = "a non-controller's Set Element was added";
  }
  expect("deleting UID 9 (none)", delete_elements(c, 10, {9}), 5);
  expect("deleting every element", delete_elements(c, 11, {kAllElements}), std::nullopt);
  auto emptied = ask<m::ReportElementCount>(c, m::QueryElementCount{});
  reset_driver(c, c.session, held);
  if (!outcome.empty()) return fail(outcome);
  if (!count) return fail("Query Element Count: " + count.error().message());
  if (count->element_count != 2) return fail("2 elements set, Report Element Count " + std::to_string(count->element_count));
  if (!list) return fail("Query Element List: " + list.error().message());
  if (list->element_uids != std::vector<std::uint16_t>{1, 2}) return fail("Report Element List is not 1, 2");
  if (!first) return fail("Query Element 1: " + first.error().message());
  if (first->next_uid != 2 || first->previous_uid != 0 || first->element_data != wp1)
    return fail("element 1 after inserting 2 behind it: previous " + std::to_string(first->previous_uid) +
                ", next " + std::to_string(first->next_uid) + " (0, 2 and its waypoint expected)");
  if (!other.empty()) return fail(other);
  if (!emptied) return fail("Query Element Count: " + emptied.error().message());
  if (emptied->element_count != 0) return fail("after deleting every element, " + std::to_string(emptied->element_count) + " left");
  return pass("Reject codes 1 (UID 0), 2, 3 (unknown links), 4 (format, not a waypoint), 5 (unknown UID); a 2-element "
              "list confirmed, counted, listed and linked; a non-controller ignored; 65535 deletes all");
}

CaseOutcome list_driver_execute(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  (void)bring_to(c, kStandby);
  const Spot here = where_vehicle_is(c);
  std::string outcome;
  auto cleared = delete_elements(c, 1, {kAllElements});
  auto loaded = set_elements(c, c.session, 2,
                             {element(1, 0, 2, jss::encode_contents(waypoint_at(here.x + 0.6, here.y))),
                              element(2, 1, 0, jss::encode_contents(waypoint_at(here.x + 1.0, here.y)))});
  if (!cleared || *cleared || !loaded || *loaded) {
    reset_driver(c, c.session, held);
    return fail("loading two elements: " + verdict_text(cleared) + ", " + verdict_text(loaded));
  }
  auto idle = ask<m::ReportActiveElement>(c, m::QueryActiveElement{});
  if (auto ready = bring_to(c, kReady); !ready) {
    reset_driver(c, c.session, held);
    return skip("not made Ready: " + ready.error().message());
  }
  m::ExecuteList execute{};
  execute.speed_mps = 0.2;
  execute.element_uid = 1;
  send(c, execute);
  std::optional<std::uint16_t> active;
  const auto until = c.session.clock().now() + 2s;
  while (c.session.clock().now() < until) {
    auto now = ask<m::ReportActiveElement>(c, m::QueryActiveElement{});
    if (now && (now->element_uid == 1 || now->element_uid == 2)) {
      active = now->element_uid;
      break;
    }
    pause(c, 100ms);
  }
  auto speed = ask<m::ReportTravelSpeed>(c, m::QueryTravelSpeed{});
  (void)bring_to(c, kStandby);
  pause(c, 200ms);
  auto after_standby = ask<m::ReportActiveElement>(c, m::QueryActiveElement{});
  auto speed_after = ask<m::ReportTravelSpeed>(c, m::QueryTravelSpeed{});
  (void)delete_elements(c, 3, {kAllElements});
  reset_driver(c, c.session, held);
  if (!idle) return fail("Query Active Element: " + idle.error().message());
  if (idle->element_uid != 0) return fail("Report Active Element " + std::to_string(idle->element_uid) + " before Execute List");
  if (!active) return fail("no element of the list active within 2 s of Execute List");
  if (!speed) return fail("Query Travel Speed: " + speed.error().message());
  if (std::abs(speed->speed_mps - 0.2) > 0.01) return fail("Execute List at 0.2 m/s, Report Travel Speed " + number(speed->speed_mps));
  if (!after_standby) return fail(after_standby.error().message());
  if (after_standby->element_uid != 0) return fail("after Standby, Report Active Element " + std::to_string(after_standby->element_uid));
  if (!speed_after) return fail(speed_after.error().message());
  if (speed_after->speed_mps != 0) return fail("after Standby, Report Travel Speed " + number(speed_after->speed_mps));
  return pass("active element " + std::to_string(*active) + " at 0.20 m/s after Execute List; 0 and 0 m/s after Standby");
}

// --- the suite ----------------------------------------------------------

JssConformanceCase mobility_case(std::string_view id, std::string_view title, std::string_view reference,
                        std::string_view service, std::function<CaseOutcome(JssCaseContext&)> run) {
  return JssConformanceCase{id, title, reference,
                            [service](const JssComponentUnderTest& c) { return unless_has(c, service); },
                            std::move(run)};
}

}  // namespace

std::span<const JssConformanceCase> jss_mobility_cases() {
  static const std::vector<JssConformanceCase> cases{
      mobility_case("jss.primitive_driver.effort",
           "its controller's Set Wrench Effort in Ready is reported; leaving Ready zeroes it and Resume does not "
           "bring it back",
           "AS6009 PrimitiveDriver; docs/jss.md: Primitive Driver", "PrimitiveDriver", primitive_driver_effort),
      mobility_case("jss.primitive_driver.non_controller_ignored", "Set Wrench Effort from a non-controller is not executed",
           "AS6009 PrimitiveDriver; docs/jss.md: Access Control, Primitive Driver",
           "PrimitiveDriver", primitive_driver_non_controller_ignored),
      mobility_case("jss.velocity_state.presence",
           "Query Velocity State gets the requested AND available fields (0x0140, 0x0001, none)",
           "AS6009 VelocityStateSensor; docs/jss.md: The bytes on the wire, Sensors",
           "VelocityStateSensor", velocity_state_presence),
      mobility_case("jss.local_pose.presence",
           "Query Local Pose gets the requested AND available fields (0x0043, 0x0103, none)",
           "AS6009 LocalPoseSensor; docs/jss.md: The bytes on the wire, Sensors",
           "LocalPoseSensor", local_pose_presence),
      mobility_case("jss.local_pose.values", "Report Local Pose's angles are within +-pi",
           "AS6009 LocalPoseSensor; docs/jss.md: Sensors", "LocalPoseSensor", local_pose_values),
      mobility_case("jss.global_pose.presence",
           "Query Global Pose gets the requested AND available fields (0x0007, 0x0143, none)",
           "AS6009 GlobalPoseSensor; docs/jss.md: The bytes on the wire, Sensors",
           "GlobalPoseSensor", global_pose_presence),
      mobility_case("jss.local_waypoint.echo",
           "its controller's Set Local Waypoint is what Report Local Waypoint gives; Query Travel Speed is answered",
           "AS6009 LocalWaypointDriver; docs/jss.md: Local Waypoint Driver",
           "LocalWaypointDriver", local_waypoint_echo),
      mobility_case("jss.local_waypoint.non_controller_ignored", "Set Local Waypoint from a non-controller is not executed",
           "AS6009 LocalWaypointDriver; docs/jss.md: Access Control, Local Waypoint Driver", "LocalWaypointDriver",
           local_waypoint_non_controller_ignored),
      mobility_case("jss.list_manager.validity",
           "Set/Delete Element keep the list valid with the Reject codes of the standard; count, list and links "
           "follow; a non-controller is ignored",
           "AS6009 ListManager; docs/jss.md: List Manager and Local Waypoint List Driver",
           "ListManager", list_manager_validity),
      mobility_case("jss.list_driver.execute",
           "Execute List in Ready makes an element of the list active at the given speed; Standby ends it (active "
           "element 0, speed 0)",
           "AS6009 LocalWaypointListDriver; docs/jss.md: List Manager and Local Waypoint List Driver",
           "LocalWaypointListDriver", list_driver_execute),
  };
  return cases;
}

}  // namespace jaus::conform
