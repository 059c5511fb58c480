// The global and the local vector driver (components 34 and 44) on a whole
// vehicle node under virtual time (drive_node.hpp), on the simulated vehicle
// and the in-process Clearpath platform, differential and Ackermann: the
// commanded heading and speed are reached and held, the command is echoed,
// absent fields keep their value, only the controller commands, speed 0 with
// the heading reached gives the primitive driver back, and every stop path
// leaves the vehicle stopped with nothing restarting it.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <tuple>

#include "drive_node.hpp"
#include "jaus/components/global_vector_driver.hpp"
#include "jaus/components/global_vector_driver_kind.hpp"
#include "jaus/components/local_vector_driver.hpp"
#include "jaus/components/local_vector_driver_kind.hpp"

namespace jaus::test {
namespace {

using components::Steering;
using components::mobility_status::kLostControl;
using std::numbers::pi;

const Address kGlobalVectorDriver{1, 1, 34, 1};
const Address kLocalVectorDriver{1, 1, 44, 1};

// What the brief promises: heading within 0.1 rad, speed within 0.1 m/s.
constexpr double kHeadingTolerance = 0.1;
constexpr double kSpeedTolerance = 0.1;
constexpr double kMaxSpeed = 1.0;  // the vehicle's (VehicleSettings default)
// Set Global Vector carries the speed in steps of 10000/65535 m/s (Part 3's
// 0..10000 m/s in 16 bits: 0.15 m/s): the tests command whole steps, so what
// is sent is what the driver follows. The heading's step is 2 pi / 65535.
constexpr double kSpeedStep = 10'000.0 / 65'535;
constexpr double kSlow = 3 * kSpeedStep;    // 0.46 m/s
constexpr double kCruise = 4 * kSpeedStep;  // 0.61 m/s
constexpr double kFast = 5 * kSpeedStep;    // 0.76 m/s
constexpr double kExact = 1e-6;
constexpr double kHeadingResolution = 2 * pi / 65'535;

msg::SetGlobalVector global_vector(std::optional<double> speed_mps, std::optional<double> heading_rad) {
  msg::SetGlobalVector m;
  m.speed_mps = speed_mps;
  m.heading_rad = heading_rad;
  return m;
}

double angle_off(double a, double b) { return std::abs(components::wrap_angle(a - b)); }

// Hears every message to the operator while alive (a failed assertion leaves no dangling listener).
class Listening {
 public:
  Listening(ocu::OcuSession& op, ocu::OcuSession::Listener listener) : op_(op), id_(op.listen(std::move(listener))) {}
  ~Listening() { op_.unlisten(id_); }
  Listening(const Listening&) = delete;
  Listening& operator=(const Listening&) = delete;

 private:
  ocu::OcuSession& op_;
  ocu::OcuSession::ListenerId id_;
};

using Param = std::tuple<PlatformUnderTest, Steering>;

std::string param_name(const ::testing::TestParamInfo<Param>& info) {
  return platform_name(std::get<0>(info.param)) +
         (std::get<1>(info.param) == Steering::ackermann ? "_ackermann" : "_differential");
}

// The fixture's node, with the Clearpath platform's specifications saying
// what an Ackermann one steers with: the bridge knows no wheel base of its
// own (a real platform's configuration gives it under `specifications`), and
// without it a driver has no limits to steer within.
host::HostConfig vehicle_config(const DriveNodeOptions& options) {
  host::HostConfig config = drive_node_config(options);
  if (options.platform == PlatformUnderTest::clearpath_sim && options.steering == Steering::ackermann) {
    auto& specifications = config.platform.sections.find<host::ClearpathSettings>()->vehicle.specifications;
    specifications.wheel_base_m = config.vehicle.wheel_base_m;
    specifications.turning_radius_m = config.vehicle.wheel_base_m / std::tan(config.vehicle.max_steering_rad);
  }
  return config;
}

DriveNodeOptions vehicle_options(const Param& p, const std::string& kind) {
  DriveNodeOptions options;
  options.platform = std::get<0>(p);
  options.steering = std::get<1>(p);
  options.drivers = {kind};
  return options;
}

// A vehicle node with one vector driver kind, Ready, the operator its controller.
class VectorDriverNode {
 public:
  VectorDriverNode(const Param& p, const std::string& kind, const Address& driver)
      : node_(vehicle_options(p, kind), vehicle_config(vehicle_options(p, kind))), address_(driver) {}

  void ready_and_controlled() {
    ASSERT_TRUE(node_.wait_ready()) << states();
    ASSERT_TRUE(node_.take_control(address_));
  }
  std::string states() {
    std::string text;
    for (const rt::Component* c : node_.host().node().local_components())
      text += c->name() + ": " + std::string(rt::to_string(c->state())) + "; ";
    return text;
  }
  components::VectorDriver& driver() { return node_.component<components::VectorDriver>(address_); }
  double heading() { return node_.pose().attitude->yaw; }
  double speed() { return node_.pose().velocity_mps->x; }
  bool moving() { return node_.speed_mps() > 0.05; }
  bool stopped() { return node_.speed_mps() < 0.01; }
  // Heading and speed both within the promised tolerances.
  bool on(double heading_rad, double speed_mps) {
    return angle_off(heading(), heading_rad) < kHeadingTolerance && std::abs(speed() - speed_mps) < kSpeedTolerance;
  }
  // Reached within `limit`, and still held `hold` later.
  void reaches_and_holds(double heading_rad, double speed_mps, rt::Duration limit = 15s, rt::Duration hold = 2s) {
    ASSERT_TRUE(node_.run_until([&] { return on(heading_rad, speed_mps); }, limit))
        << "heading " << heading() << " speed " << speed();
    const auto held_until = node_.time().now() + hold;
    while (node_.time().now() < held_until) {
      node_.run_for(100ms);
      ASSERT_TRUE(on(heading_rad, speed_mps)) << "lost it: heading " << heading() << " speed " << speed();
    }
  }
  double commanded_linear() {
    return node_.primitive_driver().wrench_effort_report().propulsive_linear_effort_x_percent.value_or(0);
  }

  DriveNode node_;
  Address address_;
};

class GlobalVectorDriverTest : public ::testing::TestWithParam<Param> {
 protected:
  GlobalVectorDriverTest() : v_(GetParam(), "global_vector_driver", kGlobalVectorDriver) {}
  void SetUp() override { v_.ready_and_controlled(); }
  std::optional<msg::ReportGlobalVector> report(std::uint8_t presence = components::global_vector_field::kAll) {
    return v_.node_.ask<msg::ReportGlobalVector>(kGlobalVectorDriver, msg::QueryGlobalVector{{presence}});
  }
  bool ackermann() const { return std::get<1>(GetParam()) == Steering::ackermann; }
  // Driving east at kSlow, held.
  void driving_east() {
    v_.node_.send(kGlobalVectorDriver, global_vector(kSlow, pi / 2));
    v_.reaches_and_holds(pi / 2, kSlow, 15s, 500ms);
  }
  void nothing_restarts() {
    const auto efforts = v_.driver().mobility_counters().efforts_sent;
    v_.node_.run_for(3s);
    EXPECT_EQ(v_.driver().mobility_counters().efforts_sent, efforts);
    EXPECT_FALSE(v_.driver().driving());
    EXPECT_TRUE(v_.stopped());
    const auto r = report();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->speed_mps, 0.0);
  }

  VectorDriverNode v_;
};

TEST_P(GlobalVectorDriverTest, ReachesAndHoldsAHeading90DegreesOffAndTheSpeed) {
  ASSERT_NEAR(v_.heading(), 0, 0.01);  // starts facing north
  v_.node_.send(kGlobalVectorDriver, global_vector(kCruise, pi / 2));
  // The turn: within 5 s, never more than 0.05 rad past east.
  double overshoot = 0;
  const auto past_east = [&] {
    overshoot = std::max(overshoot, components::wrap_angle(v_.heading() - pi / 2));
    return false;
  };
  ASSERT_TRUE(v_.node_.run_until([&] { return past_east() || v_.on(pi / 2, kCruise); }, 5s));
  v_.node_.run_until(past_east, 3s);  // and after
  EXPECT_LT(overshoot, 0.05);
  v_.reaches_and_holds(pi / 2, kCruise);
  // Through the primitive driver, with the driver's own authority.
  const auto& controller = v_.node_.primitive_driver().control().controller();
  ASSERT_TRUE(controller);
  EXPECT_EQ(controller->address, kGlobalVectorDriver);
  EXPECT_EQ(controller->authority, 1);
  // A left turn back to north-west: the short way, the other side.
  v_.node_.send(kGlobalVectorDriver, global_vector(kCruise, -pi / 4));
  v_.reaches_and_holds(-pi / 4, kCruise);
  EXPECT_EQ(v_.driver().commands(), 2u);
  EXPECT_EQ(v_.driver().mobility_counters().control_losses, 0u);
}

TEST_P(GlobalVectorDriverTest, ASpeedBeyondTheVehiclesIsDrivenAtItsMaximum) {
  v_.node_.send(kGlobalVectorDriver, global_vector(3.0, -pi / 2));
  v_.reaches_and_holds(-pi / 2, kMaxSpeed);
  // The command stays what was asked.
  const auto r = report();
  ASSERT_TRUE(r && r->speed_mps);
  EXPECT_NEAR(*r->speed_mps, 3.0, kSpeedStep);
}

TEST_P(GlobalVectorDriverTest, ReportGlobalVectorEchoesTheCommandWithinThePresenceAsked) {
  // Before any Set: speed 0, nothing else commanded.
  auto r = report();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->speed_mps, 0.0);
  EXPECT_FALSE(r->heading_rad);
  EXPECT_FALSE(r->altitude_m);

  msg::SetGlobalVector m = global_vector(0.4, 1.0);
  m.altitude_m = 120;
  m.roll_rad = 0.1;
  m.pitch_rad = -0.2;
  v_.node_.send(kGlobalVectorDriver, m);
  v_.node_.run_for(200ms);
  r = report();
  ASSERT_TRUE(r && r->speed_mps && r->heading_rad && r->altitude_m && r->roll_rad && r->pitch_rad);
  // 0.4 m/s lies between two steps: the driver holds and echoes the step it received.
  EXPECT_NEAR(*r->speed_mps, kSlow, kExact);
  EXPECT_NEAR(*r->heading_rad, 1.0, kHeadingResolution);
  EXPECT_NEAR(*r->altitude_m, 120, 0.01);  // stored and echoed, not followed
  EXPECT_NEAR(*r->roll_rad, 0.1, kHeadingResolution);
  EXPECT_NEAR(*r->pitch_rad, -0.2, kHeadingResolution);
  // The echo is the body as received: what the driver holds re-encodes to it.
  const auto& driver = v_.node_.component<components::GlobalVectorDriver>(kGlobalVectorDriver);
  EXPECT_EQ(static_cast<const msg::GlobalVectorBody&>(*r), static_cast<const msg::GlobalVectorBody&>(driver.report()));
  // Only the fields asked for.
  r = report(components::global_vector_field::kHeading);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->heading_rad);
  EXPECT_FALSE(r->speed_mps);
  EXPECT_FALSE(r->altitude_m);
}

TEST_P(GlobalVectorDriverTest, ReportGlobalVectorOnAServiceConnectionFollowsTheCommand) {
  std::vector<msg::ReportGlobalVector> reports;
  const Listening listening(v_.node_.op(), [&](const ocu::Received& r) {
    msg::ReportGlobalVector report{};
    if (r.header.command_code == msg::ReportGlobalVector::code && r.header.source == kGlobalVectorDriver &&
        wire::decode_payload_into(r.payload, report, wire::Dialect::ra, kHeaderSize))
      reports.push_back(report);
  });
  const auto confirm = v_.node_.ask<msg::ConfirmServiceConnection>(
      kGlobalVectorDriver, msg::CreateServiceConnection{{msg::ReportGlobalVector::code, 10,
                                                         components::global_vector_field::kSpeed |
                                                             components::global_vector_field::kHeading}});
  ASSERT_TRUE(confirm);
  ASSERT_EQ(confirm->response_code, 0) << "created";
  v_.node_.run_for(500ms);
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports.back().speed_mps, 0.0);
  msg::SetGlobalVector m = global_vector(kSlow, 1.0);
  m.altitude_m = 10;
  v_.node_.send(kGlobalVectorDriver, m);
  v_.node_.run_for(500ms);
  const auto& last = reports.back();
  ASSERT_TRUE(last.speed_mps && last.heading_rad);
  EXPECT_NEAR(*last.speed_mps, kSlow, kExact);
  EXPECT_NEAR(*last.heading_rad, 1.0, kHeadingResolution);
  EXPECT_FALSE(last.altitude_m);  // not asked for
}

TEST_P(GlobalVectorDriverTest, ASetWithoutAHeadingHoldsTheVehiclesAndLaterOnesKeepTheCommandedOne) {
  // The first Set has no heading: the vehicle's (north) is kept.
  v_.node_.send(kGlobalVectorDriver, global_vector(kSlow, std::nullopt));
  v_.reaches_and_holds(0, kSlow, 10s, 1s);
  auto r = report();
  ASSERT_TRUE(r && r->heading_rad);
  EXPECT_NEAR(*r->heading_rad, 0, 0.02);
  // A heading alone: the speed is kept.
  v_.node_.send(kGlobalVectorDriver, global_vector(std::nullopt, pi / 2));
  v_.reaches_and_holds(pi / 2, kSlow);
  // A speed alone: the heading is kept.
  v_.node_.send(kGlobalVectorDriver, global_vector(kFast, std::nullopt));
  v_.reaches_and_holds(pi / 2, kFast);
  r = report();
  ASSERT_TRUE(r && r->heading_rad && r->speed_mps);
  EXPECT_NEAR(*r->heading_rad, pi / 2, kHeadingResolution);
  EXPECT_NEAR(*r->speed_mps, kFast, kExact);
}

TEST_P(GlobalVectorDriverTest, ASetFromAnyoneButTheControllerIsRefused) {
  // The operator gives control back; its Set is then not the controller's.
  v_.node_.send(kGlobalVectorDriver, msg::ReleaseComponentControl{});
  v_.node_.run_for(200ms);
  ASSERT_FALSE(v_.node_.find(kGlobalVectorDriver)->control().controller());
  const auto refused = v_.node_.find(kGlobalVectorDriver)->counters().refused_not_controller;
  v_.node_.send(kGlobalVectorDriver, global_vector(kSlow, pi / 2));
  v_.node_.run_for(3s);
  EXPECT_EQ(v_.node_.find(kGlobalVectorDriver)->counters().refused_not_controller, refused + 1);
  EXPECT_EQ(v_.driver().commands(), 0u);
  EXPECT_FALSE(v_.driver().driving());
  EXPECT_TRUE(v_.stopped());
  EXPECT_NEAR(v_.heading(), 0, 0.01);
  EXPECT_FALSE(v_.node_.primitive_driver().control().controller());
}

TEST_P(GlobalVectorDriverTest, SpeedZeroWithTheHeadingReachedGivesThePrimitiveDriverBack) {
  driving_east();
  // Speed 0 and south: a differential vehicle turns in place first; an
  // Ackermann one cannot turn at rest and stops at once.
  v_.node_.send(kGlobalVectorDriver, global_vector(0, pi));
  ASSERT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, ackermann() ? 1s : 10s));
  EXPECT_EQ(v_.driver().mobility_counters().arrivals, 1u);
  EXPECT_EQ(v_.commanded_linear(), 0);
  EXPECT_FALSE(v_.node_.primitive_driver().control().controller());
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  if (!ackermann()) {
    EXPECT_EQ(v_.driver().last_halt(), "speed 0, heading reached");
    EXPECT_LT(angle_off(v_.heading(), pi), kHeadingTolerance);
  } else {
    EXPECT_NE(v_.driver().last_halt().find("Ackermann"), std::string::npos) << v_.driver().last_halt();
  }
  // An operator takes the primitive driver freely now, and nothing fights it.
  ASSERT_TRUE(v_.node_.take_control(kPrimitiveDriver));
  EXPECT_EQ(v_.driver().mobility_counters().control_losses, 0u);
  // The heading stays commanded; the speed is 0.
  const auto r = report();
  ASSERT_TRUE(r && r->heading_rad);
  EXPECT_EQ(r->speed_mps, 0.0);
  EXPECT_NEAR(std::abs(*r->heading_rad), pi, kHeadingResolution);
}

TEST_P(GlobalVectorDriverTest, AnOperatorTakingThePrimitiveDriverStopsItAndNothingRestartsIt) {
  driving_east();
  ASSERT_TRUE(v_.node_.take_control(kPrimitiveDriver));  // authority 5 > 1
  EXPECT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, 1s));
  EXPECT_EQ(v_.driver().mobility_counters().control_losses, 1u);
  const auto status = v_.node_.ask<msg::ReportComponentStatus>(kGlobalVectorDriver, msg::QueryComponentStatus{});
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->secondary_status & kLostControl);
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  // The operator lets go: still nothing moves until a new Set.
  v_.node_.send(kPrimitiveDriver, msg::ReleaseComponentControl{});
  nothing_restarts();
}

TEST_P(GlobalVectorDriverTest, SetEmergencyOnThePrimitiveDriverStopsItAndClearEmergencyDoesNotRestart) {
  driving_east();
  v_.node_.send(kPrimitiveDriver, msg::SetEmergency{{1}});
  ASSERT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, 1s));
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  v_.node_.send(kPrimitiveDriver, msg::ClearEmergency{{1}});
  ASSERT_TRUE(v_.node_.run_until(
      [&] {
        return v_.node_.state_of(kPrimitiveDriver) == rt::PrimaryStatus::ready &&
               v_.node_.state_of(kGlobalVectorDriver) == rt::PrimaryStatus::ready;
      },
      1s));
  nothing_restarts();
  EXPECT_FALSE(v_.node_.primitive_driver().control().controller());
}

TEST_P(GlobalVectorDriverTest, StandbyStopsTheVehicleAndResumeDoesNotRestartIt) {
  driving_east();
  v_.node_.send(kGlobalVectorDriver, msg::Standby{});
  ASSERT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, 1s));
  EXPECT_EQ(v_.commanded_linear(), 0);
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  // Standby refuses a Set (Ready only) ...
  const auto refused = v_.node_.find(kGlobalVectorDriver)->counters().refused_wrong_state;
  v_.node_.send(kGlobalVectorDriver, global_vector(kSlow, pi / 2));
  v_.node_.run_for(500ms);
  EXPECT_EQ(v_.node_.find(kGlobalVectorDriver)->counters().refused_wrong_state, refused + 1);
  // ... and Resume only makes it Ready again.
  v_.node_.send(kGlobalVectorDriver, msg::Resume{});
  ASSERT_TRUE(v_.node_.run_until(
      [&] { return v_.node_.state_of(kGlobalVectorDriver) == rt::PrimaryStatus::ready; }, 1s));
  nothing_restarts();
  // A new Set drives again.
  v_.node_.send(kGlobalVectorDriver, global_vector(kSlow, 0));
  v_.reaches_and_holds(0, kSlow, 15s, 500ms);
}

TEST_P(GlobalVectorDriverTest, ResetForgetsTheCommand) {
  msg::SetGlobalVector m = global_vector(kSlow, 1.0);
  m.altitude_m = 50;
  v_.node_.send(kGlobalVectorDriver, m);
  ASSERT_TRUE(v_.node_.run_until([&] { return v_.moving(); }, 3s));
  v_.node_.send(kGlobalVectorDriver, msg::Reset{});
  ASSERT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, 1s));
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  const auto r = report();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->speed_mps, 0.0);
  EXPECT_FALSE(r->heading_rad);
  EXPECT_FALSE(r->altitude_m);
}

INSTANTIATE_TEST_SUITE_P(PlatformsAndDrivetrains, GlobalVectorDriverTest,
                         ::testing::Combine(::testing::Values(PlatformUnderTest::model,
                                                              PlatformUnderTest::clearpath_sim),
                                            ::testing::Values(Steering::differential, Steering::ackermann)),
                         param_name);

class LocalVectorDriverTest : public ::testing::TestWithParam<Param> {
 protected:
  LocalVectorDriverTest() : v_(GetParam(), "local_vector_driver", kLocalVectorDriver) {}
  void SetUp() override { v_.ready_and_controlled(); }
  std::optional<msg::ReportLocalVector> report() {
    return v_.node_.ask<msg::ReportLocalVector>(kLocalVectorDriver, msg::QueryLocalVector{});
  }
  VectorDriverNode v_;
};

TEST_P(LocalVectorDriverTest, ReachesAHeadingFromTheLocalXAxisAndTheSpeedAndEchoesThem) {
  // No command yet: speed 0 and the vehicle's heading.
  auto r = report();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->speed_mps, 0.0);
  EXPECT_NEAR(r->heading_rad, 0, 0.01);
  const auto start = *v_.node_.pose().local_position;
  msg::SetLocalVector m;
  m.speed_mps = 0.6;
  m.heading_rad = pi / 2;  // along the local y axis (east)
  v_.node_.send(kLocalVectorDriver, m);
  v_.reaches_and_holds(pi / 2, 0.6);
  // Moving along +y: 2 s held at 0.6 m/s east.
  const auto before = *v_.node_.pose().local_position;
  v_.node_.run_for(2s);
  const auto after = *v_.node_.pose().local_position;
  EXPECT_NEAR(after.y_m - before.y_m, 1.2, 0.2);
  EXPECT_NEAR(after.x_m - before.x_m, 0, 0.2);
  EXPECT_GT(after.y_m, start.y_m);
  r = report();
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->speed_mps, 0.6, 1e-3);
  EXPECT_NEAR(r->heading_rad, pi / 2, kHeadingResolution);
  // The same report on a service connection.
  std::optional<msg::ReportLocalVector> streamed;
  const Listening listening(v_.node_.op(), [&](const ocu::Received& received) {
    msg::ReportLocalVector report{};
    if (received.header.command_code == msg::ReportLocalVector::code &&
        wire::decode_payload_into(received.payload, report, wire::Dialect::ra, kHeaderSize))
      streamed = report;
  });
  const auto confirm = v_.node_.ask<msg::ConfirmServiceConnection>(
      kLocalVectorDriver, msg::CreateServiceConnection{{msg::ReportLocalVector::code, 5, 0}});
  ASSERT_TRUE(confirm);
  EXPECT_EQ(confirm->response_code, 0) << "created";
  v_.node_.run_for(500ms);
  ASSERT_TRUE(streamed);
  EXPECT_EQ(*streamed, *r);
  // Standby: stopped, and the commanded speed is 0.
  v_.node_.send(kLocalVectorDriver, msg::Standby{});
  ASSERT_TRUE(v_.node_.run_until([&] { return !v_.driver().driving(); }, 1s));
  EXPECT_TRUE(v_.node_.run_until([&] { return v_.stopped(); }, 5s));
  r = report();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->speed_mps, 0.0);
}

INSTANTIATE_TEST_SUITE_P(PlatformsAndDrivetrains, LocalVectorDriverTest,
                         ::testing::Values(Param{PlatformUnderTest::model, Steering::differential},
                                           Param{PlatformUnderTest::clearpath_sim, Steering::ackermann}),
                         param_name);

// ---- the kinds ---------------------------------------------------------------------

TEST(VectorDriverKinds, DescribeThemselvesAndCheckTheirOptions) {
  const auto& global = components::global_vector_driver_kind();
  const auto& local = components::local_vector_driver_kind();
  EXPECT_EQ(global.default_id, 34);
  EXPECT_EQ(local.default_id, 44);
  for (const rt::ComponentKind* kind : {&global, &local}) {
    EXPECT_TRUE(kind->moves_hardware);
    EXPECT_FALSE(kind->one_per_node);
    EXPECT_EQ(kind->needs, std::vector<std::string_view>{components::PoseSource::kInterface});
    EXPECT_NE(std::find(kind->options.begin(), kind->options.end(), "heading_tolerance_rad"), kind->options.end());
    EXPECT_NE(std::find(kind->options.begin(), kind->options.end(), "primitive_driver"), kind->options.end());
  }
  const std::map<std::string, std::string> good{{"heading_tolerance_rad", "0.1"}, {"heading_kp", "2"},
                                                {"speed_ki", "5"}};
  auto o = components::vector_driver_options(rt::KindOptions{"global_vector_driver", good});
  ASSERT_TRUE(o);
  EXPECT_EQ(o->heading_tolerance_rad, 0.1);
  EXPECT_EQ(o->heading_gains.kp, 2);
  EXPECT_EQ(o->speed_gains.ki, 5);
  EXPECT_EQ(o->speed_gains.kp, components::VectorDriverOptions{}.speed_gains.kp);  // default kept
  for (const auto& [key, value] : std::map<std::string, std::string>{
           {"heading_tolerance_rad", "0"}, {"heading_kp", "-1"}, {"speed_kd", "x"}, {"command_rate_hz", "0"}}) {
    const std::map<std::string, std::string> bad{{key, value}};
    const auto checked = global.check(rt::KindOptions{"global_vector_driver", bad});
    ASSERT_FALSE(checked) << key;
    EXPECT_EQ(checked.error().field, key);
  }
}

}  // namespace
}  // namespace jaus::test
