// A route end to end, with real processes and jausctl only: the default
// jausd's local waypoint driver (7.1.46.1) is taken by `jausctl control
// --authority 5` and held; commands go with `jausctl send` under the
// controller's JAUS ID (--as) from the same host: Standby, Set Travel Speed,
// four Set Local Waypoint (a 3 m square back to the start), Resume. The
// route is watched with `jausctl status` (its secondary status says it is
// driving) and `jausctl query ... "Query Local Pose"` on the global pose
// sensor (7.1.38.1); once it is finished the vehicle stands at the last
// waypoint, within the arrival tolerance, having passed the far corner.
// Only outcomes are asserted, with generous deadlines (a loaded machine,
// sanitizers).
//
// One JAUS ID in two processes: the node lets an ID move between ports of
// the same IP address (the tool restarted on the operator's host), so each
// `jausctl send --as <controller>` from 127.0.0.111 is the controller's; the
// node answers at the endpoint it last heard, and the holder's next status
// query brings its replies back.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "default_jausd.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;

constexpr const char* kNode = "127.0.0.110";
constexpr const char* kOperatorHost = "127.0.0.111";  // the controller and its commands
constexpr const char* kObserverBind = "127.0.0.112:0";
constexpr const char* kOperator = "254.111.40.1";
constexpr const char* kWaypointDriver = "7.1.46.1";
constexpr const char* kPoseSensor = "7.1.38.1";
constexpr std::uint32_t kDrivingBit = 1u << 16;  // the drivers' secondary status: a route is running
constexpr double kArrivalToleranceM = 0.5;       // the default configuration's arrival_tolerance_m

struct Point {
  double x, y;  // local frame: x north, y east of the start
};
constexpr Point kSquare[] = {{3, 0}, {3, 3}, {0, 3}, {0, 0}};

class Waypoints : public ::testing::Test {
 protected:
  void SetUp() override {
    jausd = std::make_unique<DefaultJausd>("waypoints", 7, kNode);
    ASSERT_TRUE(jausd->started());
    // The daemon takes a moment to start (longer under sanitizers); the
    // driver is Ready once the primitive driver told it its specifications.
    const auto until = std::chrono::steady_clock::now() + 30s;
    for (;;) {
      const auto state = status();
      if (state && (*state)["primary_status"] == "ready") break;
      ASSERT_LT(std::chrono::steady_clock::now(), until) << jausd->output();
      std::this_thread::sleep_for(200ms);
    }
  }
  void TearDown() override {
    if (controller) {
      controller->signal(SIGINT);
      controller->wait(10s);
    }
    jausd.reset();
  }

  // The JSON line a jausctl run printed, or nothing when it failed.
  static std::optional<Json> json_line(ChildProcess& child) {
    if (child.wait(20s) != 0) return std::nullopt;
    std::istringstream lines(child.output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        Json parsed = Json::parse(line, nullptr, false);
        if (!parsed.is_discarded()) return parsed;
      }
    return std::nullopt;
  }

  std::optional<Json> status() {
    auto child = jausd->jausctl_own_id("status", {"status", kWaypointDriver, "--timeout", "2"}, kObserverBind);
    return json_line(*child);
  }

  // `jausctl query ADDR CODE [--pv PV]`: the report's fields, or nothing.
  std::optional<Json> query(const std::string& address, const std::string& code, const std::string& pv = "") {
    std::vector<std::string> args{"query", address, code, "--timeout", "2"};
    if (!pv.empty()) args.insert(args.end(), {"--pv", pv});
    auto child = jausd->jausctl_own_id("query", std::move(args), kObserverBind);
    auto report = json_line(*child);
    if (!report || !report->contains("fields")) return std::nullopt;
    return (*report)["fields"];
  }

  // Control of the waypoint driver, held by `controller` (authority 5, above the drivers' 1).
  void take_the_waypoint_driver() {
    controller = jausd->jausctl("control", {"control", kWaypointDriver, "--authority", "5", "--for", "180"},
                                std::string(kOperatorHost) + ":3794", kOperator);
    ASSERT_TRUE(controller->started());
    const auto granted_until = std::chrono::steady_clock::now() + 20s;
    while (!controller->output_contains("granted")) {
      ASSERT_TRUE(controller->running()) << controller->output();
      ASSERT_LT(std::chrono::steady_clock::now(), granted_until) << controller->output();
      std::this_thread::sleep_for(100ms);
    }
  }
  // `jausctl send` as the controller (its ID, its host).
  void send_as_controller(const std::string& message) {
    auto child = jausd->jausctl("send", {"send", kWaypointDriver, message, "--timeout", "0.2"},
                                std::string(kOperatorHost) + ":0", kOperator);
    ASSERT_EQ(child->wait(20s), 0) << message << "\n" << child->output();
  }

  std::optional<Point> local_position() {
    const auto pose = query(kPoseSensor, "Query Local Pose", "0x3");
    if (!pose || !pose->contains("x_m") || !pose->contains("y_m")) return std::nullopt;
    return Point{(*pose)["x_m"].get<double>(), (*pose)["y_m"].get<double>()};
  }

  bool driving() {
    const auto state = status();
    return state && ((*state)["secondary_status"].get<std::uint32_t>() & kDrivingBit) != 0;
  }

  // The route watched until it is finished (the driving bit seen set, then
  // clear again) or 120 s: and how close the vehicle came to `passing`.
  struct Drive {
    bool seen_driving = false, finished = false;
    double closest_m = 1e9;
  };
  Drive watch_the_route(const Point& passing);

  std::unique_ptr<DefaultJausd> jausd;
  std::unique_ptr<ChildProcess> controller;
};

double distance(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

Waypoints::Drive Waypoints::watch_the_route(const Point& passing) {
  Drive drive;
  const auto until = std::chrono::steady_clock::now() + 120s;
  while (!drive.finished && std::chrono::steady_clock::now() < until) {
    if (const auto state = status()) {
      const bool now_driving = ((*state)["secondary_status"].get<std::uint32_t>() & kDrivingBit) != 0;
      drive.seen_driving = drive.seen_driving || now_driving;
      drive.finished = drive.seen_driving && !now_driving;
    }
    if (const auto at = local_position()) drive.closest_m = std::min(drive.closest_m, distance(*at, passing));
    std::this_thread::sleep_for(200ms);
  }
  return drive;
}

TEST_F(Waypoints, JausctlLoadsFourLocalWaypointsResumesAndTheVehicleStopsAtTheLast) {
  ASSERT_NO_FATAL_FAILURE(take_the_waypoint_driver());

  // Standby, the travel speed and the list (loading never moves the vehicle), Resume.
  send_as_controller(R"({"name":"Standby"})");
  send_as_controller(R"({"name":"Set Travel Speed","fields":{"speed_mps":1.0}})");
  for (std::size_t n = 0; n < std::size(kSquare); ++n)
    send_as_controller(Json{{"name", "Set Local Waypoint"},
                            {"fields", {{"waypoint_number", n}, {"x_m", kSquare[n].x}, {"y_m", kSquare[n].y}}}}
                           .dump());
  const auto count = query(kWaypointDriver, "Query Waypoint Count");
  ASSERT_TRUE(count) << jausd->output();
  EXPECT_EQ((*count)["waypoint_count"], std::size(kSquare));
  const auto first = query(kWaypointDriver, "Query Local Waypoint");  // waypoint 0 (--fields default 0)
  ASSERT_TRUE(first);
  EXPECT_NEAR((*first)["x_m"].get<double>(), kSquare[0].x, 1e-3);
  send_as_controller(R"({"name":"Resume"})");

  // Driving, then finished: the driving bit set, then clear again; on the
  // way the vehicle passes the far corner.
  const Drive drive = watch_the_route(kSquare[1]);
  ASSERT_TRUE(drive.seen_driving) << controller->output() << jausd->output();
  ASSERT_TRUE(drive.finished) << controller->output() << jausd->output();
  EXPECT_LT(drive.closest_m, 1.0);  // pure pursuit cuts the corner a little

  // At the last waypoint, within the arrival tolerance; still there a moment later (stopped).
  const auto last = local_position();
  ASSERT_TRUE(last) << jausd->output();
  EXPECT_LE(distance(*last, kSquare[3]), kArrivalToleranceM) << last->x << ", " << last->y;
  std::this_thread::sleep_for(1s);
  const auto later = local_position();
  ASSERT_TRUE(later);
  EXPECT_LT(distance(*later, *last), 0.05) << later->x << ", " << later->y;
  // The list is kept for queries; the driver released the primitive driver; the operator still holds the driver.
  const auto kept = query(kWaypointDriver, "Query Waypoint Count");
  ASSERT_TRUE(kept);
  EXPECT_EQ((*kept)["waypoint_count"], std::size(kSquare));
  const auto primitive = query("7.1.33.1", "Query Component Control");
  ASSERT_TRUE(primitive);
  EXPECT_EQ((*primitive)["controller"], "0.0.0.0") << primitive->dump();
  EXPECT_TRUE(controller->running()) << controller->output();
}

// Issue 43, the RA implementations' start rule: a list loaded into the Ready
// driver waits until its controller sets a travel speed above zero, then
// drives (no Standby, no Resume), to the last waypoint.
TEST_F(Waypoints, AListLoadedInReadyDrivesOnceTheControllerSetsATravelSpeed) {
  ASSERT_NO_FATAL_FAILURE(take_the_waypoint_driver());
  const Point route[] = {{2, 0}, {2, 2}};
  for (std::size_t n = 0; n < std::size(route); ++n)
    send_as_controller(Json{{"name", "Set Local Waypoint"},
                            {"fields", {{"waypoint_number", n}, {"x_m", route[n].x}, {"y_m", route[n].y}}}}
                           .dump());
  const auto count = query(kWaypointDriver, "Query Waypoint Count");
  ASSERT_TRUE(count) << jausd->output();
  EXPECT_EQ((*count)["waypoint_count"], std::size(route));
  EXPECT_FALSE(driving());  // Ready, no travel speed set: it waits
  send_as_controller(R"({"name":"Set Travel Speed","fields":{"speed_mps":1.0}})");
  const Drive drive = watch_the_route(route[0]);
  ASSERT_TRUE(drive.seen_driving) << controller->output() << jausd->output();
  ASSERT_TRUE(drive.finished) << controller->output() << jausd->output();
  const auto last = local_position();
  ASSERT_TRUE(last) << jausd->output();
  EXPECT_LE(distance(*last, route[1]), kArrivalToleranceM) << last->x << ", " << last->y;
}

// Issue 42, the README's route with Set Component Authority 255 sent to the
// waypoint driver before Resume: refused (its authority stays 1, the
// drivers' ceiling max_authority), so an operator asking the primitive
// driver at 2 takes it from the driver at once and the route stops.
TEST_F(Waypoints, SetComponentAuthority255IsRefusedAndAnOperatorAtAuthority2StopsTheRoute) {
  ASSERT_NO_FATAL_FAILURE(take_the_waypoint_driver());
  send_as_controller(R"({"name":"Standby"})");
  send_as_controller(R"({"name":"Set Travel Speed","fields":{"speed_mps":1.0}})");
  // One waypoint far enough that the route is still driving when taken over.
  send_as_controller(R"({"name":"Set Local Waypoint","fields":{"waypoint_number":0,"x_m":60,"y_m":0}})");
  send_as_controller(R"({"name":"Set Component Authority","fields":{"authority":255}})");
  const auto authority = query(kWaypointDriver, "Query Component Authority");
  ASSERT_TRUE(authority) << jausd->output();
  EXPECT_EQ((*authority)["authority"], 1) << authority->dump();
  EXPECT_TRUE(jausd->output_shows("Set Component Authority 255 from 254.111.40.1 refused: above max_authority 1"))
      << jausd->output();
  send_as_controller(R"({"name":"Resume"})");

  // Driving, and the driver holds the primitive driver at its ceiling.
  const auto driving_until = std::chrono::steady_clock::now() + 60s;
  for (;;) {
    const auto state = status();
    if (state && ((*state)["secondary_status"].get<std::uint32_t>() & kDrivingBit) != 0) break;
    ASSERT_LT(std::chrono::steady_clock::now(), driving_until) << jausd->output();
    std::this_thread::sleep_for(200ms);
  }
  const auto held = query("7.1.33.1", "Query Component Control");
  ASSERT_TRUE(held) << jausd->output();
  EXPECT_EQ((*held)["controller"], kWaypointDriver) << held->dump();
  EXPECT_EQ((*held)["authority"], 1) << held->dump();

  // Another operator takes the primitive driver at authority 2.
  auto other = jausd->jausctl("operator", {"control", "7.1.33.1", "--authority", "2", "--for", "60"},
                              "127.0.0.113:0", "254.113.40.1");
  ASSERT_TRUE(other->started());
  const auto taken_until = std::chrono::steady_clock::now() + 20s;
  while (!other->output_contains("granted")) {
    ASSERT_TRUE(other->running()) << other->output() << jausd->output();
    ASSERT_LT(std::chrono::steady_clock::now(), taken_until) << other->output();
    std::this_thread::sleep_for(100ms);
  }
  // The route stops: the driving bit clears, the vehicle stands still, the operator holds the primitive driver.
  bool stopped_driving = false;
  const auto stop_until = std::chrono::steady_clock::now() + 20s;
  while (!stopped_driving && std::chrono::steady_clock::now() < stop_until) {
    const auto state = status();
    stopped_driving = state && ((*state)["secondary_status"].get<std::uint32_t>() & kDrivingBit) == 0;
    if (!stopped_driving) std::this_thread::sleep_for(200ms);
  }
  EXPECT_TRUE(stopped_driving) << jausd->output();
  std::optional<Point> before, after;
  const auto still_until = std::chrono::steady_clock::now() + 20s;
  for (;;) {  // the vehicle decelerates: still once two positions 1 s apart agree
    before = local_position();
    std::this_thread::sleep_for(1s);
    after = local_position();
    if (before && after && distance(*before, *after) < 0.05) break;
    ASSERT_LT(std::chrono::steady_clock::now(), still_until) << jausd->output();
  }
  EXPECT_LT(after->x, 55) << "the route was not stopped: the vehicle reached " << after->x;
  EXPECT_TRUE(jausd->output_shows("lost control of the primitive driver")) << jausd->output();
  const auto now_held = query("7.1.33.1", "Query Component Control");
  ASSERT_TRUE(now_held);
  EXPECT_EQ((*now_held)["controller"], "254.113.40.1") << now_held->dump();
  EXPECT_TRUE(other->running()) << other->output();
  other->signal(SIGINT);
  other->wait(10s);
}

}  // namespace
}  // namespace jaus::test
