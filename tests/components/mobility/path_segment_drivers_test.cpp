// The global and local path segment drivers (components 47 and 48, issue 30)
// on a whole vehicle node under virtual time (drive_node.hpp). Done when (the
// issue): "a path of three segments is followed within a stated cross-track
// error": a straight segment (weight 0), a curve (weight 1, tightest radius
// 2.1 m) and a tighter one (weight 2, tightest radius 1.4 m, above the
// Ackermann vehicle's 0.92 m turning radius) are driven to their end within
// the arrival tolerance, the cross-track error staying within kMaxCrossTrack_m
// (0.15 m; measured: max 0.05 m) after the first metre, on both platforms and
// both drivetrains.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "drive_node.hpp"
#include "jaus/components/global_path_segment_driver.hpp"
#include "jaus/components/local_frame.hpp"
#include "jaus/components/local_path_segment_driver.hpp"

namespace jaus::test {
namespace {

using components::Steering;

const Address kGlobalDriver{1, 1, 47, 1};
const Address kLocalDriver{1, 1, 48, 1};

// The cross-track error stated for the three-segment path (pure pursuit with
// a 1 m lookahead cuts a curve of radius R by about lookahead^2 / (8 R)).
constexpr double kMaxCrossTrack_m = 0.15;
constexpr double kArrivalTolerance_m = 0.5;
// Travel Speed on the wire: 0..10000 m/s in 16 bits.
constexpr double kTravelSpeedResolution_mps = 10000.0 / 65535;

struct LocalPoint {
  double x_m, y_m;  // from the vehicle's start: north, east
};
struct SegmentPoints {
  LocalPoint p1, p2;
  double weight;
};
// The three segments, from the vehicle's start heading north: 4 m straight
// on, a right turn to east, a tighter right turn to south.
const std::vector<SegmentPoints> kThreeSegments = {
    {{2, 0}, {4, 0}, 0},
    {{7, 0}, {7, 3}, 1},
    {{7, 7}, {3, 7}, 2},
};

msg::SetLocalPathSegment local_segment(std::uint16_t number, LocalPoint p1, LocalPoint p2, double weight) {
  msg::SetLocalPathSegment m;
  m.path_segment_number = number;
  m.p1_x_m = p1.x_m;
  m.p1_y_m = p1.y_m;
  m.p2_x_m = p2.x_m;
  m.p2_y_m = p2.y_m;
  m.weighting_factor = weight;
  return m;
}

struct NodeCase {
  PlatformUnderTest platform;
  Steering steering;
};
std::string case_name(const NodeCase& c) {
  return platform_name(c.platform) + (c.steering == Steering::ackermann ? "_ackermann" : "_differential");
}

DriveNodeOptions node_options(const NodeCase& c, std::map<std::string, std::string> driver_options = {}) {
  driver_options.emplace("travel_speed_mps", "0.8");
  return DriveNodeOptions{.platform = c.platform,
                          .steering = c.steering,
                          .drivers = {"global_path_segment_driver", "local_path_segment_driver"},
                          .driver_options = std::move(driver_options)};
}

// An operator's session with one path segment driver of the node.
class PathSession {
 public:
  PathSession(DriveNode& node, const Address& driver) : node_(node), driver_(driver) {}

  components::PathSegmentDriver& driver() { return node_.component<components::PathSegmentDriver>(driver_); }
  bool global() const { return driver_ == kGlobalDriver; }

  // The segment as Set ... Path Segment of this driver, its points from `origin`
  // (the vehicle's local frame; global: the same points on the globe).
  void send_segment(std::uint16_t number, const SegmentPoints& s, const components::LocalPosition& origin) {
    const LocalPoint p1{origin.x_m + s.p1.x_m, origin.y_m + s.p1.y_m};
    const LocalPoint p2{origin.x_m + s.p2.x_m, origin.y_m + s.p2.y_m};
    if (!global()) {
      node_.send(driver_, local_segment(number, p1, p2, s.weight));
    } else {
      // Projected from a frame at the vehicle's geo position, shifted by its local one.
      const auto here = node_.pose();
      const components::LocalFrame frame(*here.position);
      const auto& l = *here.local_position;
      const auto g1 = frame.to_geo({p1.x_m - l.x_m, p1.y_m - l.y_m, 0});
      const auto g2 = frame.to_geo({p2.x_m - l.x_m, p2.y_m - l.y_m, 0});
      msg::SetGlobalPathSegment m;
      m.path_segment_number = number;
      m.p1_latitude_deg = g1.latitude_deg;
      m.p1_longitude_deg = g1.longitude_deg;
      m.p2_latitude_deg = g2.latitude_deg;
      m.p2_longitude_deg = g2.longitude_deg;
      m.weighting_factor = s.weight;
      node_.send(driver_, m);
    }
    node_.run_for(20ms);
  }
  void load(const std::vector<SegmentPoints>& segments) {
    const auto origin = *node_.pose().local_position;
    for (std::size_t i = 0; i < segments.size(); ++i) send_segment(static_cast<std::uint16_t>(i), segments[i], origin);
  }
  bool control() { return node_.take_control(driver_); }
  void standby() {
    node_.send(driver_, msg::Standby{});
    node_.run_until([&] { return node_.state_of(driver_) == rt::PrimaryStatus::standby; }, 1s);
  }
  void resume() {
    node_.send(driver_, msg::Resume{});
    node_.run_until([&] { return node_.state_of(driver_) == rt::PrimaryStatus::ready; }, 1s);
  }
  // Control, Standby, the list, Resume: the operator's way to start a route.
  void start(const std::vector<SegmentPoints>& segments) {
    ASSERT_TRUE(control());
    standby();
    load(segments);
    ASSERT_EQ(driver().segment_count(), segments.size());
    resume();
  }

  // The vehicle's distance from the path now, if a route started.
  std::optional<components::guidance::PathProjection> projection() {
    const auto* pursuit = driver().pursuit();
    if (!pursuit) return std::nullopt;
    const auto here = driver().position_in_route(node_.pose());
    if (!here) return std::nullopt;
    return pursuit->path().project(*here);
  }

  // The cross-track error every 50 ms once a metre of the path is behind.
  struct CrossTrack {
    double max_m = 0, sum_m = 0;
    int samples = 0;
    double mean_m() const { return samples ? sum_m / samples : 0; }
  };
  // Drives until the route ends (or `limit`), measuring the cross-track error.
  CrossTrack drive_to_end_measured(rt::Duration limit = 60s) {
    CrossTrack error;
    const rt::TimePoint until = node_.time().now() + limit;
    while (!driver().route_finished() && node_.time().now() < until) {
      node_.run_for(50ms);
      if (const auto at = projection(); at && at->arc_length_m > 1.0) {
        error.max_m = std::max(error.max_m, std::abs(at->cross_track_m));
        error.sum_m += std::abs(at->cross_track_m);
        ++error.samples;
      }
    }
    return error;
  }
  double drive_to_end(rt::Duration limit = 60s) { return drive_to_end_measured(limit).max_m; }
  double distance_to_end() {
    const auto here = driver().position_in_route(node_.pose());
    return components::guidance::distance(*here, driver().pursuit()->path().end());
  }

 private:
  DriveNode& node_;
  Address driver_;
};

bool stopped(DriveNode& node) { return node.speed_mps() < 0.01; }
bool moving(DriveNode& node) { return node.speed_mps() > 0.05; }

// ---- the path, followed -----------------------------------------------------------

class ThreeSegmentPath : public ::testing::TestWithParam<NodeCase> {};

void follow_three_segments(const NodeCase& c, const Address& driver) {
  DriveNode node(node_options(c));
  ASSERT_TRUE(node.wait_ready());
  PathSession session(node, driver);
  session.start(kThreeSegments);
  ASSERT_TRUE(node.run_until([&] { return session.driver().driving(); }, 1s));
  const auto cross_track = session.drive_to_end_measured();
  ASSERT_TRUE(session.driver().route_finished());
  const double off_end = session.distance_to_end();
  std::printf("[ path ] %s %s: length %.2f m, cross-track mean %.3f m, max %.3f m, end within %.3f m\n",
              session.global() ? "global" : "local", case_name(c).c_str(),
              session.driver().pursuit()->path().length_m(), cross_track.mean_m(), cross_track.max_m, off_end);
  EXPECT_GT(cross_track.samples, 100);  // measured along the whole path (every 50 ms)
  EXPECT_LE(cross_track.max_m, kMaxCrossTrack_m);
  EXPECT_LE(off_end, kArrivalTolerance_m);
  // Finished: zero below, control released, the list kept for queries.
  EXPECT_FALSE(session.driver().driving());
  EXPECT_EQ(session.driver().mobility_counters().arrivals, 1u);
  EXPECT_EQ(session.driver().path_counters().routes_finished, 1u);
  EXPECT_FALSE(node.primitive_driver().control().controller());
  EXPECT_TRUE(node.run_until([&] { return stopped(node); }, 5s));
  EXPECT_EQ(session.driver().segment_count(), 3u);
  // A finished route does not drive again on Resume.
  session.standby();
  session.resume();
  node.run_for(2s);
  EXPECT_FALSE(session.driver().driving());
  EXPECT_TRUE(stopped(node));
}

TEST_P(ThreeSegmentPath, LocalSegmentsAreFollowedWithinTheStatedCrossTrackError) {
  follow_three_segments(GetParam(), kLocalDriver);
}

INSTANTIATE_TEST_SUITE_P(PlatformsAndDrivetrains, ThreeSegmentPath,
                         ::testing::Values(NodeCase{PlatformUnderTest::model, Steering::differential},
                                           NodeCase{PlatformUnderTest::model, Steering::ackermann},
                                           NodeCase{PlatformUnderTest::clearpath_sim, Steering::differential},
                                           NodeCase{PlatformUnderTest::clearpath_sim, Steering::ackermann}),
                         [](const auto& p) { return case_name(p.param); });

class GlobalThreeSegmentPath : public ::testing::TestWithParam<NodeCase> {};

TEST_P(GlobalThreeSegmentPath, GlobalSegmentsAreFollowedWithinTheStatedCrossTrackError) {
  follow_three_segments(GetParam(), kGlobalDriver);
}

// One platform per drivetrain.
INSTANTIATE_TEST_SUITE_P(OnePlatformPerDrivetrain, GlobalThreeSegmentPath,
                         ::testing::Values(NodeCase{PlatformUnderTest::model, Steering::differential},
                                           NodeCase{PlatformUnderTest::clearpath_sim, Steering::ackermann}),
                         [](const auto& p) { return case_name(p.param); });

// ---- what each kind does, either frame --------------------------------------------

class PathSegmentDriverTest : public ::testing::TestWithParam<Address> {
 protected:
  PathSegmentDriverTest() : node_(node_options({PlatformUnderTest::model, Steering::differential},
                                               {{"max_path_segments", "4"}})),
                            session_(node_, GetParam()) {
    EXPECT_TRUE(node_.wait_ready());
  }
  const Address& driver_address() const { return GetParam(); }
  components::PathSegmentDriver& driver() { return session_.driver(); }
  std::optional<std::uint16_t> count() {
    const auto r = node_.ask<msg::ReportPathSegmentCount>(driver_address(), msg::QueryPathSegmentCount{});
    if (!r) return std::nullopt;
    return r->path_segment_count;
  }
  double commanded_linear() {
    return node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent.value_or(0);
  }
  // Drives until `metres` of the path are behind the vehicle.
  bool drive_until_progress(double metres) {
    return node_.run_until(
        [&] { return driver().pursuit() && driver().pursuit()->progress_m() >= metres; }, 20s);
  }

  DriveNode node_;
  PathSession session_;
};

// Echo of segment `n` (presence `pv` asked) as the driver's own report, decoded.
template <class Report, class Query>
std::optional<Report> ask_segment(DriveNode& node, const Address& to, std::uint16_t n, std::uint8_t pv) {
  Query q;
  q.path_segment_number = n;
  q.presence_vector = pv;
  return node.ask<Report>(to, q);
}

TEST_P(PathSegmentDriverTest, NumberingFromZeroNewListAppendReplaceAndGapsRefused) {
  ASSERT_TRUE(session_.control());
  const auto origin = components::LocalPosition{};
  session_.send_segment(0, {{1, 0}, {2, 0}, 0}, origin);
  session_.send_segment(1, {{3, 0}, {4, 0}, 0}, origin);
  EXPECT_EQ(count(), 2);
  // A gap: refused, nothing stored.
  session_.send_segment(3, {{9, 9}, {9, 9}, 0}, origin);
  EXPECT_EQ(count(), 2);
  EXPECT_EQ(driver().path_counters().segments_refused, 1u);
  // Replace 1, append 2 and 3; the list holds at most max_path_segments (4).
  session_.send_segment(1, {{3, 1}, {4, 1}, 5}, origin);
  session_.send_segment(2, {{5, 0}, {6, 0}, 0}, origin);
  session_.send_segment(3, {{7, 0}, {8, 0}, 0}, origin);
  EXPECT_EQ(count(), 4);
  session_.send_segment(4, {{9, 0}, {10, 0}, 0}, origin);
  EXPECT_EQ(count(), 4);
  EXPECT_EQ(driver().path_counters().segments_refused, 2u);
  // Segment 1 as replaced (global: the weight, and the points' order survives).
  if (driver_address() == kLocalDriver) {
    const auto r = ask_segment<msg::ReportLocalPathSegment, msg::QueryLocalPathSegment>(node_, kLocalDriver, 1, 0xFF);
    ASSERT_TRUE(r);
    EXPECT_NEAR(r->p1_y_m, 1, 1e-3);
    EXPECT_NEAR(r->p2_x_m, 4, 1e-3);
    EXPECT_NEAR(r->weighting_factor, 5, 0.01);
  } else {
    const auto r =
        ask_segment<msg::ReportGlobalPathSegment, msg::QueryGlobalPathSegment>(node_, kGlobalDriver, 1, 0xFF);
    ASSERT_TRUE(r);
    EXPECT_NEAR(r->weighting_factor, 5, 0.01);
  }
  // Number 0 starts a new list.
  session_.send_segment(0, {{1, 1}, {2, 2}, 1}, origin);
  EXPECT_EQ(count(), 1);
  EXPECT_EQ(driver().path_counters().segments_stored, 6u);
}

TEST_P(PathSegmentDriverTest, AReportEchoesTheSegmentAsSetMaskedByTheQuery) {
  ASSERT_TRUE(session_.control());
  if (driver_address() == kLocalDriver) {
    auto m = local_segment(0, {1.5, -2.25}, {3, 4}, 12.5);
    m.p1_z_m = -1.0;
    m.p2_z_m = 2.0;
    node_.send(kLocalDriver, m);
    node_.run_for(20ms);
    const auto all = ask_segment<msg::ReportLocalPathSegment, msg::QueryLocalPathSegment>(node_, kLocalDriver, 0, 0x03);
    ASSERT_TRUE(all);
    // As set (to the codec's resolution), both optional z included.
    EXPECT_EQ(all->path_segment_number, 0);
    EXPECT_NEAR(all->p1_x_m, 1.5, 1e-3);
    EXPECT_NEAR(all->p1_y_m, -2.25, 1e-3);
    EXPECT_NEAR(all->p2_x_m, 3, 1e-3);
    EXPECT_NEAR(all->p2_y_m, 4, 1e-3);
    ASSERT_TRUE(all->p1_z_m && all->p2_z_m);
    EXPECT_NEAR(*all->p1_z_m, -1, 0.01);
    EXPECT_NEAR(*all->p2_z_m, 2, 0.01);
    EXPECT_NEAR(all->weighting_factor, 12.5, 0.01);
    const auto p2_only =
        ask_segment<msg::ReportLocalPathSegment, msg::QueryLocalPathSegment>(node_, kLocalDriver, 0, 0x02);
    ASSERT_TRUE(p2_only);
    EXPECT_FALSE(p2_only->p1_z_m);
    EXPECT_TRUE(p2_only->p2_z_m);
    EXPECT_NEAR(p2_only->p1_x_m, 1.5, 1e-3);
  } else {
    msg::SetGlobalPathSegment m;
    m.path_segment_number = 0;
    m.p1_latitude_deg = 45.5;
    m.p1_longitude_deg = -73.25;
    m.p1_elevation_m = 100;
    m.p2_latitude_deg = 45.75;
    m.p2_longitude_deg = -73.5;
    m.weighting_factor = 250;
    node_.send(kGlobalDriver, m);
    node_.run_for(20ms);
    const auto all =
        ask_segment<msg::ReportGlobalPathSegment, msg::QueryGlobalPathSegment>(node_, kGlobalDriver, 0, 0x03);
    ASSERT_TRUE(all);
    // The codec's scaled integers round: compared field by field.
    EXPECT_NEAR(all->p1_latitude_deg, 45.5, 1e-6);
    EXPECT_NEAR(all->p2_longitude_deg, -73.5, 1e-6);
    ASSERT_TRUE(all->p1_elevation_m);
    EXPECT_NEAR(*all->p1_elevation_m, 100, 0.01);
    EXPECT_FALSE(all->p2_elevation_m);  // not set, not made up
    EXPECT_NEAR(all->weighting_factor, 250, 0.01);
    const auto none =
        ask_segment<msg::ReportGlobalPathSegment, msg::QueryGlobalPathSegment>(node_, kGlobalDriver, 0, 0x00);
    ASSERT_TRUE(none);
    EXPECT_FALSE(none->p1_elevation_m);
  }
}

TEST_P(PathSegmentDriverTest, AQueryBeyondTheCountGetsNoReply) {
  ASSERT_TRUE(session_.control());
  session_.send_segment(0, {{1, 0}, {2, 0}, 0}, {});
  const bool local = driver_address() == kLocalDriver;
  const auto answered =
      local ? ask_segment<msg::ReportLocalPathSegment, msg::QueryLocalPathSegment>(node_, kLocalDriver, 1, 0xFF)
                  .has_value()
            : ask_segment<msg::ReportGlobalPathSegment, msg::QueryGlobalPathSegment>(node_, kGlobalDriver, 1, 0xFF)
                  .has_value();
  EXPECT_FALSE(answered);
  EXPECT_EQ(driver().path_counters().queries_unanswered, 1u);
}

TEST_P(PathSegmentDriverTest, OnlyTheControllerLoadsSegmentsAndTheTravelSpeed) {
  session_.send_segment(0, {{1, 0}, {2, 0}, 0}, {});
  node_.send(driver_address(), msg::SetTravelSpeed{{0.3}});
  node_.run_for(20ms);
  EXPECT_EQ(count(), 0);
  EXPECT_EQ(driver().travel_speed_mps(), 0.8);  // the option's, unchanged
  EXPECT_EQ(driver().counters().refused_not_controller, 2u);
  // With control, in Ready: a list without a travel speed set in Ready moves nothing.
  ASSERT_TRUE(session_.control());
  session_.send_segment(0, {{1, 0}, {2, 0}, 0}, {});
  EXPECT_EQ(count(), 1);
  node_.run_for(1s);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped(node_));
  // Its Set Travel Speed is taken and, above zero in Ready, drives the list
  // (start rule 2, route_start_test.cpp).
  node_.send(driver_address(), msg::SetTravelSpeed{{0.3}});
  node_.run_for(20ms);
  const auto speed = node_.ask<msg::ReportTravelSpeed>(driver_address(), msg::QueryTravelSpeed{});
  ASSERT_TRUE(speed);
  EXPECT_NEAR(speed->speed_mps, 0.3, kTravelSpeedResolution_mps);
  EXPECT_TRUE(driver().driving());
}

TEST_P(PathSegmentDriverTest, ResumeStartsStandbyPausesAndResumeContinuesFromTheProgress) {
  session_.start(kThreeSegments);
  ASSERT_TRUE(drive_until_progress(2.5));
  const auto p0 = driver().pursuit()->path().segments().front().p0;
  session_.standby();
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(commanded_linear(), 0);
  ASSERT_TRUE(node_.run_until([&] { return stopped(node_); }, 5s));
  const double paused_at = driver().pursuit()->progress_m();
  node_.run_for(2s);
  EXPECT_TRUE(stopped(node_));
  session_.resume();
  ASSERT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  // The same path (its P0), continued from where it paused.
  EXPECT_EQ(driver().pursuit()->path().segments().front().p0, p0);
  EXPECT_GE(driver().pursuit()->progress_m(), paused_at - 0.1);
  EXPECT_EQ(driver().path_counters().routes_started, 1u);
  session_.drive_to_end();
  EXPECT_TRUE(driver().route_finished());
  EXPECT_LE(session_.distance_to_end(), kArrivalTolerance_m);
}

TEST_P(PathSegmentDriverTest, ASegmentAppendedToAPausedRouteExtendsItsPathFromTheSameStart) {
  const std::vector<SegmentPoints> first_two(kThreeSegments.begin(), kThreeSegments.begin() + 2);
  const auto origin = *node_.pose().local_position;
  session_.start(first_two);
  ASSERT_TRUE(drive_until_progress(2.5));
  const auto p0 = driver().pursuit()->path().segments().front().p0;
  const double two_segments_m = driver().pursuit()->path().length_m();
  session_.standby();
  session_.send_segment(2, kThreeSegments[2], origin);
  EXPECT_EQ(count(), 3);
  session_.resume();
  ASSERT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  EXPECT_EQ(driver().pursuit()->path().segments().size(), 3u);
  EXPECT_EQ(driver().pursuit()->path().segments().front().p0, p0);
  EXPECT_GT(driver().pursuit()->path().length_m(), two_segments_m + 5);
  EXPECT_GT(driver().pursuit()->progress_m(), 2.0);  // from the vehicle's nearest point, not the start
  EXPECT_LE(session_.drive_to_end(), kMaxCrossTrack_m);
  EXPECT_TRUE(driver().route_finished());
  EXPECT_LE(session_.distance_to_end(), kArrivalTolerance_m);
}

TEST_P(PathSegmentDriverTest, TravelSpeedLimitsTheRouteAndZeroHoldsItStill) {
  ASSERT_TRUE(session_.control());
  node_.send(driver_address(), msg::SetTravelSpeed{{0.3}});
  session_.standby();
  session_.load({{{10, 0}, {20, 0}, 0}});
  session_.resume();
  ASSERT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  node_.run_for(4s);
  EXPECT_NEAR(node_.speed_mps(), 0.3, 0.05);
  node_.send(driver_address(), msg::SetTravelSpeed{{0}});
  ASSERT_TRUE(node_.run_until([&] { return stopped(node_); }, 5s));
  node_.run_for(2s);
  EXPECT_TRUE(stopped(node_));
  EXPECT_TRUE(driver().driving());  // the route still runs
  node_.send(driver_address(), msg::SetTravelSpeed{{0.6}});
  EXPECT_TRUE(node_.run_until([&] { return node_.speed_mps() > 0.5; }, 5s));
}

TEST_P(PathSegmentDriverTest, ANewListHaltsTheRouteAndResetClearsListAndTravelSpeed) {
  session_.start(kThreeSegments);
  ASSERT_TRUE(drive_until_progress(1.0));
  session_.send_segment(0, {{1, 0}, {2, 0}, 0}, {});
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(driver().last_halt(), "new list");
  EXPECT_FALSE(driver().pursuit());
  EXPECT_EQ(count(), 1);
  node_.send(driver_address(), msg::SetTravelSpeed{{0.2}});
  node_.send(driver_address(), msg::Reset{});
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(driver_address()) == rt::PrimaryStatus::ready; }, 2s));
  EXPECT_EQ(count(), 0);
  const auto speed = node_.ask<msg::ReportTravelSpeed>(driver_address(), msg::QueryTravelSpeed{});
  ASSERT_TRUE(speed);
  EXPECT_NEAR(speed->speed_mps, 0.8, kTravelSpeedResolution_mps);  // the option's
}

// ---- the safety rules every driver keeps ------------------------------------------

TEST_P(PathSegmentDriverTest, AnOperatorTakingThePrimitiveDriverStopsTheRouteAndNothingRestartsIt) {
  session_.start(kThreeSegments);
  ASSERT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  ASSERT_TRUE(node_.take_control(kPrimitiveDriver));  // authority 5 > 1
  EXPECT_TRUE(node_.run_until([&] { return !driver().driving(); }, 1s));
  EXPECT_EQ(driver().mobility_counters().control_losses, 1u);
  const auto status = node_.ask<msg::ReportComponentStatus>(driver_address(), msg::QueryComponentStatus{});
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->secondary_status & components::mobility_status::kLostControl);
  EXPECT_FALSE(status->secondary_status & components::mobility_status::kDriving);
  EXPECT_TRUE(node_.run_until([&] { return stopped(node_); }, 5s));
  const auto efforts = driver().mobility_counters().efforts_sent;
  node_.run_for(3s);
  EXPECT_EQ(driver().mobility_counters().efforts_sent, efforts);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped(node_));
}

TEST_P(PathSegmentDriverTest, SetEmergencyStopsTheRouteAndClearEmergencyDoesNotRestartIt) {
  session_.start(kThreeSegments);
  ASSERT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  node_.send(kPrimitiveDriver, msg::SetEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return !driver().driving(); }, 1s));
  EXPECT_TRUE(node_.run_until([&] { return stopped(node_); }, 5s));
  node_.send(kPrimitiveDriver, msg::ClearEmergency{{1}});
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(kPrimitiveDriver) == rt::PrimaryStatus::ready; }, 1s));
  node_.run_for(3s);
  EXPECT_FALSE(driver().driving());
  EXPECT_TRUE(stopped(node_));
  EXPECT_FALSE(node_.primitive_driver().control().controller());
  // The list and the progress are kept: Standby and Resume continue the route.
  ASSERT_TRUE(node_.run_until([&] { return node_.state_of(driver_address()) == rt::PrimaryStatus::ready; }, 2s));
  const double progress = driver().pursuit()->progress_m();
  EXPECT_GT(progress, 0);
  session_.standby();
  session_.resume();
  EXPECT_TRUE(node_.run_until([&] { return moving(node_); }, 3s));
  EXPECT_GE(driver().pursuit()->progress_m(), progress - 0.1);
}

TEST_P(PathSegmentDriverTest, StandbyOnTheDriverCommandsZeroAndStopsTheVehicle) {
  session_.start(kThreeSegments);
  ASSERT_TRUE(node_.run_until([&] { return moving(node_) && commanded_linear() > 0; }, 3s));
  session_.standby();
  EXPECT_FALSE(driver().driving());
  EXPECT_EQ(commanded_linear(), 0);
  EXPECT_TRUE(node_.run_until([&] { return stopped(node_); }, 5s));
  EXPECT_FALSE(node_.primitive_driver().control().controller());
}

INSTANTIATE_TEST_SUITE_P(Kinds, PathSegmentDriverTest, ::testing::Values(kGlobalDriver, kLocalDriver),
                         [](const auto& p) { return p.param == kGlobalDriver ? "global" : "local"; });

// ---- the kinds ----------------------------------------------------------------------

TEST(PathSegmentDriverKinds, OptionsAreCheckedWithTheirRanges) {
  const std::map<std::string, std::string> bad = {{"lookahead_m", "0"}};
  const auto error = components::path_segment_driver_options({"local_path_segment_driver", bad});
  ASSERT_FALSE(error);
  EXPECT_EQ(error.error().field, "lookahead_m");
  const std::map<std::string, std::string> fractional = {{"max_path_segments", "2.5"}};
  EXPECT_FALSE(components::path_segment_driver_options({"global_path_segment_driver", fractional}));
  const std::map<std::string, std::string> good = {{"travel_speed_mps", "0"}, {"arrival_tolerance_m", "1"}};
  const auto ok = components::path_segment_driver_options({"global_path_segment_driver", good});
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->travel_speed_mps, 0);
  EXPECT_EQ(ok->arrival_tolerance_m, 1);
  EXPECT_EQ(ok->max_path_segments, 1000u);
}

}  // namespace
}  // namespace jaus::test
