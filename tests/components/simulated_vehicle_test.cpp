// The simulated vehicle under virtual time: effort becomes motion within the
// configured limits, devices gate it, stop() holds, motion becomes WGS 84, and
// samples are timed at integration steps, deterministically.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "jaus/base/virtual_time.hpp"
#include "jaus/components/simulated_vehicle.hpp"

namespace jaus::components {
namespace {

using namespace std::chrono_literals;
using std::numbers::pi;

// Metres per degree near 45 degrees latitude on WGS 84.
constexpr double kMetresPerDegreeLatitude = 111132.95;
constexpr double kMetresPerDegreeLongitude = 78846.8;

WrenchEffort effort(double linear, double turn = 0, double brake = 0) {
  WrenchEffort e;
  e.propulsive_linear.x = linear;
  e.propulsive_rotational.z = turn;
  e.resistive_linear.x = brake;
  return e;
}

void expect_same(const PoseSample& a, const PoseSample& b) {
  EXPECT_EQ(a.taken_at, b.taken_at);
  EXPECT_EQ(a.taken_utc, b.taken_utc);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.local_position, b.local_position);
  EXPECT_EQ(a.position_rms_m, b.position_rms_m);
  EXPECT_EQ(a.attitude, b.attitude);
  EXPECT_EQ(a.attitude_rms_rad, b.attitude_rms_rad);
  EXPECT_EQ(a.velocity_mps, b.velocity_mps);
  EXPECT_EQ(a.velocity_rms_mps, b.velocity_rms_mps);
  EXPECT_EQ(a.rates_rps, b.rates_rps);
  EXPECT_EQ(a.rate_rms_rps, b.rate_rms_rps);
}

class SimulatedVehicleTest : public ::testing::Test {
 protected:
  void advance(rt::Duration d) { time.advance(d); }

  rt::VirtualTime time{rt::UtcTime{std::chrono::hours(24 * 365 * 50)}};  // a UTC origin that is not the epoch
  SimulatedVehicle vehicle{SimulatedVehicleConfig{}, time};
};

TEST_F(SimulatedVehicleTest, FullForwardEffortReachesMaxSpeedAfterMaxSpeedOverAcceleration) {
  // Defaults: 1 m/s at 100 %, 1 m/s^2: one second.
  vehicle.apply_effort(effort(100));
  advance(500ms);
  EXPECT_NEAR(vehicle.speed_mps(), 0.5, 1e-9);
  advance(460ms);
  EXPECT_LT(vehicle.speed_mps(), 0.97 + 1e-9);  // not before
  advance(40ms);
  EXPECT_NEAR(vehicle.speed_mps(), 1.0, 1e-9);
  advance(5s);
  EXPECT_NEAR(vehicle.speed_mps(), 1.0, 1e-9);  // and no further
}

TEST_F(SimulatedVehicleTest, PartialEffortAndBrakeScaleTheTargetSpeed) {
  vehicle.apply_effort(effort(40));
  advance(3s);
  EXPECT_NEAR(vehicle.speed_mps(), 0.4, 1e-9);
  vehicle.apply_effort(effort(100, 0, 50));  // full effort against half brake: half speed
  advance(3s);
  EXPECT_NEAR(vehicle.speed_mps(), 0.5, 1e-9);
}

TEST_F(SimulatedVehicleTest, ACommandTakesEffectFromTheStepInWhichItArrives) {
  advance(10ms);  // mid-step (50 Hz: 20 ms steps)
  vehicle.apply_effort(effort(100));
  advance(10ms);
  EXPECT_NEAR(vehicle.speed_mps(), 0.02, 1e-12);  // the whole first step accelerated
}

TEST(SimulatedVehicle, DrivingNorthMovesLatitudeByTheDistanceOverMetresPerDegree) {
  rt::VirtualTime time;
  SimulatedVehicle vehicle({}, time);  // heading 0: north
  const auto start = *vehicle.sample();
  vehicle.apply_effort(effort(100));
  time.advance(10s);
  const auto end = *vehicle.sample();

  // One second speeding up (0.5 m), nine at 1 m/s.
  EXPECT_NEAR(vehicle.distance_travelled_m(), 9.5, 1e-9);
  ASSERT_TRUE(end.position && start.position);
  EXPECT_NEAR((end.position->latitude_deg - start.position->latitude_deg) * kMetresPerDegreeLatitude, 9.5, 0.01);
  EXPECT_NEAR((end.position->longitude_deg - start.position->longitude_deg) * kMetresPerDegreeLongitude, 0, 1e-6);
  EXPECT_NEAR(end.position->altitude_m, 50.0, 1e-3);
  ASSERT_TRUE(end.local_position);
  EXPECT_NEAR(end.local_position->x_m, 9.5, 1e-9);  // x north
  EXPECT_NEAR(end.local_position->y_m, 0, 1e-9);
  EXPECT_NEAR(end.local_position->z_m, 0, 1e-9);
}

TEST(SimulatedVehicle, DrivingEastMovesLongitude) {
  rt::VirtualTime time;
  SimulatedVehicleConfig config;
  config.start_heading_rad = pi / 2;
  SimulatedVehicle vehicle(config, time);
  const auto start = *vehicle.sample();
  vehicle.apply_effort(effort(100));
  time.advance(10s);
  const auto end = *vehicle.sample();

  EXPECT_NEAR((end.position->longitude_deg - start.position->longitude_deg) * kMetresPerDegreeLongitude, 9.5, 0.01);
  EXPECT_NEAR((end.position->latitude_deg - start.position->latitude_deg) * kMetresPerDegreeLatitude, 0, 1e-3);
  EXPECT_NEAR(end.local_position->x_m, 0, 1e-9);
  EXPECT_NEAR(end.local_position->y_m, 9.5, 1e-9);  // y east
  EXPECT_NEAR(end.attitude->yaw, pi / 2, 1e-12);
}

TEST_F(SimulatedVehicleTest, ARightTurnIncreasesHeadingAndALeftTurnDecreasesIt) {
  vehicle.apply_effort(effort(50, 50));
  advance(2s);
  EXPECT_NEAR(vehicle.yaw_rate_rps(), 0.5, 1e-9);  // 50 % of 1 rad/s, reached at 3 rad/s^2
  const double heading = vehicle.heading_rad();
  EXPECT_GT(heading, 0.8);
  EXPECT_LT(heading, 1.0);
  const auto s = *vehicle.sample();
  EXPECT_GT(s.local_position->y_m, 0);  // from north, a right turn goes east
  EXPECT_EQ(s.attitude->yaw, heading);
  EXPECT_EQ(s.rates_rps->z, vehicle.yaw_rate_rps());

  vehicle.apply_effort(effort(50, -50));
  advance(4s);
  EXPECT_NEAR(vehicle.yaw_rate_rps(), -0.5, 1e-9);
  EXPECT_LT(vehicle.heading_rad(), heading);
}

TEST_F(SimulatedVehicleTest, TheHeadingStaysWrapped) {
  vehicle.apply_effort(effort(0, 100));  // a differential vehicle turns in place
  advance(20s);
  EXPECT_EQ(vehicle.distance_travelled_m(), 0);
  EXPECT_GT(vehicle.heading_rad(), -pi);
  EXPECT_LE(vehicle.heading_rad(), pi);
}

TEST_F(SimulatedVehicleTest, StopBrakesToZeroWithinTheBrakingTimeAndStaysThere) {
  vehicle.apply_effort(effort(100, 30));
  advance(2s);
  ASSERT_NEAR(vehicle.speed_mps(), 1.0, 1e-9);
  vehicle.stop(100);
  EXPECT_EQ(vehicle.applied_effort(), effort(0, 0, 100));
  advance(200ms);
  EXPECT_NEAR(vehicle.speed_mps(), 1.0 - 3.0 * 0.2, 1e-9);  // at max_deceleration
  advance(140ms);                                          // 1 m/s / 3 m/s^2 = 0.333 s
  EXPECT_EQ(vehicle.speed_mps(), 0);
  const double distance = vehicle.distance_travelled_m();
  advance(10s);
  EXPECT_EQ(vehicle.speed_mps(), 0);  // never resumes the earlier effort
  EXPECT_EQ(vehicle.yaw_rate_rps(), 0);
  EXPECT_EQ(vehicle.distance_travelled_m(), distance);
  vehicle.stop(100);  // idempotent
  EXPECT_EQ(vehicle.speed_mps(), 0);
}

TEST_F(SimulatedVehicleTest, StopWithoutBrakeCoastsDownAtTheAccelerationLimit) {
  vehicle.apply_effort(effort(-100));  // reversing
  advance(2s);
  ASSERT_NEAR(vehicle.speed_mps(), -1.0, 1e-9);
  vehicle.stop(0);
  advance(500ms);
  EXPECT_NEAR(vehicle.speed_mps(), -0.5, 1e-9);
  advance(500ms);
  EXPECT_EQ(vehicle.speed_mps(), 0);
  advance(5s);
  EXPECT_EQ(vehicle.speed_mps(), 0);
}

TEST_F(SimulatedVehicleTest, ParkingBrakeMainPowerOffParkAndNeutralPreventMotion) {
  const DiscreteDevices cases[] = {{std::nullopt, true, std::nullopt, std::nullopt},
                                   {false, std::nullopt, std::nullopt, std::nullopt},
                                   {std::nullopt, std::nullopt, std::nullopt, 0},
                                   {std::nullopt, std::nullopt, std::nullopt, 128}};
  for (const auto& devices : cases) {
    rt::VirtualTime t;
    SimulatedVehicle v({}, t);
    v.set_devices(devices);
    v.apply_effort(effort(100, 100));
    t.advance(5s);
    EXPECT_EQ(v.speed_mps(), 0);
    EXPECT_EQ(v.yaw_rate_rps(), 0);
    EXPECT_EQ(v.heading_rad(), 0);
    EXPECT_EQ(v.distance_travelled_m(), 0);

    // Released (power on, brake off, a forward gear), the same effort drives.
    v.set_devices({true, false, std::nullopt, 1});
    t.advance(2s);
    EXPECT_NEAR(v.speed_mps(), 1.0, 1e-9);
  }
}

TEST_F(SimulatedVehicleTest, TheParkingBrakeStopsAMovingVehicleAtMaxDeceleration) {
  vehicle.apply_effort(effort(100));
  advance(2s);
  vehicle.set_devices({std::nullopt, true, std::nullopt, std::nullopt});
  advance(200ms);
  EXPECT_NEAR(vehicle.speed_mps(), 0.4, 1e-9);
  advance(140ms);
  EXPECT_EQ(vehicle.speed_mps(), 0);
}

TEST_F(SimulatedVehicleTest, MainPowerOffCoastsDown) {
  vehicle.apply_effort(effort(100));
  advance(2s);
  vehicle.set_devices({false, std::nullopt, std::nullopt, std::nullopt});
  advance(500ms);
  EXPECT_NEAR(vehicle.speed_mps(), 0.5, 1e-9);
}

TEST_F(SimulatedVehicleTest, TheEffortSignIsTheDirectionInEveryDriveGear) {
  vehicle.apply_effort(effort(-100));  // forward gear, negative effort: reverses
  advance(2s);
  EXPECT_NEAR(vehicle.speed_mps(), -1.0, 1e-9);
  EXPECT_LT(vehicle.sample()->local_position->x_m, 0);  // backwards from north: south

  vehicle.set_devices({std::nullopt, std::nullopt, std::nullopt, 200});  // a reverse gear
  vehicle.apply_effort(effort(100));
  advance(3s);
  EXPECT_NEAR(vehicle.speed_mps(), 1.0, 1e-9);
  EXPECT_EQ(vehicle.device_state().gear, 200);
}

TEST_F(SimulatedVehicleTest, ReversingThroughZeroBrakesThenAccelerates) {
  vehicle.apply_effort(effort(100));
  advance(1s);
  vehicle.apply_effort(effort(-100, 0, 0));
  advance(500ms);
  EXPECT_NEAR(vehicle.speed_mps(), 0.5, 1e-9);  // slowing at the acceleration limit
  advance(1s);
  EXPECT_NEAR(vehicle.speed_mps(), -0.5, 1e-9);
}

TEST_F(SimulatedVehicleTest, PositionRmsGrowsWithDistanceAndTheOdometerWithEveryMetre) {
  EXPECT_DOUBLE_EQ(*vehicle.sample()->position_rms_m, 0.5);
  EXPECT_EQ(vehicle.operational_data().odometer_m, 0.0);
  vehicle.apply_effort(effort(100));
  advance(10s);
  EXPECT_NEAR(*vehicle.sample()->position_rms_m, 0.5 + 0.01 * 9.5, 1e-9);
  const double forward = *vehicle.operational_data().odometer_m;
  EXPECT_NEAR(forward, 9.5, 1e-9);

  vehicle.apply_effort(effort(-100));  // back the way it came: the odometer still counts up
  double last = forward;
  for (int i = 0; i < 20; ++i) {
    advance(500ms);
    const double odometer = *vehicle.operational_data().odometer_m;
    EXPECT_GE(odometer, last);
    last = odometer;
  }
  EXPECT_GT(last, forward + 5);
  EXPECT_LT(vehicle.sample()->local_position->x_m, forward);
  EXPECT_NEAR(*vehicle.sample()->position_rms_m, 0.5 + 0.01 * last, 1e-9);
}

TEST_F(SimulatedVehicleTest, TheBatteryDrainsOnlyWhileMainPowerIsOnAndNotBelowZero) {
  const auto start = vehicle.operational_data();
  EXPECT_EQ(start.battery_voltage_percent, 100.0);
  EXPECT_FALSE(start.engine_temperature_c);
  EXPECT_FALSE(start.fuel_level_percent);
  advance(1h);
  EXPECT_NEAR(*vehicle.operational_data().battery_voltage_percent, 95, 1e-9);
  vehicle.set_devices({false, std::nullopt, std::nullopt, std::nullopt});
  advance(2h);
  EXPECT_NEAR(*vehicle.operational_data().battery_voltage_percent, 95, 1e-9);
  vehicle.set_devices({true, std::nullopt, std::nullopt, std::nullopt});
  advance(std::chrono::hours(100));
  EXPECT_EQ(*vehicle.operational_data().battery_voltage_percent, 0);
}

TEST_F(SimulatedVehicleTest, SampleTimesAreStepBoundaries) {
  const rt::TimePoint t0 = time.now();
  const auto first = *vehicle.sample();  // a sample from the start
  EXPECT_EQ(first.taken_at, t0);
  EXPECT_EQ(first.taken_utc, time.utc_now());

  advance(1s + 7ms);
  const auto s = *vehicle.sample();
  EXPECT_EQ(s.taken_at, t0 + 1s);  // 50 Hz: 20 ms steps
  EXPECT_EQ(s.taken_utc, time.utc_now() - 7ms);
  advance(12ms);
  EXPECT_EQ(vehicle.sample()->taken_at, t0 + 1s);  // 1.019 s: still the same step
  advance(1ms);
  EXPECT_EQ(vehicle.sample()->taken_at, t0 + 1s + 20ms);
  EXPECT_DOUBLE_EQ(vehicle.update_rate_hz(), 50);
}

TEST(SimulatedVehicle, StepsCountFromConstructionNotFromTheClocksOrigin) {
  rt::VirtualTime time;
  time.advance(123ms);
  SimulatedVehicle vehicle({}, time);
  time.advance(50ms);
  EXPECT_EQ(vehicle.sample()->taken_at, rt::TimePoint{} + 123ms + 40ms);
}

TEST_F(SimulatedVehicleTest, FrozenSamplesKeepTheirOldTimeWhileTheVehicleMoves) {
  vehicle.apply_effort(effort(100));
  advance(1s);
  const auto before = *vehicle.sample();
  vehicle.freeze_samples(true);
  advance(2s);
  const auto frozen = *vehicle.sample();
  expect_same(frozen, before);
  EXPECT_GT(vehicle.distance_travelled_m(), 2);  // still moving
  vehicle.freeze_samples(true);                  // freezing again keeps the first frozen sample
  expect_same(*vehicle.sample(), before);

  vehicle.freeze_samples(false);
  const auto fresh = *vehicle.sample();
  EXPECT_EQ(fresh.taken_at, time.now());
  EXPECT_GT(fresh.local_position->x_m, before.local_position->x_m + 1.9);
}

TEST(SimulatedVehicle, AckermannTurnsWithSpeedTimesTanSteeringOverWheelBase) {
  rt::VirtualTime time;
  SimulatedVehicleConfig config;
  config.steering = Steering::ackermann;
  config.wheel_base_m = 0.8;
  config.max_steering_rad = 0.5;
  SimulatedVehicle vehicle(config, time);

  vehicle.apply_effort(effort(0, 100));  // full steering at rest: no turn
  time.advance(1s);
  EXPECT_EQ(vehicle.yaw_rate_rps(), 0);
  EXPECT_EQ(vehicle.heading_rad(), 0);

  vehicle.apply_effort(effort(100, 50));  // steering 0.25 rad
  time.advance(1s);                       // at 1 m/s now
  const double expected_rate = 1.0 * std::tan(0.25) / 0.8;
  EXPECT_NEAR(vehicle.yaw_rate_rps(), expected_rate, 1e-9);
  const double heading = vehicle.heading_rad();
  time.advance(1s);
  EXPECT_NEAR(vehicle.heading_rad() - heading, expected_rate * 1.0, 1e-9);

  vehicle.apply_effort(effort(-100, 50));  // reversing with the wheels turned right: heading decreases
  time.advance(4s);
  EXPECT_NEAR(vehicle.yaw_rate_rps(), -expected_rate, 1e-9);

  const auto spec = vehicle.specifications();
  EXPECT_NEAR(*spec.turning_radius_m, 0.8 / std::tan(0.5), 1e-12);
  EXPECT_NEAR(*spec.max_yaw_rate_rps, 1.0 * std::tan(0.5) / 0.8, 1e-12);
  EXPECT_EQ(spec.wheel_base_m, 0.8);
  EXPECT_EQ(spec.max_velocity_x_mps, 1.0);
}

TEST(SimulatedVehicle, IdenticalCommandsAtIdenticalTimesGiveIdenticalSamples) {
  rt::VirtualTime time;
  SimulatedVehicle a({}, time), b({}, time);
  const WrenchEffort script[] = {effort(100, 20), effort(60, -80, 10), effort(-30, 100), effort(100, 0, 40)};
  for (const auto& e : script) {
    a.apply_effort(e);
    b.apply_effort(e);
    for (int i = 0; i < 37; ++i) {
      time.advance(13ms);
      a.sample();  // `a` is asked often, `b` only at the end of each command: no difference
    }
  }
  a.stop(60);
  b.stop(60);
  time.advance(3s + 5ms);
  expect_same(*a.sample(), *b.sample());
  EXPECT_EQ(a.operational_data(), b.operational_data());
}

TEST_F(SimulatedVehicleTest, OutOfRangeAndNonFiniteEffortsAreClamped) {
  WrenchEffort wild = effort(250, -300, 150);
  wild.propulsive_linear.y = 50;  // not a field this drive acts on
  wild.resistive_rotational.z = 20;
  EXPECT_EQ(vehicle.apply_effort(wild), effort(100, -100, 100));
  EXPECT_EQ(vehicle.applied_effort(), effort(100, -100, 100));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(vehicle.apply_effort(effort(nan, inf, -inf)), effort(0, 0, 0));
  EXPECT_EQ(vehicle.apply_effort(effort(-100, 100, -5)), effort(-100, 100, 0));
  advance(3s);
  EXPECT_NEAR(vehicle.speed_mps(), -1.0, 1e-9);

  vehicle.stop(250);
  EXPECT_EQ(vehicle.applied_effort(), effort(0, 0, 100));
  vehicle.stop(nan);
  EXPECT_EQ(vehicle.applied_effort(), effort(0, 0, 0));
}

TEST_F(SimulatedVehicleTest, AnInjectedDriveFaultReachesTheListenerOnChangesOnly) {
  std::vector<std::optional<std::string>> heard;
  vehicle.on_fault([&](const std::optional<std::string>& fault) { heard.push_back(fault); });
  vehicle.inject_drive_fault("link lost");
  vehicle.inject_drive_fault("link lost");  // no change
  vehicle.inject_drive_fault(std::nullopt);
  vehicle.inject_drive_fault(std::nullopt);  // no change
  ASSERT_EQ(heard.size(), 2u);
  EXPECT_EQ(heard[0], "link lost");
  EXPECT_EQ(heard[1], std::nullopt);
  vehicle.on_fault({});  // no listener: nothing is called
  vehicle.inject_drive_fault("again");
  EXPECT_EQ(heard.size(), 2u);
}

TEST_F(SimulatedVehicleTest, ReportsItsFieldsDevicesAndSpecifications) {
  EXPECT_EQ(vehicle.effort_fields(), effort_field::kPropulsiveLinearX | effort_field::kPropulsiveRotationalZ |
                                         effort_field::kResistiveLinearX);
  const auto has = vehicle.devices();
  EXPECT_TRUE(has.main_power && has.parking_brake && has.horn && has.gear);
  EXPECT_EQ(vehicle.device_state(), (DiscreteDevices{true, false, false, 1}));
  EXPECT_EQ(vehicle.set_devices({std::nullopt, std::nullopt, true, std::nullopt}),
            (DiscreteDevices{true, false, true, 1}));  // absent devices unchanged

  const auto spec = vehicle.specifications();
  EXPECT_EQ(spec.name, "jaus-sim");
  EXPECT_EQ(spec.max_velocity_x_mps, 1.0);
  EXPECT_EQ(spec.max_yaw_rate_rps, 1.0);
  EXPECT_EQ(spec.wheel_base_m, 0.5);
  EXPECT_FALSE(spec.turning_radius_m);
}

TEST(SimulatedVehicle, SamplesCarryEveryValueAndTheLocalPoseOnlyWhenConfigured) {
  rt::VirtualTime time;
  SimulatedVehicleConfig config;
  config.local_frame = false;
  SimulatedVehicle vehicle(config, time);
  vehicle.apply_effort(effort(50));
  time.advance(2s);
  const auto s = *vehicle.sample();
  EXPECT_FALSE(s.local_position);
  ASSERT_TRUE(s.position && s.attitude && s.velocity_mps && s.rates_rps);
  EXPECT_EQ(*s.attitude, (EulerAngles{0, 0, 0}));
  EXPECT_EQ(*s.velocity_mps, (Axes{0.5, 0, 0}));
  EXPECT_EQ(*s.rates_rps, (Axes{0, 0, 0}));
  EXPECT_EQ(s.attitude_rms_rad, 0.01);
  EXPECT_EQ(s.velocity_rms_mps, 0.02);
  EXPECT_EQ(s.rate_rms_rps, 0.01);
}

TEST(SimulatedVehicle, ANonPositiveUpdateRateIsClampedSoTimeStillMoves) {
  rt::VirtualTime time;
  SimulatedVehicleConfig config;
  config.update_rate_hz = 0;
  SimulatedVehicle vehicle(config, time);
  EXPECT_GT(vehicle.update_rate_hz(), 0);
  EXPECT_EQ(vehicle.config().update_rate_hz, vehicle.update_rate_hz());
  vehicle.apply_effort(effort(100));
  time.advance(60s);
  EXPECT_GT(vehicle.distance_travelled_m(), 0);
  EXPECT_GT(vehicle.sample()->taken_at, rt::TimePoint{});
}

}  // namespace
}  // namespace jaus::components
