// The mobility driver cases (vector, waypoint and path segment drivers,
// components 34 and 44-48) against our six driver kinds on one node in this
// process, on the components' own simulated vehicle: on each driver every
// case that applies passes, those of its kind pass rather than skip, and it
// is left as found (nobody in control of it, the primitive driver released
// by it, the vehicle not driven, no list left loaded). Each case says why it
// does not apply to a component of another kind. On a memory network under
// virtual time.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "broken_mobility_components.hpp"
#include "case_results.hpp"
#include "ready_start_waypoint_driver.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::conform {
namespace {

using namespace std::chrono_literals;
using namespace test;

const Address kManager{1, 1, 1, 1};
const Address kPrimitiveDriver{1, 1, 33, 1};
const Address kGlobalVectorDriver{1, 1, 34, 1};
const Address kLocalVectorDriver{1, 1, 44, 1};
const Address kGlobalWaypointDriver{1, 1, 45, 1};
const Address kLocalWaypointDriver{1, 1, 46, 1};
const Address kGlobalPathSegmentDriver{1, 1, 47, 1};
const Address kLocalPathSegmentDriver{1, 1, 48, 1};

// A vehicle node with the six drivers at authority 1 (as jausd's default
// configuration has them), beside the primitive driver and the pose sensor.
class MobilityNode {
 public:
  MobilityNode(rt::VirtualTime& time, testing::MemoryNetwork& network) : link_(network.attach(1, 1)) {
    host::HostConfig config;
    config.node.subsystem = 1;
    config.node.node = 1;
    auto spec = [](const char* kind, const Address& at, std::uint8_t authority = 0) {
      return host::ComponentSpec{kind, at.component, 1, authority, kind, {}, 0, {}};
    };
    config.components = {spec("node_manager", kManager),
                         spec("primitive_driver", kPrimitiveDriver),
                         spec("global_pose_sensor", {1, 1, 38, 1}),
                         spec("global_vector_driver", kGlobalVectorDriver, 1),
                         spec("local_vector_driver", kLocalVectorDriver, 1),
                         spec("global_waypoint_driver", kGlobalWaypointDriver, 1),
                         spec("local_waypoint_driver", kLocalWaypointDriver, 1),
                         spec("global_path_segment_driver", kGlobalPathSegmentDriver, 1),
                         spec("local_path_segment_driver", kLocalPathSegmentDriver, 1)};
    auto host = host::NodeHost::attach(config, link_, time, time);
    if (!host) throw std::runtime_error(host.error().message());
    host_ = std::move(*host);
    link_.deliver_to(host_->node());
  }
  ~MobilityNode() {
    host_.reset();  // stopped while its link still carries the last messages
    link_.on_receive({});
    link_.set_connected(false);
  }
  MobilityNode(const MobilityNode&) = delete;
  MobilityNode& operator=(const MobilityNode&) = delete;
  host::NodeHost& host() { return *host_; }

 private:
  testing::MemoryLink& link_;
  std::unique_ptr<host::NodeHost> host_;
};

struct Driver {
  Address address;
  std::vector<std::string_view> passing;  // the case id prefixes that must pass on it (not skip)
  std::uint16_t count_query = 0;          // Query Waypoint/Path Segment Count; 0: no list
};

void PrintTo(const Driver& d, std::ostream* out) { *out << d.address.to_string(); }

class MobilityConformance : public ::testing::TestWithParam<Driver> {
 protected:
  void SetUp() override {
    node = std::make_unique<MobilityNode>(net.time, net.network);
    auto opened = net.open_session();
    ASSERT_TRUE(opened) << opened.error().message();
    session = std::move(*opened);
  }

  rt::Component& component_at(const Address& address) {
    auto* found = node->host().node().find(address);
    if (found == nullptr) throw std::runtime_error("no component at " + address.to_string());
    return *found;
  }

  // Nobody controls `component` once the last Release Component Control,
  // maybe still on its way, has arrived.
  bool released(const rt::Component& component) {
    return session->run_until([&] { return !component.control().controller().has_value(); }, 3s);
  }

  VirtualNetwork net;
  std::unique_ptr<MobilityNode> node;
  std::unique_ptr<ocu::OcuSession> session;
};

TEST_P(MobilityConformance, EveryApplicableCasePassesAndThoseOfItsKindRun) {
  const Driver& tested = GetParam();
  rt::Component& driver = component_at(tested.address);
  // A driver is Ready once the primitive driver has told it its specifications.
  ASSERT_TRUE(session->run_until([&] { return driver.state() == msg::PrimaryStatus::ready; }, 5s));

  RunOptions options;
  options.skip = "control.silent_requester";  // runs in multi_requester_cases_test.cpp
  const auto results = net.run_on(*session, tested.address, options);
  ASSERT_EQ(results.size(), all_cases().size() - 1) << describe(results);
  std::size_t of_its_kind = 0;
  for (const auto& r : results) {
    EXPECT_NE(r.outcome.verdict, Verdict::fail) << r.test_case->id << ": " << r.outcome.detail;
    for (const auto prefix : tested.passing)
      if (std::string_view(r.test_case->id).starts_with(prefix)) {
        ++of_its_kind;
        EXPECT_EQ(r.outcome.verdict, Verdict::pass) << r.test_case->id << ": " << r.outcome.detail;
      }
  }
  EXPECT_GE(of_its_kind, 2u);

  // Left as found: nobody controls it, it released the primitive driver, the
  // vehicle is not driven, and no list a case loaded is left (Reset).
  EXPECT_TRUE(released(driver));
  EXPECT_TRUE(released(component_at(kPrimitiveDriver)));
  const components::WrenchEffort effort = node->host().platform_as<host::ModelPlatform>()->vehicle()->applied_effort();
  EXPECT_EQ(effort.propulsive_linear, components::Axes{});
  EXPECT_EQ(effort.propulsive_rotational, components::Axes{});
  if (tested.count_query != 0) {
    auto count = tested.count_query == msg::QueryPathSegmentCount::code
                     ? session->request(tested.address, msg::QueryPathSegmentCount{},
                                        {msg::ReportPathSegmentCount::code}, 1s)
                     : session->request(tested.address, msg::QueryWaypointCount{}, {msg::ReportWaypointCount::code}, 1s);
    ASSERT_TRUE(count) << count.error().message();
    ASSERT_EQ(count->payload.size(), 2u);
    EXPECT_EQ(count->payload[0] | (count->payload[1] << 8), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Drivers, MobilityConformance,
    ::testing::Values(
        Driver{kGlobalVectorDriver, {"mobility.global_vector."}, 0},
        Driver{kLocalVectorDriver, {"mobility.local_vector."}, 0},
        Driver{kGlobalWaypointDriver, {"mobility.global_waypoint.", "mobility.travel_speed."},
               msg::QueryWaypointCount::code},
        Driver{kLocalWaypointDriver, {"mobility.local_waypoint.", "mobility.travel_speed."},
               msg::QueryWaypointCount::code},
        Driver{kGlobalPathSegmentDriver, {"mobility.global_path_segment.", "mobility.travel_speed."},
               msg::QueryPathSegmentCount::code},
        Driver{kLocalPathSegmentDriver, {"mobility.local_path_segment.", "mobility.travel_speed."},
               msg::QueryPathSegmentCount::code}),
    [](const ::testing::TestParamInfo<Driver>& p) { return "component_" + std::to_string(p.param.address.component); });

// One driver broken one way, the case that must catch it, and what its
// failure must say.
struct Broken {
  const char* name;
  Address address;
  std::string_view case_id;
  std::string_view says;
};

void PrintTo(const Broken& b, std::ostream* out) { *out << b.name; }

class BrokenMobilityFails : public ::testing::TestWithParam<Broken> {};

TEST_P(BrokenMobilityFails, TheCaseThatLooksForTheFlawFailsSayingWhy) {
  const Broken& b = GetParam();
  VirtualNetwork net;
  test::BrokenMobilityNode broken(net.time, net.network);
  auto session = net.open_session();
  ASSERT_TRUE(session) << session.error().message();
  RunOptions options;
  options.only = std::string(b.case_id);
  const auto results = net.run_on(**session, b.address, options);
  ASSERT_EQ(results.size(), 1u) << describe(results);
  EXPECT_EQ(results[0].outcome.verdict, Verdict::fail) << describe(results);
  EXPECT_NE(results[0].outcome.detail.find(b.says), std::string::npos) << results[0].outcome.detail;
  // Whatever it did, it is left with nobody in control.
  auto* component = broken.node().find(b.address);
  ASSERT_NE(component, nullptr);
  EXPECT_TRUE((*session)->run_until([&] { return !component->control().controller().has_value(); }, 3s));
}

INSTANTIATE_TEST_SUITE_P(
    Flaws, BrokenMobilityFails,
    ::testing::Values(
        Broken{"WaypointsObeyAnyone", test::kWaypointsObeyAnyone, "mobility.local_waypoint.non_controller_ignored",
               "after a new waypoint 0 from a non-controller (controller 0.0.0.0), waypoint 0 reported as "},
        Broken{"WaypointsDropYaw", test::kWaypointsDropYaw, "mobility.local_waypoint.count_and_echo",
               "waypoint 0 reported as "},
        Broken{"WaypointsAppendPastEnd", test::kWaypointsAppendPastEnd, "mobility.local_waypoint.numbering",
               "waypoint 4 sent with 3 loaded: counted 4 (a number past the end must be refused)"},
        Broken{"WaypointsKeepOldList", test::kWaypointsKeepOldList, "mobility.local_waypoint.numbering",
               "a new waypoint 0 with 3 loaded: counted 3, not 1 (element 0 starts a new list)"},
        Broken{"VectorObeysAnyone", test::kVectorObeysAnyone, "mobility.local_vector.non_controller_ignored",
               "Set Local Vector from a non-controller (controller 0.0.0.0) executed: reported 0.100 m/s heading "
               "1.000 rad; stopped again with speed 0 and Standby"},
        Broken{"VectorForgetsSpeed", test::kVectorForgetsSpeed, "mobility.local_vector.echo",
               "Set Local Vector 0.100 m/s heading 0.500 rad reported as 0.000 m/s heading 0.500 rad"}),
    [](const ::testing::TestParamInfo<Broken>& p) { return std::string(p.param.name); });

// Both start rules of a route driver are accepted (issue 43): our drivers
// (Standby -> load -> Resume, and load and go in Ready) pass above; a driver
// with only the RA implementations' rule (a list loaded in Ready drives once
// a travel speed above zero is set, OpenJAUS's) passes every waypoint and
// travel speed case too, and the cases never make it start: they load in
// Standby and never Resume.
TEST(MobilityCases, ADriverThatStartsALoadedListInReadyPassesAndIsNeverStartedByThem) {
  VirtualNetwork net;
  test::ReadyStartNode ra(net.time, net.network);
  auto session = net.open_session();
  ASSERT_TRUE(session) << session.error().message();
  RunOptions options;
  options.only = "mobility.";
  const auto results = net.run_on(**session, test::kReadyStartWaypointDriver, options);
  std::size_t passed = 0;
  for (const auto& r : results) {
    const std::string_view id = r.test_case->id;
    if (id.starts_with("mobility.local_waypoint.") || id.starts_with("mobility.travel_speed.")) {
      EXPECT_EQ(r.outcome.verdict, Verdict::pass) << id << ": " << r.outcome.detail;
      ++passed;
    } else {
      EXPECT_EQ(r.outcome.verdict, Verdict::skip) << id << ": " << r.outcome.detail;
    }
  }
  EXPECT_EQ(passed, 4u) << describe(results);
  EXPECT_EQ(ra.driver().routes_started(), 0);
  EXPECT_TRUE((*session)->run_until([&] { return !ra.driver().control().controller().has_value(); }, 3s));

  // And it is such a driver: its controller's list and speed in Ready start it.
  auto granted = (*session)->request(test::kReadyStartWaypointDriver, msg::RequestComponentControl{{5}},
                                     {msg::ConfirmComponentControl::code}, 1s);
  ASSERT_TRUE(granted) << granted.error().message();
  ASSERT_EQ(ra.driver().state(), msg::PrimaryStatus::ready);
  msg::SetLocalWaypoint waypoint;
  waypoint.waypoint_number = 0;
  waypoint.x_m = 3;
  (*session)->send(test::kReadyStartWaypointDriver, waypoint);
  (*session)->send(test::kReadyStartWaypointDriver, msg::SetTravelSpeed{{0.5}});
  EXPECT_TRUE((*session)->run_until([&] { return ra.driver().routes_started() == 1; }, 1s));
}

// Each mobility case says why it does not apply to a component of another
// kind (the primitive driver), and each driver kind runs only its own.
TEST(MobilityCases, SayWhyTheyDoNotApplyToOtherComponents) {
  VirtualNetwork net;
  MobilityNode node(net.time, net.network);
  auto session = net.open_session();
  ASSERT_TRUE(session) << session.error().message();
  auto primitive = learn_component(**session, kPrimitiveDriver, nullptr, 1s);
  ASSERT_TRUE(primitive) << primitive.error().message();
  for (const auto& c : mobility_driver_cases()) {
    ASSERT_TRUE(c.not_applicable) << c.id;
    const std::string why = c.not_applicable(*primitive);
    EXPECT_TRUE(std::string_view(why).starts_with("it does not accept ")) << c.id << ": " << why;
  }
  auto local_waypoints = learn_component(**session, kLocalWaypointDriver, nullptr, 1s);
  ASSERT_TRUE(local_waypoints) << local_waypoints.error().message();
  for (const auto& c : mobility_driver_cases()) {
    const bool applies = c.not_applicable(*local_waypoints).empty();
    const std::string_view id = c.id;
    EXPECT_EQ(applies, id.starts_with("mobility.local_waypoint.") || id.starts_with("mobility.travel_speed.")) << id;
  }
}

}  // namespace
}  // namespace jaus::conform
