// The judge's operator unit of the competitions that used JAUS, over AS5669A
// only, against a real jausd (JSS face on) driving a separate clearpath-sim:
// Query Identification every 5 s until the vehicle answers (the judge is up
// before jausd, so the first goes unanswered); Query Services; Query
// Control, Request Control, Query Status, Resume, Standby, Shutdown on a
// component with Management and no mobility service (Shutdown is final, so
// not on one the waypoints need); Query Velocity State (0x0140) and Query
// Local Pose (0x0043, 0x0103); four local waypoints loaded into the list
// driver with Set Element, the element list and count, Execute List, the
// active element and travel speed polled until the route is done, and the
// simulated vehicle reaches all four. Every step asserted; under a minute.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "clearpath_simulator.hpp"
#include "default_jausd.hpp"
#include "jss_system.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
namespace m = jss::msg;

constexpr const char* kNode = "127.0.0.160";
constexpr const char* kSimAddress = "127.0.0.161";
constexpr const char* kJudgeHost = "127.0.0.162";
constexpr int kSubsystem = 12;
constexpr jss::JssId kJudge{300, 1, 1};
constexpr std::uint8_t kJudgeAuthority = 10;  // above the drivers' own (1)
constexpr auto kIdentificationPeriod = 5s;   // the judge's, as fkie IOP's discovery client
constexpr double kArrivalToleranceM = 0.5;   // the default configuration's arrival_tolerance_m
constexpr double kCornerToleranceM = 1.0;    // pure pursuit cuts a corner a little

struct Point {
  double x, y;
};

class JssJudge : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() / ("jaus-jss-judge-sim-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    sim = std::make_unique<ClearpathSimulator>(ClearpathSimulator::Line::udp, dir, "sim", kSimAddress);
    ASSERT_TRUE(sim->started());
    judge = open_jss_operator(kJudge, kJudgeHost, kNode, "judge");
    ASSERT_TRUE(judge);
  }
  void TearDown() override {
    judge.reset();
    jausd.reset();
    sim.reset();
    if (!HasFailure()) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }
  void start_jausd() {
    jausd = std::make_unique<DefaultJausd>("jss-judge", kSubsystem, kNode,
                                           std::string("platform: {udp: ") + kSimAddress + ":7300}\n" + jss_on_config());
    ASSERT_TRUE(jausd->started());
  }
  std::string log() const { return jausd ? jausd->output() : std::string("(no jausd)"); }

  template <class Report, class Query>
  std::optional<Report> ask(const jss::JssId& to, const Query& query, rt::Duration timeout = 2s) {
    auto report = judge->query<Report>(to, query, timeout);
    if (!report) {
      ADD_FAILURE() << Query::name << " to " << to.to_string() << ": " << report.error().message();
      return std::nullopt;
    }
    return *report;
  }
  // A query whose reply's raw contents we need (its presence vector).
  std::optional<ocu::JssReceived> ask_raw(const jss::JssId& to, const std::vector<std::uint8_t>& query,
                                          std::uint16_t reply_id) {
    auto reply = judge->request_contents(to, query, {reply_id}, 2s);
    if (!reply) {
      ADD_FAILURE() << "query to " << to.to_string() << ": " << reply.error().message();
      return std::nullopt;
    }
    return *reply;
  }
  std::optional<std::uint8_t> status(const jss::JssId& to) {
    auto report = ask<m::ReportStatus>(to, m::QueryStatus{});
    if (!report) return std::nullopt;
    return static_cast<std::uint8_t>(report->status & 0x0F);
  }
  bool wait_status(const jss::JssId& to, std::uint8_t wanted, rt::Duration limit = 5s) {
    const auto until = judge->clock().now() + limit;
    std::optional<std::uint8_t> seen;
    while (judge->clock().now() < until) {
      seen = status(to);
      if (seen == wanted) return true;
      judge->run_for(100ms);
    }
    ADD_FAILURE() << to.to_string() << " not status " << int(wanted) << " within the limit; last "
                  << (seen ? std::to_string(*seen) : std::string("none"));
    return false;
  }
  std::uint8_t request_control(const jss::JssId& to) {
    auto confirm = ask<m::ConfirmControl>(to, m::RequestControl{{kJudgeAuthority}});
    return confirm ? confirm->response_code : 255;
  }
  std::optional<Point> local_position(const jss::JssId& pose_sensor) {
    auto pose = judge->query<m::ReportLocalPose>(pose_sensor, m::QueryLocalPose{{0x0003}}, 1s);
    if (!pose || !pose->x_m || !pose->y_m) return std::nullopt;
    return Point{*pose->x_m, *pose->y_m};
  }

  std::filesystem::path dir;
  std::unique_ptr<ClearpathSimulator> sim;
  std::unique_ptr<DefaultJausd> jausd;
  std::unique_ptr<ocu::JssSession> judge;
};

double distance(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

TEST_F(JssJudge, TheJudgesOperatorUnitDiscoversManagesAndDrivesFourWaypointsOverAs5669aOnly) {
  const auto began = std::chrono::steady_clock::now();
  // 1. Query Identification (subsystem) to every subsystem every 5 s until the vehicle answers.
  //    The judge is up first: its first query reaches no jausd.
  int identification_queries = 0;
  std::optional<ocu::JssReceived> identified;
  const auto identify_until = judge->clock().now() + 30s;
  while (!identified && judge->clock().now() < identify_until) {
    judge->send(ocu::kJssBroadcast, m::QueryIdentification{{2}});
    ++identification_queries;
    if (identification_queries == 1) start_jausd();
    auto reply = judge->await_reply(ocu::kJssBroadcast, {m::ReportIdentification::code}, kIdentificationPeriod);
    if (reply) identified = *reply;
  }
  ASSERT_TRUE(identified) << "no Report Identification in 30 s\n" << log();
  EXPECT_GE(identification_queries, 2) << "jausd answered the query sent before it started";
  auto identification = jss::decode_contents<m::ReportIdentification>(identified->contents);
  ASSERT_TRUE(identification);
  EXPECT_EQ(identification->query_type, 2);
  EXPECT_EQ(identification->type, 10001) << "a vehicle";
  const jss::JssId discovery = identified->source();
  EXPECT_EQ(discovery.subsystem, kSubsystem);

  // 2. Query Services: every component of the vehicle with its services.
  auto services = ask<m::ReportServices>(discovery, all_services_query());
  ASSERT_TRUE(services) << log();
  const auto components = listed_components(discovery.subsystem, *services);
  const ListedComponent* managed = nullptr;  // Management and no mobility service: Shutdown is final
  for (const auto& c : components)
    if (c.has("urn:jaus:jss:core:Management") && !c.has_mobility() && (!managed || c.id.component == 37)) managed = &c;
  const ListedComponent* list_driver = first_with(components, "urn:jaus:jss:mobility:LocalWaypointListDriver");
  const ListedComponent* velocity = first_with(components, "urn:jaus:jss:mobility:VelocityStateSensor");
  const ListedComponent* local_pose = first_with(components, "urn:jaus:jss:mobility:LocalPoseSensor");
  ASSERT_TRUE(managed && list_driver && velocity && local_pose) << "Report Services lacks a service\n" << log();
  EXPECT_TRUE(list_driver->has("urn:jaus:jss:mobility:ListManager"));

  // 3. Query Control, Request Control, Query Status, Resume, Standby, Shutdown.
  const jss::JssId target = managed->id;
  auto control = ask<m::ReportControl>(target, m::QueryControl{});
  ASSERT_TRUE(control);
  EXPECT_FALSE(control->controller.is_valid()) << "controlled by " << control->controller.to_string();
  ASSERT_EQ(request_control(target), m::confirm_control::kControlAccepted) << log();
  control = ask<m::ReportControl>(target, m::QueryControl{});
  ASSERT_TRUE(control);
  EXPECT_EQ(control->controller, kJudge);
  EXPECT_EQ(control->authority, kJudgeAuthority);
  const auto found = status(target);
  ASSERT_TRUE(found);
  EXPECT_TRUE(*found == 1 || *found == 2) << "status " << int(*found);
  judge->send(target, m::Resume{});
  EXPECT_TRUE(wait_status(target, 1));
  judge->send(target, m::Standby{});
  EXPECT_TRUE(wait_status(target, 2));
  judge->send(target, m::Shutdown{});
  auto released = judge->await_reply(target, {m::RejectControl::code}, 3s);
  ASSERT_TRUE(released) << "no Reject Control after Shutdown\n" << log();
  EXPECT_EQ(jss::decode_contents<m::RejectControl>(released->contents)->response_code,
            m::reject_control::kControlReleased);
  // Shutdown is final: the component may answer Report Status Shutdown (3), or nothing any more.
  judge->run_for(300ms);
  if (auto after = judge->query<m::ReportStatus>(target, m::QueryStatus{}, 1s)) {
    EXPECT_EQ(after->status & 0x0F, 3) << "after Shutdown";
  }

  // 4. Query Velocity State (0x0140) and Query Local Pose (0x0043, 0x0103): the requested AND available fields.
  const std::vector<std::pair<std::uint16_t, std::uint16_t>> presence_queries{
      {m::QueryVelocityState::code, 0x0140}, {m::QueryLocalPose::code, 0x0043}, {m::QueryLocalPose::code, 0x0103}};
  for (const auto& [query_id, pv] : presence_queries) {
    const bool is_velocity = query_id == m::QueryVelocityState::code;
    const jss::JssId sensor = is_velocity ? velocity->id : local_pose->id;
    const auto contents = is_velocity ? jss::encode_contents(m::QueryVelocityState{{pv}})
                                      : jss::encode_contents(m::QueryLocalPose{{pv}});
    auto reply = ask_raw(sensor, contents, is_velocity ? m::ReportVelocityState::code : m::ReportLocalPose::code);
    ASSERT_TRUE(reply) << log();
    const auto reported = presence_vector_of(reply->contents);
    EXPECT_EQ(reported & ~pv, 0) << std::hex << "asked 0x" << pv << ", reported 0x" << reported;
    EXPECT_NE(reported, 0) << std::hex << "asked 0x" << pv << ": nothing available";
    if (is_velocity) {
      EXPECT_TRUE(jss::decode_contents<m::ReportVelocityState>(reply->contents));
    } else {
      EXPECT_TRUE(jss::decode_contents<m::ReportLocalPose>(reply->contents));
    }
  }

  // 5. Four local waypoints (a 3 m square back to the start) into the list driver, executed.
  const jss::JssId driver = list_driver->id;
  ASSERT_EQ(request_control(driver), m::confirm_control::kControlAccepted) << log();
  judge->send(driver, m::Resume{});
  ASSERT_TRUE(wait_status(driver, 1)) << log();
  const auto start = local_position(local_pose->id);
  ASSERT_TRUE(start) << log();
  const Point square[] = {{start->x + 3, start->y}, {start->x + 3, start->y + 3}, {start->x, start->y + 3}, *start};
  for (std::uint16_t uid = 1; uid <= 4; ++uid) {
    m::SetLocalWaypoint waypoint{};
    waypoint.x_m = square[uid - 1].x;
    waypoint.y_m = square[uid - 1].y;
    m::SetElement set{};
    set.request_id = static_cast<std::uint8_t>(uid);
    set.elements.push_back(m::ElementRecord{uid, static_cast<std::uint16_t>(uid - 1), 0, m::element_format::kJausMessage,
                                            jss::encode_contents(waypoint)});
    auto reply = judge->request_contents(driver, jss::encode_contents(set),
                                         {m::ConfirmElementRequest::code, m::RejectElementRequest::code}, 2s);
    ASSERT_TRUE(reply) << "Set Element " << uid << "\n" << log();
    ASSERT_EQ(reply->message_id(), m::ConfirmElementRequest::code) << "Set Element " << uid << " rejected";
    EXPECT_EQ(jss::decode_contents<m::ConfirmElementRequest>(reply->contents)->request_id, uid);
  }
  auto list = ask<m::ReportElementList>(driver, m::QueryElementList{});
  ASSERT_TRUE(list);
  EXPECT_EQ(list->element_uids, (std::vector<std::uint16_t>{1, 2, 3, 4}));
  auto count = ask<m::ReportElementCount>(driver, m::QueryElementCount{});
  ASSERT_TRUE(count);
  EXPECT_EQ(count->element_count, 4);
  m::ExecuteList execute{};
  execute.speed_mps = 1.0;
  execute.element_uid = 1;
  judge->send(driver, execute);

  // Poll the active element and the travel speed until the last element is done.
  std::vector<std::uint16_t> actives;  // each new active element, in order
  double closest[4] = {1e9, 1e9, 1e9, 1e9};
  double speed_while_active = -1;
  bool finished = false;
  const auto route_until = judge->clock().now() + 90s;
  while (!finished && judge->clock().now() < route_until) {
    auto active = judge->query<m::ReportActiveElement>(driver, m::QueryActiveElement{}, 1s);
    auto speed = judge->query<m::ReportTravelSpeed>(driver, m::QueryTravelSpeed{}, 1s);
    if (active) {
      if (active->element_uid != 0 && (actives.empty() || actives.back() != active->element_uid))
        actives.push_back(active->element_uid);
      if (active->element_uid != 0 && speed) speed_while_active = speed->speed_mps;
      finished = !actives.empty() && active->element_uid == 0;
    }
    if (const auto at = local_position(local_pose->id))
      for (int i = 0; i < 4; ++i) closest[i] = std::min(closest[i], distance(*at, square[i]));
    judge->run_for(200ms);
  }
  ASSERT_TRUE(finished) << "route not finished; active elements seen: " << ::testing::PrintToString(actives) << "\n"
                        << log();
  EXPECT_EQ(actives, (std::vector<std::uint16_t>{1, 2, 3, 4}));
  EXPECT_NEAR(speed_while_active, 1.0, 0.01);
  for (int i = 0; i < 3; ++i) EXPECT_LT(closest[i], kCornerToleranceM) << "waypoint " << i + 1;
  const auto last = local_position(local_pose->id);
  ASSERT_TRUE(last);
  EXPECT_LE(distance(*last, square[3]), kArrivalToleranceM) << last->x << ", " << last->y;
  // The simulator's wheels agree: the vehicle stands at the end.
  EXPECT_TRUE(sim->wait_for(ClearpathSimulator::stopped, 5000ms)) << sim->state()->dump();
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::cout << "[ judge    ] identified after " << identification_queries << " queries; whole run " << took << " s\n";
  EXPECT_LT(took, 75.0);
}

}  // namespace
}  // namespace jaus::test
