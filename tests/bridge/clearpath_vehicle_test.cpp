// The Clearpath backend of the mobility components (ClearpathVehicle) against
// the simulated Clearpath platform, in process and under virtual time: every
// command crosses the real protocol (frames, ACKs, subscriptions) to the
// platform's model, and the checks read the model's true state.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "jaus/base/virtual_time.hpp"
#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace bridge = jaus::bridge;
namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace comp = jaus::components;
namespace rt = jaus::rt;
using namespace std::chrono_literals;

namespace {

sim::LoopbackConfig loopback_for(sim::Drive drive) {
  sim::LoopbackConfig config;
  config.platform.vehicle.drive = drive;
  return config;
}

class Rig {
 public:
  explicit Rig(bridge::ClearpathVehicleConfig config = {}, sim::Drive drive = sim::Drive::differential)
      : loopback(time, time, loopback_for(drive)), platform(loopback, time), vehicle(platform, config) {
    vehicle.on_fault([this](const std::optional<std::string>& f) { fault = f; });
    loopback.on_written([this](std::span<const std::uint8_t> frame) {
      if (const auto f = cp::decode_frame(frame)) written.push_back(f->header.type);
    });
    time.advance(200ms);  // subscriptions answered, the platform alive
  }

  // What a driver under an OCU's 10 Hz stream does: apply the same effort again and again.
  void drive_for(const comp::WrenchEffort& effort, rt::Duration d) {
    for (auto t = rt::Duration::zero(); t < d; t += 100ms) {
      vehicle.apply_effort(effort);
      time.advance(100ms);
    }
  }
  std::size_t written_of(std::uint16_t type) const { return static_cast<std::size_t>(std::count(written.begin(), written.end(), type)); }
  const sim::VehicleModel& model() const { return loopback.platform().vehicle(); }

  rt::VirtualTime time;
  sim::LoopbackClient loopback;
  bridge::PlatformConnection platform;
  bridge::ClearpathVehicle vehicle;
  std::optional<std::string> fault = std::string("never told");
  std::vector<std::uint16_t> written;
};

comp::WrenchEffort effort(double x, double z, double brake = 0) {
  comp::WrenchEffort e;
  e.propulsive_linear.x = x;
  e.propulsive_rotational.z = z;
  e.resistive_linear.x = brake;
  return e;
}

}  // namespace

TEST(ClearpathGear, PartThreeCodesMapBothWays) {
  EXPECT_EQ(bridge::clearpath_gear(0), -1);    // park
  EXPECT_EQ(bridge::clearpath_gear(1), 1);     // first forward
  EXPECT_EQ(bridge::clearpath_gear(127), 127);
  EXPECT_EQ(bridge::clearpath_gear(128), 0);   // neutral
  EXPECT_EQ(bridge::clearpath_gear(129), -2);  // first reverse
  EXPECT_EQ(bridge::clearpath_gear(255), -128);
  for (int g = 0; g <= 255; ++g) EXPECT_EQ(bridge::jaus_gear(bridge::clearpath_gear(static_cast<std::uint8_t>(g))), g);
}

TEST(ClearpathVehicle, TheFirstDataClearsTheStartupFault) {
  Rig rig;
  EXPECT_TRUE(rig.platform.alive());
  EXPECT_EQ(rig.fault, std::nullopt);
}

TEST(ClearpathVehicle, DifferentialOutputsTurnToTheSideJausAsksFor) {
  Rig rig;
  // X 50 %, Z 40 % (right): the left side gets more, L = 90, R = 10.
  const auto told = rig.vehicle.apply_effort(effort(50, 40));
  rig.time.advance(20ms);
  const auto out = rig.model().differential_output();
  EXPECT_DOUBLE_EQ(out[0], 90);
  EXPECT_DOUBLE_EQ(out[1], 10);
  EXPECT_DOUBLE_EQ(told.propulsive_linear.x, 50);
  EXPECT_DOUBLE_EQ(told.propulsive_rotational.z, 40);
  rig.drive_for(effort(50, 40), 1s);
  EXPECT_LT(rig.model().yaw_rate(), 0);  // the model's yaw is right-handed: negative = turning right
  // Clamped per side: X 80, Z 60 -> L 100 (not 140), R 20; reported as what was told.
  const auto clamped = rig.vehicle.apply_effort(effort(80, 60));
  EXPECT_DOUBLE_EQ(clamped.propulsive_linear.x, 60);
  EXPECT_DOUBLE_EQ(clamped.propulsive_rotational.z, 40);
}

TEST(ClearpathVehicle, ABrakeScalesDifferentialOutputsOrIsIgnored) {
  Rig scaled;
  scaled.vehicle.apply_effort(effort(80, 0, 50));
  scaled.time.advance(20ms);
  EXPECT_DOUBLE_EQ(scaled.model().differential_output()[0], 40);
  EXPECT_NE(scaled.vehicle.effort_fields() & comp::effort_field::kResistiveLinearX, 0);

  bridge::ClearpathVehicleConfig config;
  config.brake = bridge::BrakeMode::ignore;
  Rig ignored(config);
  ignored.vehicle.apply_effort(effort(80, 0, 50));
  ignored.time.advance(20ms);
  EXPECT_DOUBLE_EQ(ignored.model().differential_output()[0], 80);
  EXPECT_EQ(ignored.vehicle.effort_fields() & comp::effort_field::kResistiveLinearX, 0);
}

TEST(ClearpathVehicle, VelocityModeConvertsTheTurnSign) {
  bridge::ClearpathVehicleConfig config;
  config.drive = bridge::DriveMode::velocity;
  config.max_speed_mps = 0.8;
  config.max_yaw_rate_rps = 0.5;
  Rig rig(config);
  rig.vehicle.apply_effort(effort(50, -100));  // turning left at full rate
  rig.time.advance(20ms);
  const auto v = rig.model().velocity_setpoint();
  EXPECT_DOUBLE_EQ(v[0], 0.4);
  EXPECT_DOUBLE_EQ(v[1], 0.5);  // Clearpath: positive = left
  EXPECT_DOUBLE_EQ(v[2], 1.0);
}

TEST(ClearpathVehicle, DifferentialSpeedsStayWithinThePlatformsLimits) {
  bridge::ClearpathVehicleConfig config;
  config.drive = bridge::DriveMode::differential_speeds;
  config.max_speed_mps = 5.0;  // more than the platform's own 1.0 m/s (0x8210)
  config.track_width_m = 0.5;
  Rig rig(config);
  rig.time.advance(1s);  // 0x8210 arrives
  const auto told = rig.vehicle.apply_effort(effort(100, 0));
  rig.time.advance(20ms);
  const auto s = rig.model().differential_speeds_setpoint();
  EXPECT_DOUBLE_EQ(s[0], 1.0);
  EXPECT_DOUBLE_EQ(s[1], 1.0);
  EXPECT_DOUBLE_EQ(told.propulsive_linear.x, 20);  // 1 m/s of the configured 5
  EXPECT_DOUBLE_EQ(*rig.vehicle.specifications().max_velocity_x_mps, 1.0);
}

// Report Platform Specifications says what 100 % rotational z does: the
// drivers above the primitive driver steer by it (guidance::limits_from).
TEST(ClearpathVehicle, SpecificationsSayWhatFullRotationalEffortDoes) {
  bridge::ClearpathVehicleConfig open_loop;  // differential_output
  open_loop.max_speed_mps = 1.0;
  open_loop.track_width_m = 0.5;
  Rig differential(open_loop);
  // Both wheels at full speed either way: 2 * 1 m/s / 0.5 m.
  EXPECT_DOUBLE_EQ(*differential.vehicle.specifications().max_yaw_rate_rps, 4.0);
  EXPECT_FALSE(differential.vehicle.specifications().turning_radius_m);

  bridge::ClearpathVehicleConfig closed_loop;
  closed_loop.drive = bridge::DriveMode::differential_speeds;
  closed_loop.max_yaw_rate_rps = 0.7;
  Rig speeds(closed_loop);
  EXPECT_DOUBLE_EQ(*speeds.vehicle.specifications().max_yaw_rate_rps, 0.7);

  bridge::ClearpathVehicleConfig steered;
  steered.drive = bridge::DriveMode::ackermann;
  steered.wheel_base_m = 1.2;
  steered.max_steering_rad = 0.5;
  Rig ackermann(steered, sim::Drive::ackermann);
  const auto spec = ackermann.vehicle.specifications();
  EXPECT_DOUBLE_EQ(*spec.wheel_base_m, 1.2);
  EXPECT_NEAR(*spec.turning_radius_m, 1.2 / std::tan(0.5), 1e-9);
  EXPECT_FALSE(spec.max_yaw_rate_rps);
}

TEST(ClearpathVehicle, AckermannSteersLeftPositive) {
  bridge::ClearpathVehicleConfig config;
  config.drive = bridge::DriveMode::ackermann;
  Rig rig(config, sim::Drive::ackermann);
  rig.vehicle.apply_effort(effort(30, 25, 10));  // steering right
  rig.time.advance(20ms);
  const auto a = rig.model().ackermann_output();
  EXPECT_DOUBLE_EQ(a[0], -25);
  EXPECT_DOUBLE_EQ(a[1], 30);
  EXPECT_DOUBLE_EQ(a[2], 10);
}

TEST(ClearpathVehicle, ForwardThenLeftShowsInThePose) {
  bridge::ClearpathVehicleConfig config;
  config.datum = {45.0, -73.0, 50.0};
  config.datum_heading_rad = 0;  // facing north
  Rig rig(config);
  rig.drive_for(effort(100, 0), 3s);
  auto s = rig.vehicle.sample();
  ASSERT_TRUE(s && s->position && s->local_position && s->attitude && s->velocity_mps);
  EXPECT_GT(s->local_position->x_m, 1.5);  // north
  EXPECT_NEAR(s->local_position->y_m, 0, 0.05);
  EXPECT_GT(s->position->latitude_deg, 45.0);
  EXPECT_GT(s->velocity_mps->x, 0.5);
  const double rms_before = *s->position_rms_m;
  EXPECT_GT(rms_before, config.position_rms_m);  // grows with the distance

  rig.drive_for(effort(50, -10), 2s);  // turning left (L 40 %, R 60 %): the heading decreases (counter-clockwise)
  s = rig.vehicle.sample();
  ASSERT_TRUE(s && s->attitude && s->rates_rps);
  EXPECT_LT(s->attitude->yaw, -0.3);
  EXPECT_GT(s->attitude->yaw, -1.5);
  EXPECT_LT(s->rates_rps->z, 0);      // yaw rate: negative = turning left in JAUS
  EXPECT_LT(s->local_position->y_m, 0);  // drifted west
}

TEST(ClearpathVehicle, TheDatumHeadingRotatesThePlatformsFrame) {
  bridge::ClearpathVehicleConfig config;
  config.datum_heading_rad = M_PI / 2;  // facing east
  Rig rig(config);
  rig.drive_for(effort(100, 0), 2s);
  const auto s = rig.vehicle.sample();
  ASSERT_TRUE(s && s->local_position);
  EXPECT_GT(s->local_position->y_m, 1.0);
  EXPECT_NEAR(s->local_position->x_m, 0, 0.05);
  EXPECT_NEAR(s->attitude->yaw, M_PI / 2, 1e-3);
}

// Safety: stop() writes one zero setpoint and ends the stream.
TEST(ClearpathVehicle, AStopIsOneZeroSetpointThenSilence) {
  Rig rig;
  rig.drive_for(effort(80, 0), 1s);
  ASSERT_GT(rig.model().linear_speed(), 0.3);
  const auto before = rig.written_of(cp::SetDifferentialOutput::kType);
  rig.vehicle.stop(0);
  rig.time.advance(5ms);
  EXPECT_EQ(rig.written_of(cp::SetDifferentialOutput::kType), before + 1);
  EXPECT_EQ(rig.model().differential_output()[0], 0);
  rig.time.advance(2s);
  EXPECT_EQ(rig.written_of(cp::SetDifferentialOutput::kType), before + 1);
  EXPECT_EQ(rig.model().linear_speed(), 0);
  EXPECT_EQ(rig.vehicle.applied_effort(), comp::WrenchEffort{});
}

// Safety: a command the driver stops renewing is no longer sent after the
// setpoint's maximum age; the platform's watchdog stops it and the report says zero.
TEST(ClearpathVehicle, AnUnrenewedCommandEndsAtItsMaximumAge) {
  Rig rig;
  rig.vehicle.apply_effort(effort(80, 0));
  rig.time.advance(300ms);
  EXPECT_DOUBLE_EQ(rig.vehicle.applied_effort().propulsive_linear.x, 80);
  rig.time.advance(1500ms);
  EXPECT_EQ(rig.vehicle.applied_effort(), comp::WrenchEffort{});
  EXPECT_EQ(rig.model().linear_speed(), 0);
  EXPECT_TRUE(rig.model().safety_flags() & sim::kSafetyTimeout);
}

// Safety: link down -> fault, motion refused; link back -> fault cleared, and
// nothing moves until a new command.
TEST(ClearpathVehicle, ALostLinkIsAFaultAndItsReturnMovesNothing) {
  Rig rig;
  rig.drive_for(effort(80, 0), 500ms);
  rig.loopback.set_plugged(false);
  rig.time.advance(1500ms);
  ASSERT_TRUE(rig.fault);
  EXPECT_EQ(*rig.fault, "link to the Clearpath platform lost");
  EXPECT_EQ(rig.vehicle.apply_effort(effort(80, 0)), comp::WrenchEffort{});
  EXPECT_EQ(rig.vehicle.counters().refused_offline, 1u);
  EXPECT_EQ(rig.model().linear_speed(), 0);  // the platform's watchdog

  const auto before = rig.written_of(cp::SetDifferentialOutput::kType);
  rig.loopback.set_plugged(true);
  rig.time.advance(4s);
  EXPECT_EQ(rig.fault, std::nullopt);
  EXPECT_EQ(rig.written_of(cp::SetDifferentialOutput::kType), before);
  EXPECT_EQ(rig.model().linear_speed(), 0);
  rig.drive_for(effort(50, 0), 1s);  // a new command moves it again
  EXPECT_GT(rig.model().linear_speed(), 0.2);
}

TEST(ClearpathVehicle, DevicesGoToGearSafetyFlagsAndGpio) {
  bridge::ClearpathVehicleConfig config;
  config.drive = bridge::DriveMode::ackermann;  // the simulated platform has gears when it steers
  config.gear = true;
  config.parking_brake = {bridge::DeviceOutput::Kind::gpio, 0x04, true};
  config.horn = {bridge::DeviceOutput::Kind::gpio, 0x08, true};
  config.main_power = {bridge::DeviceOutput::Kind::safety_flag, 0x02, false};  // lockout set = power off
  Rig rig(config, sim::Drive::ackermann);
  const auto has = rig.vehicle.devices();
  EXPECT_TRUE(has.gear && has.parking_brake && has.horn && has.main_power);

  comp::DiscreteDevices d;
  d.gear = 129;  // first reverse
  d.parking_brake = true;
  d.horn = false;
  rig.vehicle.set_devices(d);
  rig.time.advance(1s);
  EXPECT_EQ(rig.model().gear(), -2);
  EXPECT_EQ(rig.model().gpio_value() & 0x0C, 0x04u);
  EXPECT_EQ(rig.vehicle.device_state().gear, 129);

  comp::DiscreteDevices off;
  off.main_power = false;
  rig.vehicle.set_devices(off);
  rig.time.advance(100ms);
  EXPECT_TRUE(rig.model().safety_flags() & sim::kSafetyLockout);
  EXPECT_EQ(rig.vehicle.device_state().main_power, false);
}

TEST(ClearpathVehicle, OperationalDataAndSpecificationsComeFromThePlatform) {
  Rig rig;
  rig.drive_for(effort(100, 0), 2s);
  const auto d = rig.vehicle.operational_data();
  ASSERT_TRUE(d.battery_voltage_percent && d.odometer_m && d.fuel_level_percent);
  EXPECT_GT(*d.battery_voltage_percent, 90);
  EXPECT_GT(*d.odometer_m, 1.0);
  EXPECT_GT(*d.fuel_level_percent, 50);
  EXPECT_EQ(rig.vehicle.specifications().name, "Clearpath1");  // 0x8002
}

// The platform's own e-stop or pause (0x8010) is reported, and so is its end;
// the emergency flag the bridge sets itself for JAUS is not taken for one, and
// its clear is reported held until the platform shows it clear (the flag is
// the e-stop's bit: until then the platform may still be stopped).
TEST(ClearpathVehicle, ThePlatformsEstopIsHeardAndOurOwnFlagIsNot) {
  bridge::ClearpathVehicleConfig config;
  config.emergency_flags = 0x08;
  Rig rig(config);
  std::vector<std::optional<std::string>> heard;
  rig.vehicle.on_platform_emergency([&](const std::optional<std::string>& why) { heard.push_back(why); });

  rig.vehicle.command_emergency(true);
  rig.time.advance(500ms);
  EXPECT_TRUE(rig.model().safety_flags() & sim::kSafetyEmergencyStop);
  EXPECT_TRUE(heard.empty());
  rig.vehicle.command_emergency(false);
  ASSERT_EQ(heard.size(), 1u);  // at once, before anything could leave Emergency
  ASSERT_TRUE(heard[0]);
  EXPECT_EQ(*heard[0], "waiting for the Clearpath platform to report its emergency flag 0x0008 clear");
  rig.time.advance(500ms);
  EXPECT_FALSE(rig.model().safety_flags() & sim::kSafetyEmergencyStop);
  ASSERT_EQ(heard.size(), 2u);
  EXPECT_FALSE(heard[1]);

  rig.loopback.platform().press(sim::HardwareInput::pause, true, rig.time.now());  // on the platform, not by the bridge
  rig.time.advance(500ms);
  ASSERT_EQ(heard.size(), 3u);
  ASSERT_TRUE(heard[2]);
  EXPECT_EQ(*heard[2], "Clearpath platform e-stop or pause (safety flags 0x0010)");
  rig.loopback.platform().press(sim::HardwareInput::pause, false, rig.time.now());
  rig.time.advance(500ms);
  ASSERT_EQ(heard.size(), 4u);
  EXPECT_FALSE(heard[3]);
}
