// The primitive driver on a recording drive, under virtual time: what reaches
// the drive, what the reports say, and every path that must stop it.
#include "harness.hpp"
#include "jaus/components/primitive_driver.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using components::Axes;
using components::DiscreteDevices;
using components::WrenchEffort;
namespace field = components::effort_field;

// A drive that records what it is told; it acts on linear x, rotational z
// and the linear brake, and has every discrete device.
class RecordingDrive final : public components::Drive {
 public:
  std::uint16_t effort_fields() const override {
    return field::kPropulsiveLinearX | field::kPropulsiveRotationalZ | field::kResistiveLinearX;
  }
  components::DeviceSet devices() const override { return {true, true, true, true}; }
  components::PlatformSpecifications specifications() const override {
    components::PlatformSpecifications s;
    s.name = "a very long platform name";
    s.front_m = 0.5;
    s.wheel_base_m = 0.6;
    s.max_velocity_x_mps = 1.5;
    return s;
  }
  WrenchEffort apply_effort(const WrenchEffort& e) override {
    applied = {};
    applied.propulsive_linear.x = e.propulsive_linear.x;
    applied.propulsive_rotational.z = e.propulsive_rotational.z;
    applied.resistive_linear.x = e.resistive_linear.x;
    efforts.push_back(applied);
    return applied;
  }
  DiscreteDevices set_devices(const DiscreteDevices& d) override {
    if (d.main_power) state.main_power = d.main_power;
    if (d.parking_brake) state.parking_brake = d.parking_brake;
    if (d.horn) state.horn = d.horn;
    if (d.gear) state.gear = d.gear;
    device_commands.push_back(d);
    return state;
  }
  void stop(double brake_percent) override {
    applied = {};
    applied.resistive_linear.x = brake_percent;
    stops.push_back(brake_percent);
  }
  WrenchEffort applied_effort() const override { return applied; }
  DiscreteDevices device_state() const override { return state; }
  components::OperationalData operational_data() override {
    components::OperationalData d;
    d.odometer_m = 1234.7;
    d.battery_voltage_percent = 87;
    return d;
  }

  // As the Clearpath bridge does: a fault present when the listener arrives is told at once.
  void on_fault(FaultListener listener) override {
    fault_listener = std::move(listener);
    if (fault_listener && current_fault) fault_listener(current_fault);
  }
  void fault(std::optional<std::string> what) {
    current_fault = what;
    if (fault_listener) fault_listener(what);
  }
  FaultListener fault_listener;
  std::optional<std::string> current_fault;

  bool propelling() const { return applied.propulsive_linear != Axes{} || applied.propulsive_rotational != Axes{}; }
  // As the Clearpath bridge does once setpoint_max_age has passed: the report
  // says zero while the platform may still act on the last setpoint.
  void forget_applied() { applied = {}; }

  WrenchEffort applied;
  DiscreteDevices state{true, false, false, 1};
  std::vector<WrenchEffort> efforts;
  std::vector<DiscreteDevices> device_commands;
  std::vector<double> stops;
};

const Address kPrimitiveDriver{1, 1, 33, 1};

class PrimitiveDriverTest : public ::testing::Test {
 protected:
  PrimitiveDriverTest() { make(); }

  void make(components::PrimitiveDriverOptions options = {}) {
    driver.reset();
    rt::ComponentConfig config;
    config.name = "primitive driver";
    config.address = kPrimitiveDriver;
    config.authority = 5;
    outbox.clock = &time;
    driver = std::make_unique<components::PrimitiveDriver>(
        config, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); }},
        drive, options);
    driver->start();
  }

  template <class M>
  void deliver(const Address& from, const M& m) {
    deliver_to(*driver, time, from, m);
  }
  void take_control(const Address& ocu, std::uint8_t authority = 5) {
    deliver(ocu, msg::RequestComponentControl{{authority}});
    ASSERT_TRUE(driver->control().is_controller(ocu));
  }
  void effort(const Address& from, double x, double rz = 0) {
    msg::SetWrenchEffort m;
    m.propulsive_linear_effort_x_percent = x;
    m.propulsive_rotational_effort_z_percent = rz;
    deliver(from, m);
  }
  // Drives at 60 %, then checks `trigger` stops the drive (with the brake)
  // and that nothing moves it again until a new Set Wrench Effort.
  template <class Trigger, class Recover>
  void expect_stop_and_no_resume(const std::string& what, Trigger trigger, Recover recover) {
    SCOPED_TRACE(what);
    effort(kOcuA, 60);
    ASSERT_TRUE(drive.propelling());
    const auto stops_before = drive.stops.size();
    trigger();
    ASSERT_GT(drive.stops.size(), stops_before) << "no stop";
    EXPECT_EQ(drive.stops.back(), 100);
    EXPECT_FALSE(drive.propelling());
    const auto efforts_before = drive.efforts.size();
    recover();
    time.advance(2s);
    EXPECT_EQ(drive.efforts.size(), efforts_before) << "an effort was applied without a new Set Wrench Effort";
    EXPECT_FALSE(drive.propelling());
  }

  template <class M>
  std::vector<M> reports_to(const Address& a) const {
    return outbox.to<M>(a);
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  RecordingDrive drive;
  std::unique_ptr<components::PrimitiveDriver> driver;
};

TEST_F(PrimitiveDriverTest, ControllersEffortReachesTheDriveAndTheReportShowsWhatWasApplied) {
  take_control(kOcuA);
  msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = 50;
  m.propulsive_linear_effort_y_percent = 30;  // this platform has no lateral effort
  m.propulsive_rotational_effort_z_percent = -20;
  deliver(kOcuA, m);
  ASSERT_EQ(drive.efforts.size(), 1u);
  EXPECT_NEAR(drive.efforts[0].propulsive_linear.x, 50, 0.01);  // one scale step of the wire
  EXPECT_NEAR(drive.efforts[0].propulsive_rotational.z, -20, 0.01);

  deliver(kOcuB, msg::QueryWrenchEffort{{0xFFFF}});
  const auto reports = reports_to<msg::ReportWrenchEffort>(kOcuB);
  ASSERT_EQ(reports.size(), 1u);
  const auto& r = reports[0];
  // Exactly the fields this platform has, with what it applied: never the query's echo.
  EXPECT_EQ(wire::presence_of(r), field::kPropulsiveLinearX | field::kPropulsiveRotationalZ | field::kResistiveLinearX);
  EXPECT_NEAR(*r.propulsive_linear_effort_x_percent, 50, 0.01);
  EXPECT_NEAR(*r.propulsive_rotational_effort_z_percent, -20, 0.01);
  EXPECT_NEAR(*r.resistive_linear_effort_x_percent, 0, 0.01);
  EXPECT_FALSE(r.propulsive_linear_effort_y_percent);
}

TEST_F(PrimitiveDriverTest, QueriesAndTheFieldsThePlatformHas) {
  deliver(kOcuB, msg::QueryWrenchEffort{{field::kPropulsiveLinearX | field::kPropulsiveLinearY}});
  auto effort_reports = reports_to<msg::ReportWrenchEffort>(kOcuB);
  ASSERT_EQ(effort_reports.size(), 1u);
  EXPECT_EQ(wire::presence_of(effort_reports[0]), field::kPropulsiveLinearX);

  deliver(kOcuB, msg::QueryDiscreteDevices{{0x04}});  // gear only
  const auto devices = reports_to<msg::ReportDiscreteDevices>(kOcuB);
  ASSERT_EQ(devices.size(), 1u);
  EXPECT_EQ(wire::presence_of(devices[0]), 0x04u);
  EXPECT_EQ(devices[0].gear, 1);

  deliver(kOcuB, msg::QueryPlatformSpecifications{{0xFFFFFFFF}});
  const auto specs = reports_to<msg::ReportPlatformSpecifications>(kOcuB);
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_EQ(specs[0].mobility_platform_name, "a very long pla");  // the field holds 15 characters
  EXPECT_NEAR(*specs[0].front_m, 0.5, 0.001);
  EXPECT_NEAR(*specs[0].wheel_base_m, 0.6, 0.001);
  EXPECT_NEAR(*specs[0].max_velocity_x_mps, 1.5, 0.001);
  EXPECT_FALSE(specs[0].back_m);  // unknown stays absent

  deliver(kOcuB, msg::QueryPlatformOperationalData{{0xFF}});
  const auto data = reports_to<msg::ReportPlatformOperationalData>(kOcuB);
  ASSERT_EQ(data.size(), 1u);
  EXPECT_EQ(data[0].odometer_m, 1234u);  // whole metres
  EXPECT_NEAR(*data[0].battery_voltage_percent, 87, 0.5);
  EXPECT_FALSE(data[0].engine_temperature_c);
  EXPECT_FALSE(data[0].fuel_level_percent);
}

TEST_F(PrimitiveDriverTest, DiscreteDevicesFromTheControllerReachTheDrive) {
  take_control(kOcuA);
  msg::SetDiscreteDevices m;
  m.parking_brake_and_horn = 0x03;  // brake set, horn on
  m.gear = 129;                     // first reverse gear
  deliver(kOcuA, m);
  ASSERT_EQ(drive.device_commands.size(), 1u);
  EXPECT_EQ(drive.state.parking_brake, true);
  EXPECT_EQ(drive.state.horn, true);
  EXPECT_EQ(drive.state.gear, 129);
  EXPECT_EQ(drive.state.main_power, true);  // not named: unchanged

  deliver(kOcuB, msg::QueryDiscreteDevices{{0xFF}});
  const auto reports = reports_to<msg::ReportDiscreteDevices>(kOcuB);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].main_propulsion, 0x01);
  EXPECT_EQ(reports[0].parking_brake_and_horn, 0x03);
  EXPECT_EQ(reports[0].gear, 129);
  EXPECT_FALSE(reports[0].transfer_case);
}

TEST_F(PrimitiveDriverTest, CommandsFromANonControllerOrOutsideReadyNeverReachTheDrive) {
  effort(kOcuA, 50);  // nobody has control
  deliver(kOcuA, msg::SetDiscreteDevices{{std::nullopt, 0x02, std::nullopt, std::nullopt}});
  take_control(kOcuA);
  effort(kOcuB, 50);  // not the controller
  EXPECT_TRUE(drive.efforts.empty());
  EXPECT_TRUE(drive.device_commands.empty());
  EXPECT_EQ(driver->counters().refused_not_controller, 3u);

  deliver(kOcuA, msg::Standby{});
  effort(kOcuA, 50);  // the controller, but in Standby
  EXPECT_TRUE(drive.efforts.empty());
  EXPECT_EQ(driver->counters().refused_wrong_state, 1u);
}

TEST_F(PrimitiveDriverTest, EveryStopPathStopsTheDriveAndNothingResumesWithoutANewEffort) {
  take_control(kOcuA);
  expect_stop_and_no_resume(
      "standby", [&] { deliver(kOcuA, msg::Standby{}); }, [&] { deliver(kOcuA, msg::Resume{}); });
  ASSERT_EQ(driver->state(), msg::PrimaryStatus::ready);

  expect_stop_and_no_resume(
      "emergency", [&] { deliver(kOcuB, msg::SetEmergency{{1}}); }, [&] { deliver(kOcuB, msg::ClearEmergency{{1}}); });
  ASSERT_EQ(driver->state(), msg::PrimaryStatus::ready);

  expect_stop_and_no_resume(
      "reset", [&] { deliver(kOcuA, msg::Reset{}); }, [&] { take_control(kOcuA); });
  ASSERT_EQ(driver->state(), msg::PrimaryStatus::ready);
  take_control(kOcuA);

  expect_stop_and_no_resume(
      "control released", [&] { deliver(kOcuA, msg::ReleaseComponentControl{}); }, [&] { take_control(kOcuA); });

  expect_stop_and_no_resume(
      "control taken over", [&] { take_control(kOcuB, 9); },
      [&] {
        deliver(kOcuB, msg::ReleaseComponentControl{});
        take_control(kOcuA);
      });

  expect_stop_and_no_resume(
      "command timeout", [&] { time.advance(600ms); }, [] {});
  EXPECT_EQ(driver->driver_counters().command_timeouts, 1u);

  expect_stop_and_no_resume(
      "drive fault (Failure)", [&] { drive.fault("link to the platform lost"); },
      [&] { drive.fault(std::nullopt); });
  ASSERT_EQ(driver->state(), msg::PrimaryStatus::ready);

  expect_stop_and_no_resume(
      "shutdown", [&] { deliver(kOcuA, msg::Shutdown{}); }, [] {});
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::shutdown);
}

TEST_F(PrimitiveDriverTest, ADriveFaultIsAFailureUntilItClearsEvenAcrossAnEmergency) {
  take_control(kOcuA);
  drive.fault("motor controller tripped");
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::failure);
  effort(kOcuA, 50);
  EXPECT_TRUE(drive.efforts.empty());  // refused in Failure

  // A fault that clears during an Emergency: back to Failure, then Ready at once.
  deliver(kOcuB, msg::SetEmergency{{1}});
  drive.fault(std::nullopt);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
  deliver(kOcuB, msg::ClearEmergency{{1}});
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);

  // A fault that appears during an Emergency: Failure once the emergency clears, never Ready.
  deliver(kOcuB, msg::SetEmergency{{1}});
  drive.fault("link to the platform lost");
  deliver(kOcuB, msg::ClearEmergency{{1}});
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::failure);
  drive.fault(std::nullopt);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_TRUE(drive.efforts.empty());
}

TEST_F(PrimitiveDriverTest, ControllerSilenceStopsTheDrive) {
  components::PrimitiveDriverOptions options;
  options.command_timeout = rt::Duration::zero();  // only the controller's liveness is at work
  make(options);
  take_control(kOcuA);
  effort(kOcuA, 60);
  time.advance(2s);
  EXPECT_TRUE(drive.propelling());  // no command timeout configured
  time.advance(2s);                // 4 s of silence from the controller > 3 s timeout
  EXPECT_FALSE(driver->control().is_controller(kOcuA));
  ASSERT_FALSE(drive.stops.empty());
  EXPECT_FALSE(drive.propelling());
}

TEST_F(PrimitiveDriverTest, CommandTimeoutRunsFromTheLastEffort) {
  take_control(kOcuA);
  for (int i = 0; i < 10; ++i) {
    effort(kOcuA, 40);
    time.advance(400ms);  // under the 0.5 s timeout each time
  }
  EXPECT_TRUE(drive.stops.empty());
  EXPECT_TRUE(drive.propelling());
  time.advance(150ms);  // 0.55 s since the last effort
  ASSERT_EQ(drive.stops.size(), 1u);
  EXPECT_FALSE(drive.propelling());
  EXPECT_TRUE(driver->control().is_controller(kOcuA));  // control is kept: the next effort drives again
  effort(kOcuA, 40);
  EXPECT_TRUE(drive.propelling());
}

// Issue 27, failure 2: the drive's report already says zero when the timeout
// fires; the stop (with the brake) is written all the same.
TEST_F(PrimitiveDriverTest, CommandTimeoutStopsADriveThatAlreadyReportsZero) {
  take_control(kOcuA);
  effort(kOcuA, 60);
  time.advance(450ms);
  drive.forget_applied();
  time.advance(100ms);
  ASSERT_EQ(drive.stops.size(), 1u);
  EXPECT_EQ(drive.stops.back(), 100);  // stop_brake_percent
}

// Issue 28: every stop a controller can cause in a loop (release, Standby,
// Emergency) stops the drive every time, and writes "drive stopped" only up
// to the burst per 10 s window, the rest counted; so do a Reset loop's
// failure and initialisation lines.
TEST_F(PrimitiveDriverTest, AControllerLoopingStopsWritesABoundedLogAndEveryStopStillStops) {
  logs.clear();
  for (int i = 0; i < 1000; ++i) {
    take_control(kOcuA);
    deliver(kOcuA, msg::Standby{});
    deliver(kOcuA, msg::Resume{});
    deliver(kOcuA, msg::SetEmergency{{1}});
    deliver(kOcuA, msg::ClearEmergency{{1}});
    deliver(kOcuA, msg::ReleaseComponentControl{});
  }
  EXPECT_GE(drive.stops.size(), 3000u);  // the limiter leaves out lines, never stops
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_TRUE(any_line_contains(logs, "drive stopped: entered Standby"));
  EXPECT_TRUE(any_line_contains(logs, "drive stopped: entered Emergency"));
  EXPECT_LE(logs.size(), 40u);  // 6000 messages
  time.advance(10s);
  EXPECT_TRUE(any_line_contains(logs, "left out in the last 10 s: "));
  EXPECT_TRUE(any_line_contains(logs, "x drive stops"));

  // A faulted drive Reset in a loop: each Reset waits for the drive again.
  take_control(kOcuA);
  logs.clear();
  for (int i = 0; i < 1000; ++i) {
    drive.fault("motor controller tripped");
    ASSERT_EQ(driver->state(), msg::PrimaryStatus::failure);
    deliver(kOcuA, msg::Reset{});
    ASSERT_EQ(driver->state(), msg::PrimaryStatus::initialize);
    drive.fault(std::nullopt);
    ASSERT_EQ(driver->state(), msg::PrimaryStatus::ready);
  }
  EXPECT_TRUE(any_line_contains(logs, "failure: drive fault: motor controller tripped"));
  EXPECT_TRUE(any_line_contains(logs, "initialising: waiting for the drive (motor controller tripped)"));
  EXPECT_TRUE(any_line_contains(logs, "hardware ready: initialised"));
  EXPECT_LE(logs.size(), 40u);
  time.advance(10s);
  for (const char* kind : {"x failures", "x initialisations waiting for the hardware", "x hardware ready"})
    EXPECT_TRUE(any_line_contains(logs, kind)) << kind;
}

TEST_F(PrimitiveDriverTest, ADriveNotHeardFromYetKeepsTheDriverInInitialize) {
  drive.fault("no data from the platform yet");
  make();
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::initialize);
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  effort(kOcuA, 50);
  EXPECT_TRUE(drive.efforts.empty());  // nothing moves in Initialize
  drive.fault(std::nullopt);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_TRUE(drive.efforts.empty());  // and nothing resumes by itself
}

TEST_F(PrimitiveDriverTest, StandbySurvivesADriveFault) {
  take_control(kOcuA);
  deliver(kOcuB, msg::Standby{});
  drive.fault("link to the platform lost");
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::failure);
  drive.fault(std::nullopt);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::standby);
  effort(kOcuA, 50);
  EXPECT_TRUE(drive.efforts.empty());
}

TEST_F(PrimitiveDriverTest, CommandServiceConnectionDeadmanStopsTheDrive) {
  components::PrimitiveDriverOptions options;
  options.command_timeout = rt::Duration::zero();
  make(options);
  take_control(kOcuA);
  deliver(kOcuA, msg::CreateServiceConnection{{msg::SetWrenchEffort::code, 10, 0}});
  for (int i = 0; i < 5; ++i) {
    effort(kOcuA, 30);
    time.advance(100ms);
  }
  EXPECT_TRUE(drive.propelling());
  time.advance(500ms);  // 3 periods of 0.1 s without the command
  EXPECT_FALSE(drive.propelling());
  ASSERT_FALSE(drive.stops.empty());
}

TEST_F(PrimitiveDriverTest, ServicesListWhatItAcceptsAndProvides) {
  const auto entry = driver->service_entry();
  EXPECT_EQ(entry.type, 33);
  std::map<std::uint16_t, std::uint32_t> inputs, outputs;
  for (const auto& i : entry.inputs) inputs[i.command_code] = i.presence_vector;
  for (const auto& o : entry.outputs) outputs[o.command_code] = o.presence_vector;
  for (std::uint16_t code : {0x0405, 0x0406, 0x2400, 0x2401, 0x2405, 0x2406}) EXPECT_TRUE(inputs.contains(code)) << code;
  EXPECT_EQ(inputs.at(0x0405), field::kPropulsiveLinearX | field::kPropulsiveRotationalZ | field::kResistiveLinearX);
  EXPECT_EQ(inputs.at(0x0406), 0x07u);
  EXPECT_EQ(outputs.at(0x4405), field::kPropulsiveLinearX | field::kPropulsiveRotationalZ | field::kResistiveLinearX);
  EXPECT_EQ(outputs.at(0x4406), 0x07u);
  EXPECT_EQ(outputs.at(0x4401), 0x06u);  // odometer and battery
  EXPECT_TRUE(outputs.contains(0x4400));
}

TEST_F(PrimitiveDriverTest, WrenchEffortStreamsOnAServiceConnection) {
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportWrenchEffort::code, 10, 0x0001}});
  time.advance(1s);
  const auto reports = reports_to<msg::ReportWrenchEffort>(kOcuB);
  EXPECT_GE(reports.size(), 10u);
  for (const auto& r : reports) EXPECT_EQ(wire::presence_of(r), 0x0001u);
}

}  // namespace
}  // namespace jaus::test
