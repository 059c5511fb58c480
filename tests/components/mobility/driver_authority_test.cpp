// Issue 42: an operator always wins over the drivers above the primitive
// driver. Every driver kind (34, 44-48), on a whole vehicle node under
// virtual time (drive_node.hpp), with its authority's ceiling max_authority:
// its controller's Set Component Authority above the ceiling is refused (the
// authority it reports stays), it takes the primitive driver with at most
// the ceiling, and an operator asking the primitive driver at ceiling + 1
// takes it from the driver at once: the driver halts and the vehicle stops.
#include <functional>
#include <stdexcept>

#include "drive_node.hpp"
#include "jaus/components/local_frame.hpp"
#include "jaus/host/component_options.hpp"

namespace jaus::test {
namespace {

struct DriverCase {
  std::string kind;
  Address address;
  // Sent by the driver's controller to make it drive (far enough that it is still driving when taken over).
  std::function<void(DriveNode&, const Address&)> start;
};

// Standby, the travel speed, `load`, Resume: the RA's way to start a route.
void start_route_as_controller(DriveNode& node, const Address& driver, const std::function<void()>& load) {
  node.send(driver, msg::Standby{});
  ASSERT_TRUE(node.run_until([&] { return node.state_of(driver) == rt::PrimaryStatus::standby; }, 1s));
  node.send(driver, msg::SetTravelSpeed{{1.0}});
  load();
  node.run_for(20ms);
  node.send(driver, msg::Resume{});
  ASSERT_TRUE(node.run_until([&] { return node.state_of(driver) == rt::PrimaryStatus::ready; }, 1s));
}

// A point `north_m` ahead of the vehicle (which starts heading north), on the globe.
components::GeoPosition ahead_on_the_globe(DriveNode& node, double north_m) {
  const auto here = node.pose();
  return components::LocalFrame(*here.position).to_geo({north_m, 0, 0});
}

const std::vector<DriverCase>& driver_cases() {
  static const std::vector<DriverCase> cases = {
      {"global_vector_driver", {1, 1, 34, 1},
       [](DriveNode& node, const Address& driver) {
         msg::SetGlobalVector m;
         m.speed_mps = 0.8;
         m.heading_rad = node.pose().attitude->yaw;
         node.send(driver, m);
       }},
      {"local_vector_driver", {1, 1, 44, 1},
       [](DriveNode& node, const Address& driver) {
         msg::SetLocalVector m;
         m.speed_mps = 0.8;
         m.heading_rad = 0;
         node.send(driver, m);
       }},
      {"global_waypoint_driver", {1, 1, 45, 1},
       [](DriveNode& node, const Address& driver) {
         start_route_as_controller(node, driver, [&] {
           const auto far = ahead_on_the_globe(node, 40);
           msg::SetGlobalWaypoint w;
           w.waypoint_number = 0;
           w.latitude_deg = far.latitude_deg;
           w.longitude_deg = far.longitude_deg;
           node.send(driver, w);
         });
       }},
      {"local_waypoint_driver", {1, 1, 46, 1},
       [](DriveNode& node, const Address& driver) {
         start_route_as_controller(node, driver, [&] {
           const auto here = *node.pose().local_position;
           msg::SetLocalWaypoint w;
           w.waypoint_number = 0;
           w.x_m = here.x_m + 40;
           w.y_m = here.y_m;
           node.send(driver, w);
         });
       }},
      {"global_path_segment_driver", {1, 1, 47, 1},
       [](DriveNode& node, const Address& driver) {
         start_route_as_controller(node, driver, [&] {
           const auto near = ahead_on_the_globe(node, 2);
           const auto far = ahead_on_the_globe(node, 40);
           msg::SetGlobalPathSegment m;
           m.path_segment_number = 0;
           m.p1_latitude_deg = near.latitude_deg;
           m.p1_longitude_deg = near.longitude_deg;
           m.p2_latitude_deg = far.latitude_deg;
           m.p2_longitude_deg = far.longitude_deg;
           m.weighting_factor = 0;
           node.send(driver, m);
         });
       }},
      {"local_path_segment_driver", {1, 1, 48, 1},
       [](DriveNode& node, const Address& driver) {
         start_route_as_controller(node, driver, [&] {
           const auto here = *node.pose().local_position;
           msg::SetLocalPathSegment m;
           m.path_segment_number = 0;
           m.p1_x_m = here.x_m + 2;
           m.p1_y_m = here.y_m;
           m.p2_x_m = here.x_m + 40;
           m.p2_y_m = here.y_m;
           m.weighting_factor = 0;
           node.send(driver, m);
         });
       }},
  };
  return cases;
}

std::string driver_case_name(const ::testing::TestParamInfo<DriverCase>& info) { return info.param.kind; }

DriveNodeOptions node_with_driver(const std::string& kind, std::uint8_t authority = 1,
                            std::map<std::string, std::string> options = {}) {
  return DriveNodeOptions{.drivers = {kind}, .driver_options = std::move(options), .driver_authority = authority};
}

class DriverAuthorityTest : public ::testing::TestWithParam<DriverCase> {
 protected:
  DriverAuthorityTest() : node_(node_with_driver(GetParam().kind)), driver_(GetParam().address) {}

  components::MobilityDriver& driver() { return node_.component<components::MobilityDriver>(driver_); }
  std::optional<std::uint8_t> reported_authority() {
    const auto r = node_.ask<msg::ReportComponentAuthority>(driver_, msg::QueryComponentAuthority{});
    if (!r) return std::nullopt;
    return r->authority;
  }
  // An operator's Request Component Control of the primitive driver at `authority`: confirmed?
  bool operator_takes_primitive_driver(std::uint8_t authority) {
    const auto confirm =
        node_.ask<msg::ConfirmComponentControl>(kPrimitiveDriver, msg::RequestComponentControl{{authority}});
    return confirm && confirm->response_code == msg::control_response::kAccepted;
  }
  bool moving() { return node_.speed_mps() > 0.05; }
  bool stopped() { return node_.speed_mps() < 0.01; }

  DriveNode node_;
  Address driver_;
};

// The README's "Drive a route" with Set Component Authority 255 before Resume.
TEST_P(DriverAuthorityTest, SetAuthorityAboveTheCeilingIsRefusedAndAnOperatorAboveItTakesThePrimitiveDriverAtOnce) {
  ASSERT_TRUE(node_.wait_ready());
  ASSERT_TRUE(node_.take_control(driver_));  // the operator (authority 5) controls the driver
  node_.send(driver_, msg::SetComponentAuthority{{255}});
  EXPECT_EQ(reported_authority(), 1);  // not applied: Query Component Authority says what is in effect
  EXPECT_EQ(driver().control().own_authority(), 1);
  EXPECT_EQ(driver().counters().refused_authority_changes, 1u);

  GetParam().start(node_, driver_);
  ASSERT_TRUE(node_.run_until([&] { return driver().commanding() && moving(); }, 10s)) << driver().last_halt();
  // It holds the primitive driver with at most its ceiling.
  const auto& controller = node_.primitive_driver().control().controller();
  ASSERT_TRUE(controller);
  EXPECT_EQ(controller->address, driver_);
  EXPECT_EQ(controller->authority, 1);

  // An operator at the ceiling does not take it (equal authority never does in the RA)...
  EXPECT_FALSE(operator_takes_primitive_driver(1));
  EXPECT_TRUE(driver().commanding());
  // ...one above it does, at once: the driver is rejected, halts, and the vehicle stops.
  ASSERT_TRUE(operator_takes_primitive_driver(2));
  EXPECT_EQ(node_.primitive_driver().control().controller()->address, kOperator);
  EXPECT_TRUE(node_.run_until([&] { return !driver().driving(); }, 100ms));
  EXPECT_EQ(driver().mobility_counters().control_losses, 1u);
  EXPECT_NE(driver().last_halt().find("Reject"), std::string::npos) << driver().last_halt();
  EXPECT_TRUE(node_.run_until([&] { return stopped(); }, 5s));
  // Nothing restarts it: the operator holds the primitive driver, the driver sends nothing more.
  const auto efforts = driver().mobility_counters().efforts_sent;
  node_.run_for(2s);
  EXPECT_EQ(driver().mobility_counters().efforts_sent, efforts);
  EXPECT_TRUE(stopped());
  EXPECT_EQ(node_.primitive_driver().control().controller()->address, kOperator);
}

// Lowering its authority (below the ceiling) is its controller's to do; it
// then asks the primitive driver with the lower one.
TEST_P(DriverAuthorityTest, ItsControllerMayLowerItsAuthorityAndItAsksWithTheLowerOne) {
  ASSERT_TRUE(node_.wait_ready());
  ASSERT_TRUE(node_.take_control(driver_));
  node_.send(driver_, msg::SetComponentAuthority{{0}});
  EXPECT_EQ(reported_authority(), 0);
  EXPECT_EQ(driver().counters().refused_authority_changes, 0u);
  GetParam().start(node_, driver_);
  ASSERT_TRUE(node_.run_until([&] { return driver().commanding(); }, 10s)) << driver().last_halt();
  EXPECT_EQ(node_.primitive_driver().control().controller()->authority, 0);
  ASSERT_TRUE(operator_takes_primitive_driver(1));
  EXPECT_TRUE(node_.run_until([&] { return !driver().driving(); }, 100ms));
}

INSTANTIATE_TEST_SUITE_P(Kinds, DriverAuthorityTest, ::testing::ValuesIn(driver_cases()), driver_case_name);

// A configured ceiling: authority up to it, an operator above it wins.
TEST(DriverAuthorityCeiling, AConfiguredCeilingIsTheLimitAndAnOperatorAboveItWins) {
  const Address driver{1, 1, 46, 1};
  DriveNode node(node_with_driver("local_waypoint_driver", 3, {{"max_authority", "3"}}));
  ASSERT_TRUE(node.wait_ready());
  auto& d = node.component<components::MobilityDriver>(driver);
  ASSERT_TRUE(node.take_control(driver));
  node.send(driver, msg::SetComponentAuthority{{4}});
  node.run_for(20ms);
  EXPECT_EQ(d.control().own_authority(), 3);
  EXPECT_EQ(d.counters().refused_authority_changes, 1u);
  driver_cases()[3].start(node, driver);
  ASSERT_TRUE(node.run_until([&] { return d.commanding(); }, 10s)) << d.last_halt();
  EXPECT_EQ(node.primitive_driver().control().controller()->authority, 3);
  const auto confirm = node.ask<msg::ConfirmComponentControl>(kPrimitiveDriver, msg::RequestComponentControl{{4}});
  ASSERT_TRUE(confirm);
  EXPECT_EQ(confirm->response_code, msg::control_response::kAccepted);
  EXPECT_TRUE(node.run_until([&] { return !d.driving(); }, 100ms));
}

// A driver configured above its ceiling is not made: the node does not start.
TEST(DriverAuthorityCeiling, AnAuthorityAboveTheCeilingIsAConfigurationError) {
  try {
    DriveNode node(node_with_driver("global_vector_driver", 5));
    FAIL() << "a driver with authority 5 and max_authority 1 was made";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("global_vector_driver: authority 5 is above its max_authority 1"),
              std::string::npos)
        << e.what();
  }
  // Raised with the ceiling: made.
  DriveNode node(node_with_driver("global_vector_driver", 5, {{"max_authority", "5"}}));
  EXPECT_TRUE(node.wait_ready());
}

// The option, for every kind: a whole number 0..254 (an operator must be able to ask for more).
TEST(DriverAuthorityCeiling, TheOptionIsAWholeNumberUpTo254ForEveryKind) {
  for (const auto& c : driver_cases()) {
    SCOPED_TRACE(c.kind);
    const host::ComponentKind* kind = host::find_component_kind(c.kind);
    ASSERT_TRUE(kind);
    for (const char* good : {"0", "1", "254"}) {
      host::ComponentSpec spec{c.kind, kind->default_id, 1, 0, "", {{"max_authority", good}}, 0, {}};
      EXPECT_TRUE(host::check_component_options(spec)) << good;
    }
    for (const char* bad : {"255", "-1", "1.5", "one", ""}) {
      host::ComponentSpec spec{c.kind, kind->default_id, 1, 0, "", {{"max_authority", bad}}, 0, {}};
      const auto checked = host::check_component_options(spec);
      ASSERT_FALSE(checked) << bad;
      EXPECT_EQ(checked.error().what, c.kind + " option 'max_authority' must be a whole number 0..254 (an operator "
                                               "must be able to ask for more), got '" + std::string(bad) + "'");
    }
  }
}

}  // namespace
}  // namespace jaus::test
