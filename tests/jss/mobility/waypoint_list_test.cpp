// The judge's waypoint steps through the face: the list kept by the face
// (Set Element, Query Element List / Count, rejections with their codes),
// Execute List loading the RA local waypoint driver as the client's alias,
// Query Active Element following the RA driver's active waypoint, the
// vehicle reaching every waypoint; the single-waypoint service; and the stop
// paths staying the RA component's (Set Emergency stops, nothing resumes).
#include <limits>

#include "jss_vehicle.hpp"

namespace jaus::test {
namespace waypoint_list_test {

struct Point {
  double x_m = 0, y_m = 0;
};
const std::vector<Point> kSquare = {{6, 0}, {6, 6}, {0, 6}, {0, 0}};

jss::msg::SetLocalWaypoint waypoint(const Point& p) {
  jss::msg::SetLocalWaypoint w{};
  w.x_m = p.x_m;
  w.y_m = p.y_m;
  return w;
}

jss::msg::ElementRecord record(std::uint16_t uid, std::uint16_t previous, std::uint16_t next, const Point& p) {
  jss::msg::ElementRecord r{};
  r.element_uid = uid;
  r.previous_uid = previous;
  r.next_uid = next;
  r.element_data = jss::encode_contents(waypoint(p));
  return r;
}

jss::msg::SetElement set_element(std::uint8_t request_id, std::vector<jss::msg::ElementRecord> records) {
  jss::msg::SetElement m{};
  m.request_id = request_id;
  m.elements = std::move(records);
  return m;
}

jss::msg::ExecuteList execute(double speed_mps, std::optional<std::uint16_t> start) {
  jss::msg::ExecuteList m{};
  m.speed_mps = speed_mps;
  m.element_uid = start;
  return m;
}

class JssWaypointList : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(v_.wait_ready());
    ASSERT_EQ(v_.request_control(kJssWaypointDriver), jss::msg::confirm_control::kControlAccepted);
    v_.send(kJssWaypointDriver, jss::msg::Resume{});
    v_.run_for(20ms);
    ASSERT_EQ(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::ready);
  }
  // The judge's four elements, one Set Element each, appended.
  void load_square() {
    for (std::uint16_t uid = 1; uid <= kSquare.size(); ++uid) {
      const auto confirm = v_.ask<jss::msg::ConfirmElementRequest>(
          kJssWaypointDriver,
          set_element(static_cast<std::uint8_t>(uid), {record(uid, uid - 1, 0, kSquare[uid - 1])}));
      ASSERT_TRUE(confirm) << uid;
      EXPECT_EQ(confirm->request_id, uid);
    }
  }
  std::optional<std::uint16_t> active() {
    const auto r = v_.ask<jss::msg::ReportActiveElement>(kJssWaypointDriver, jss::msg::QueryActiveElement{});
    if (!r) return std::nullopt;
    return r->element_uid;
  }
  std::optional<double> travel_speed() {
    const auto r = v_.ask<jss::msg::ReportTravelSpeed>(kJssWaypointDriver, jss::msg::QueryTravelSpeed{});
    if (!r) return std::nullopt;
    return r->speed_mps;
  }
  std::optional<std::uint8_t> rejected(const jss::msg::SetElement& m) {
    const auto r = v_.ask<jss::msg::RejectElementRequest>(kJssWaypointDriver, m);
    if (!r) return std::nullopt;
    EXPECT_EQ(r->request_id, m.request_id);
    return r->response_code;
  }
  Point here() {
    const auto p = *v_.pose().local_position;
    return {p.x_m, p.y_m};
  }
  static double distance(const Point& a, const Point& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

  JssVehicle v_;
};

TEST_F(JssWaypointList, TheJudgesFourWaypointsAreReachedInOrder) {
  // Like the judge, the client does not re-request control: its list
  // messages and polls, answered by the face, still keep it (RA counts any
  // traffic from the controller).
  v_.stop_keeping_control();
  load_square();
  const auto list = v_.ask<jss::msg::ReportElementList>(kJssWaypointDriver, jss::msg::QueryElementList{});
  ASSERT_TRUE(list);
  EXPECT_EQ(list->element_uids, (std::vector<std::uint16_t>{1, 2, 3, 4}));
  const auto count = v_.ask<jss::msg::ReportElementCount>(kJssWaypointDriver, jss::msg::QueryElementCount{});
  ASSERT_TRUE(count);
  EXPECT_EQ(count->element_count, 4);
  const auto third = v_.ask<jss::msg::ReportElement>(kJssWaypointDriver, jss::msg::QueryElement{{3}});
  ASSERT_TRUE(third);
  EXPECT_EQ(third->previous_uid, 2);
  EXPECT_EQ(third->next_uid, 4);
  EXPECT_EQ(third->element_data, jss::encode_contents(waypoint(kSquare[2])));
  EXPECT_EQ(active(), 0);
  // An every-change event on the active element, as a COP would watch it.
  jss::msg::CreateEvent watch{};
  watch.request_id = 9;
  watch.event_type = jss::msg::event_type::kEveryChange;
  watch.query_message = jss::encode_contents(jss::msg::QueryActiveElement{});
  ASSERT_TRUE(v_.ask<jss::msg::ConfirmEventRequest>(kJssWaypointDriver, watch));

  v_.send(kJssWaypointDriver, execute(1.0, 1));
  std::vector<std::uint16_t> order;
  std::vector<double> closest(kSquare.size(), std::numeric_limits<double>::infinity());
  bool speed_checked = false;
  const bool finished = v_.run_until(
      [&] {
        const auto uid = active();
        if (!uid) return false;
        if (*uid != 0 && (order.empty() || order.back() != *uid)) order.push_back(*uid);
        if (*uid != 0 && !speed_checked) {
          EXPECT_NEAR(*travel_speed(), 1.0, 0.01);  // the JSS speed, not RA's 0.153 m/s steps
          // Query Local Waypoint: the active element's waypoint.
          const auto target =
              v_.ask<jss::msg::ReportLocalWaypoint>(kJssWaypointDriver, jss::msg::QueryLocalWaypoint{{0x01}});
          EXPECT_TRUE(target);
          if (target) {
            EXPECT_NEAR(target->x_m, kSquare[*uid - 1].x_m, 1e-3);
          }
          speed_checked = true;
        }
        for (std::size_t i = 0; i < kSquare.size(); ++i) closest[i] = std::min(closest[i], distance(here(), kSquare[i]));
        v_.run_for(150ms);
        return *uid == 0 && !order.empty();
      },
      90s);
  ASSERT_TRUE(finished) << "active elements so far: " << order.size();
  // Loaded in Standby and started by the Resume alone: the list and the speed
  // never started the Ready RA driver on their own before the face's Standby.
  EXPECT_EQ(v_.waypoint_driver().waypoint_counters().ready_starts, 0u);
  EXPECT_EQ(order, (std::vector<std::uint16_t>{1, 2, 3, 4}));
  for (std::size_t i = 0; i < kSquare.size(); ++i) EXPECT_LT(closest[i], 1.0) << "waypoint " << i + 1;
  EXPECT_TRUE(v_.waypoint_driver().route_finished());
  EXPECT_LT(distance(here(), kSquare.back()), 1.0);
  v_.keep_alive_for(kJssWaypointDriver, 2s);
  EXPECT_LT(v_.speed_mps(), 0.02);
  EXPECT_EQ(active(), 0);
  // The event said each change once: 0 (its first report), 1, 2, 3, 4, 0.
  std::vector<std::uint16_t> changes;
  while (auto event = v_.take<jss::msg::Event>(kJssWaypointDriver)) {
    auto report = jss::decode_contents<jss::msg::ReportActiveElement>(event->report_message);
    ASSERT_TRUE(report);
    changes.push_back(report->element_uid);
  }
  EXPECT_EQ(changes, (std::vector<std::uint16_t>{0, 1, 2, 3, 4, 0}));
}

TEST_F(JssWaypointList, InvalidListsAreRejectedWithTheirCodes) {
  const Point p{3, 3};
  EXPECT_EQ(rejected(set_element(1, {record(0, 0, 0, p)})), jss::msg::reject_element::kInvalidElementId);
  EXPECT_EQ(rejected(set_element(2, {record(65535, 0, 0, p)})), jss::msg::reject_element::kInvalidElementId);
  EXPECT_EQ(rejected(set_element(3, {record(1, 9, 0, p)})), jss::msg::reject_element::kInvalidPreviousElement);
  EXPECT_EQ(rejected(set_element(4, {record(1, 0, 9, p)})), jss::msg::reject_element::kInvalidNextElement);
  auto user_defined = record(1, 0, 0, p);
  user_defined.format = jss::msg::element_format::kUserDefined;
  EXPECT_EQ(rejected(set_element(5, {user_defined})), jss::msg::reject_element::kUnsupportedElementType);
  auto not_a_waypoint = record(1, 0, 0, p);
  not_a_waypoint.element_data = jss::encode_contents(jss::msg::QueryLocalPose{{1}});
  EXPECT_EQ(rejected(set_element(6, {not_a_waypoint})), jss::msg::reject_element::kUnsupportedElementType);
  jss::msg::DeleteElement del{};
  del.request_id = 7;
  del.element_uids = {5};
  const auto not_found = v_.ask<jss::msg::RejectElementRequest>(kJssWaypointDriver, del);
  ASSERT_TRUE(not_found);
  EXPECT_EQ(not_found->response_code, jss::msg::reject_element::kElementIdNotFound);
  // Nothing was stored; a valid head is confirmed, a second head refused.
  const auto count = v_.ask<jss::msg::ReportElementCount>(kJssWaypointDriver, jss::msg::QueryElementCount{});
  ASSERT_TRUE(count);
  EXPECT_EQ(count->element_count, 0);
  EXPECT_TRUE(v_.ask<jss::msg::ConfirmElementRequest>(kJssWaypointDriver, set_element(8, {record(1, 0, 0, p)})));
  EXPECT_EQ(rejected(set_element(9, {record(2, 0, 0, p)})), jss::msg::reject_element::kInvalidPreviousElement);
  EXPECT_FALSE(v_.ask<jss::msg::ReportElement>(kJssWaypointDriver, jss::msg::QueryElement{{2}}, 200ms));
  // Execute List from an element that does not exist starts nothing.
  const auto starts = v_.waypoint_driver().waypoint_counters().routes_started;
  v_.send(kJssWaypointDriver, execute(1.0, 42));
  v_.run_for(500ms);
  EXPECT_EQ(v_.waypoint_driver().waypoint_counters().routes_started, starts);
}

TEST_F(JssWaypointList, OnlyTheControllerChangesTheList) {
  v_.release_control(kJssWaypointDriver);
  v_.run_for(50ms);
  EXPECT_FALSE(v_.ask<jss::msg::ConfirmElementRequest>(kJssWaypointDriver, set_element(1, {record(1, 0, 0, {2, 2})}),
                                                        200ms));
  EXPECT_EQ(v_.count(jss::msg::RejectElementRequest::code), 0u);
  const auto count = v_.ask<jss::msg::ReportElementCount>(kJssWaypointDriver, jss::msg::QueryElementCount{});
  ASSERT_TRUE(count);
  EXPECT_EQ(count->element_count, 0);
}

TEST_F(JssWaypointList, SetEmergencyDuringTheRouteStopsAndNothingResumesIt) {
  load_square();
  v_.send(kJssWaypointDriver, execute(1.0, 1));
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() > 0.5; }, 10s));
  v_.send(kJssWaypointDriver, jss::msg::SetEmergency{{1}});
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() < 0.02; }, 3s));
  EXPECT_EQ(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::emergency);
  EXPECT_EQ(v_.state_of(kRaPrimitiveDriver), rt::PrimaryStatus::emergency);  // emergency_scope vehicle
  v_.keep_alive_for(kJssWaypointDriver, 5s);
  EXPECT_LT(v_.speed_mps(), 0.02);
  EXPECT_EQ(active(), 0);
  EXPECT_EQ(travel_speed(), 0.0);
  // Cleared by its holder: the RA driver returns to the state it left
  // (Ready) without driving, and nothing in the face resumes the route.
  v_.send(kJssWaypointDriver, jss::msg::ClearEmergency{{1}});
  v_.keep_alive_for(kJssWaypointDriver, 5s);
  EXPECT_NE(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::emergency);
  EXPECT_FALSE(v_.waypoint_driver().driving());
  EXPECT_LT(v_.speed_mps(), 0.02);
  EXPECT_EQ(active(), 0);
  EXPECT_EQ(travel_speed(), 0.0);
}

TEST_F(JssWaypointList, ASilentClientLosesControlAndTheRouteStops) {
  load_square();
  v_.send(kJssWaypointDriver, execute(1.0, 1));
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() > 0.5; }, 10s));
  v_.stop_keeping_control();
  // Silent past the RA controller timeout (3 s): control ends, the route halts.
  ASSERT_TRUE(v_.run_until([&] { return !v_.host().node().find(kRaWaypointDriver)->control().controller(); }, 5s));
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() < 0.02; }, 3s));
  EXPECT_FALSE(v_.waypoint_driver().driving());
  v_.run_for(3s);
  EXPECT_LT(v_.speed_mps(), 0.02);
  EXPECT_EQ(active(), 0);
}

TEST_F(JssWaypointList, LeavingReadyResetsTheTravelSpeed) {
  load_square();
  v_.send(kJssWaypointDriver, execute(1.0, 1));
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() > 0.5; }, 10s));
  // Standby and Resume at once: RA would continue at the old speed, JSS at 0.
  v_.send(kJssWaypointDriver, jss::msg::Standby{});
  v_.send(kJssWaypointDriver, jss::msg::Resume{});
  v_.keep_alive_for(kJssWaypointDriver, 4s);
  EXPECT_EQ(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::ready);
  EXPECT_LT(v_.speed_mps(), 0.02);
  EXPECT_EQ(travel_speed(), 0.0);
  // Execute List without a start element changes only the speed: on it goes.
  v_.send(kJssWaypointDriver, execute(1.0, std::nullopt));
  ASSERT_TRUE(v_.run_until([&] { return v_.speed_mps() > 0.5; }, 5s));
  EXPECT_NE(active(), 0);
}

TEST_F(JssWaypointList, ASingleWaypointWaitsForItsTravelSpeed) {
  // Set in Standby (any controlled state), then Resume: the route starts at
  // JSS's speed after entering Ready, 0, until Set Travel Speed.
  v_.send(kJssWaypointDriver, jss::msg::Standby{});
  v_.run_for(50ms);
  ASSERT_EQ(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::standby);
  auto w = waypoint({5, 0});
  w.waypoint_tolerance_m = 1.0;
  v_.send(kJssWaypointDriver, w);
  v_.send(kJssWaypointDriver, jss::msg::SetTravelSpeed{{2.0}});  // not Ready: not executed
  v_.run_for(50ms);
  EXPECT_EQ(v_.waypoint_driver().waypoints().size(), 1u);
  v_.send(kJssWaypointDriver, jss::msg::Resume{});
  v_.run_for(50ms);
  ASSERT_EQ(v_.state_of(kRaWaypointDriver), rt::PrimaryStatus::ready);
  const auto report =
      v_.ask<jss::msg::ReportLocalWaypoint>(kJssWaypointDriver, jss::msg::QueryLocalWaypoint{{0xFF}});
  ASSERT_TRUE(report);
  EXPECT_NEAR(report->x_m, 5, 1e-3);
  ASSERT_TRUE(report->waypoint_tolerance_m);  // kept by the face (RA has no tolerance)
  EXPECT_NEAR(*report->waypoint_tolerance_m, 1.0, 0.01);
  EXPECT_EQ(travel_speed(), 0.0);
  v_.keep_alive_for(kJssWaypointDriver, 2s);
  EXPECT_LT(v_.speed_mps(), 0.02);
  v_.send(kJssWaypointDriver, jss::msg::SetTravelSpeed{{1.0}});
  const bool arrived = v_.run_until(
      [&] {
        v_.send(kJssWaypointDriver, jss::msg::QueryStatus{});
        v_.run_for(200ms);
        return v_.waypoint_driver().route_finished();
      },
      30s);
  EXPECT_TRUE(arrived);
  EXPECT_LT(distance(here(), {5, 0}), 1.0);
}

}  // namespace waypoint_list_test
}  // namespace jaus::test
