// The local pose sensor (component 41): Report Local Pose from the simulated
// vehicle moving under virtual time, in the vehicle's local frame (origin at
// its start, x north, y east, z down); presence, a stale source, service
// connections, Report Services, and the kind (options, a source without a
// local frame). What every sensor shares is tested in pose_sensors_test.cpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "harness.hpp"
#include "jaus/components/global_pose_sensor.hpp"
#include "jaus/components/local_frame.hpp"
#include "jaus/components/local_pose_sensor.hpp"
#include "jaus/components/local_pose_sensor_kind.hpp"
#include "jaus/components/simulated_vehicle.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using components::PoseSample;
using rt::PrimaryStatus;
using std::numbers::pi;

const Address kLocalPoseSensor{1, 1, 41, 1};

// 2024-05-17 13:45:12.345 UTC at virtual time zero.
const rt::UtcTime kUtcOrigin =
    rt::UtcTime{std::chrono::sys_days{std::chrono::year{2024} / 5 / 17}.time_since_epoch()} + 13h + 45min + 12s + 345ms;

// Presence bits of Report Local Pose (Part 3: bit 0 x ... bit 3 position RMS,
// bit 4 roll ... bit 7 attitude RMS, bit 8 time stamp).
constexpr std::uint32_t kAllFields = 0x1FF;
constexpr std::uint32_t kPositionFields = 0x00F;
constexpr std::uint32_t kAttitudeFields = 0x0F0;
constexpr std::uint32_t kTimeStamp = 0x100;

template <class Report>
std::uint32_t presence(const Report& report) {
  return wire::presence_of(static_cast<const typename Report::body_type&>(report));
}

components::WrenchEffort effort(double linear, double turn = 0) {
  components::WrenchEffort e;
  e.propulsive_linear.x = linear;
  e.propulsive_rotational.z = turn;
  return e;
}

// A vehicle that does not start at the default datum, nor facing north:
// the local frame's origin is its start, its axes north and east whatever
// the vehicle's heading.
components::SimulatedVehicleConfig vehicle_config() {
  components::SimulatedVehicleConfig c;
  c.start = components::GeoPosition{47.25, 8.5, 420.0};
  c.start_heading_rad = pi / 2;  // facing east
  return c;
}

class LocalPoseSensorTest : public ::testing::Test {
 protected:
  LocalPoseSensorTest() : time(kUtcOrigin) { outbox.clock = &time; }

  rt::Environment environment() {
    return rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& line) { logs.push_back(line); }};
  }
  rt::ComponentConfig config(const Address& address) {
    rt::ComponentConfig c;
    c.name = "local pose sensor";
    c.address = address;
    return c;
  }
  components::LocalPoseSensor& make(components::SensorOptions options = {}) {
    sensor = std::make_unique<components::LocalPoseSensor>(config(kLocalPoseSensor), environment(), vehicle, options);
    sensor->start();
    time.run_ready();  // the first staleness check
    return *sensor;
  }

  template <class M>
  void deliver(const M& message) {
    deliver_to(*sensor, time, kOcuA, message);
  }

  std::optional<msg::ReportLocalPose> ask(std::uint16_t presence_vector = 0xFFFF) {
    outbox.clear();
    deliver(msg::QueryLocalPose{{presence_vector}});
    const auto reports = outbox.to<msg::ReportLocalPose>(kOcuA);
    if (reports.size() != 1) return std::nullopt;
    return reports.front();
  }

  PrimaryStatus reported_status() {
    outbox.clear();
    deliver(msg::QueryComponentStatus{});
    const auto reports = outbox.to<msg::ReportComponentStatus>(kOcuA);
    EXPECT_EQ(reports.size(), 1u);
    return reports.empty() ? PrimaryStatus::initialize : static_cast<PrimaryStatus>(reports.back().primary_status);
  }

  std::vector<msg::ReportLocalPose> sc_reports() const {
    std::vector<msg::ReportLocalPose> out;
    for (const auto& s : outbox.sent)
      if (s.header.command_code == msg::ReportLocalPose::code && s.header.destination == kOcuA &&
          s.header.service_connection) {
        auto decoded = wire::decode_payload<msg::ReportLocalPose>(s.payload);
        EXPECT_TRUE(decoded);
        if (decoded) out.push_back(*decoded);
      }
    return out;
  }

  // The report agrees with the vehicle's own sample now: x, y, z in its
  // local frame, yaw its heading (within the wire's resolution).
  void expect_agrees_with_source(const msg::ReportLocalPose& report) {
    const auto sample = vehicle.sample();
    ASSERT_TRUE(sample && sample->local_position && sample->attitude);
    ASSERT_TRUE(report.x_m && report.y_m && report.z_m && report.yaw_rad);
    EXPECT_NEAR(*report.x_m, sample->local_position->x_m, 1e-3);
    EXPECT_NEAR(*report.y_m, sample->local_position->y_m, 1e-3);
    EXPECT_NEAR(*report.z_m, sample->local_position->z_m, 1e-3);
    EXPECT_NEAR(*report.yaw_rad, components::wrap_angle(sample->attitude->yaw), 1e-3);
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  components::SimulatedVehicle vehicle{vehicle_config(), time};
  std::unique_ptr<components::LocalPoseSensor> sensor;
};

// ---- the simulated vehicle moving --------------------------------------------

TEST_F(LocalPoseSensorTest, AtTheStartTheVehicleIsAtTheOriginFacingItsStartHeading) {
  make();
  ASSERT_EQ(sensor->state(), PrimaryStatus::ready);
  const auto report = ask();
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kAllFields);
  EXPECT_NEAR(*report->x_m, 0, 1e-3);
  EXPECT_NEAR(*report->y_m, 0, 1e-3);
  EXPECT_NEAR(*report->z_m, 0, 1e-3);
  EXPECT_NEAR(*report->yaw_rad, pi / 2, 1e-3);
  EXPECT_NEAR(*report->roll_rad, 0, 1e-3);
  EXPECT_NEAR(*report->pitch_rad, 0, 1e-3);
  EXPECT_EQ(*report->time_stamp, (TimeStamp{345, 12, 45, 13, 17}));
}

TEST_F(LocalPoseSensorTest, DrivingEastThenTurningIsReportedInTheSourcesLocalFrame) {
  make();
  vehicle.apply_effort(effort(100));  // straight ahead: east
  for (int second = 0; second < 5; ++second) {
    time.advance(1s);
    const auto report = ask();
    ASSERT_TRUE(report);
    expect_agrees_with_source(*report);
  }
  // 0.5 m accelerating, then 4 s at 1 m/s: y east, x north unchanged.
  const auto east = ask();
  ASSERT_TRUE(east);
  EXPECT_NEAR(*east->y_m, 4.5, 0.05);
  EXPECT_NEAR(*east->x_m, 0, 1e-3);

  // Turning left (negative rotational z) while driving: yaw and x, y follow.
  vehicle.apply_effort(effort(100, -50));
  for (int step = 0; step < 20; ++step) {
    time.advance(250ms);
    const auto report = ask();
    ASSERT_TRUE(report);
    expect_agrees_with_source(*report);
  }
  const auto turned = ask();
  ASSERT_TRUE(turned);
  EXPECT_GT(*turned->x_m, 1.0);  // turned towards the north
  EXPECT_LT(*turned->yaw_rad, pi / 2 - 1.0);
}

// The origin is the source's datum: the local position reported and the
// vehicle's global position are the same point of LocalFrame at its start.
TEST_F(LocalPoseSensorTest, TheOriginIsTheSourcesDatum) {
  make();
  vehicle.apply_effort(effort(100, 30));
  time.advance(7s);
  const auto report = ask();
  ASSERT_TRUE(report);
  const components::LocalFrame frame(vehicle_config().start);
  const auto geo = frame.to_geo(components::LocalPosition{*report->x_m, *report->y_m, *report->z_m});
  const auto sample = vehicle.sample();
  ASSERT_TRUE(sample && sample->position);
  EXPECT_NEAR(geo.latitude_deg, sample->position->latitude_deg, 1e-7);
  EXPECT_NEAR(geo.longitude_deg, sample->position->longitude_deg, 1e-7);
  EXPECT_NEAR(geo.altitude_m, sample->position->altitude_m, 1e-2);
  EXPECT_GT(std::hypot(*report->x_m, *report->y_m), 3.0);
}

// The same sample makes the same Report Local Pose here and at the global
// pose sensor's `local_pose`: one frame, whichever component an OCU asks.
TEST_F(LocalPoseSensorTest, AgreesWithTheGlobalPoseSensorsLocalPose) {
  vehicle.apply_effort(effort(80, 20));
  time.advance(3s);
  const auto sample = vehicle.sample();
  ASSERT_TRUE(sample);
  const auto ours = components::LocalPoseSensor::local_pose(*sample);
  const auto theirs = components::GlobalPoseSensor::local_pose(*sample);
  EXPECT_EQ(presence(ours), presence(theirs));
  EXPECT_EQ(ours.x_m, theirs.x_m);
  EXPECT_EQ(ours.y_m, theirs.y_m);
  EXPECT_EQ(ours.z_m, theirs.z_m);
  EXPECT_EQ(ours.position_rms_m, theirs.position_rms_m);
  EXPECT_EQ(ours.yaw_rad, theirs.yaw_rad);
  EXPECT_EQ(ours.attitude_rms_rad, theirs.attitude_rms_rad);
  EXPECT_EQ(ours.time_stamp, theirs.time_stamp);
}

// ---- presence --------------------------------------------------------------------

TEST_F(LocalPoseSensorTest, AReportCarriesTheFieldsAskedThatTheSourceHas) {
  make();
  const auto x = ask(0x0001);
  ASSERT_TRUE(x);
  EXPECT_EQ(presence(*x), 0x001u);
  const auto yaw_and_stamp = ask(0x0140);
  ASSERT_TRUE(yaw_and_stamp);
  EXPECT_EQ(presence(*yaw_and_stamp), 0x140u);
  EXPECT_FALSE(yaw_and_stamp->x_m);
  const auto attitude = ask(kAttitudeFields);
  ASSERT_TRUE(attitude);
  EXPECT_EQ(presence(*attitude), kAttitudeFields);
  const auto none = ask(0);
  ASSERT_TRUE(none);
  EXPECT_EQ(presence(*none), 0u);
  // Asking for bits Part 3 does not define gets only the defined ones.
  const auto everything = ask(0xFFFF);
  ASSERT_TRUE(everything);
  EXPECT_EQ(presence(*everything), kAllFields);
}

class FakeSource final : public components::PoseSource {
 public:
  std::optional<PoseSample> sample() override { return current; }
  double update_rate_hz() const override { return 20; }
  std::optional<PoseSample> current;
};

TEST_F(LocalPoseSensorTest, FieldsTheSampleLacksAreLeftOutNotFilledIn) {
  FakeSource source;
  PoseSample s;
  s.taken_at = time.now();
  s.taken_utc = time.utc_now();
  s.local_position = components::LocalPosition{3, -4, 0.5};
  s.position_rms_m = 0.25;  // no attitude
  source.current = s;
  components::LocalPoseSensor without_attitude(config(kLocalPoseSensor), environment(), source);
  without_attitude.start();
  time.run_ready();
  outbox.clear();
  deliver_to(without_attitude, time, kOcuA, msg::QueryLocalPose{{0xFFFF}});
  auto reports = outbox.to<msg::ReportLocalPose>(kOcuA);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(presence(reports[0]), kPositionFields | kTimeStamp);
  EXPECT_NEAR(*reports[0].x_m, 3, 1e-3);
  EXPECT_NEAR(*reports[0].y_m, -4, 1e-3);

  // The position goes (a source that lost its frame): x, y, z and its RMS go with it.
  source.current->local_position.reset();
  source.current->attitude = components::EulerAngles{0, 0, 1};
  outbox.clear();
  deliver_to(without_attitude, time, kOcuA, msg::QueryLocalPose{{0xFFFF}});
  reports = outbox.to<msg::ReportLocalPose>(kOcuA);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(presence(reports[0]), kTimeStamp);  // attitude was not available at the start either
  const auto said = [&] {
    return std::count_if(logs.begin(), logs.end(), [](const std::string& line) {
      return line.find("its pose source gives no local position (vehicle.local_frame: false?)") != std::string::npos;
    });
  };
  EXPECT_EQ(said(), 1);
  deliver_to(without_attitude, time, kOcuA, msg::QueryLocalPose{{0xFFFF}});
  EXPECT_EQ(said(), 1);  // once
}

TEST_F(LocalPoseSensorTest, WithoutASampleAQueryGetsAnEmptyReportAndTheSensorInitialises) {
  FakeSource source;
  components::LocalPoseSensor waiting(config(kLocalPoseSensor), environment(), source);
  waiting.start();
  time.run_ready();
  EXPECT_EQ(waiting.state(), PrimaryStatus::initialize);
  outbox.clear();
  deliver_to(waiting, time, kOcuA, msg::QueryLocalPose{{0xFFFF}});
  const auto reports = outbox.to<msg::ReportLocalPose>(kOcuA);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(presence(reports[0]), 0u);
}

// ---- staleness --------------------------------------------------------------------

TEST_F(LocalPoseSensorTest, AFrozenSourceIsAFailureUntilItMovesOn) {
  make({500ms});
  vehicle.apply_effort(effort(100));
  time.advance(1s);
  ASSERT_EQ(sensor->state(), PrimaryStatus::ready);
  vehicle.freeze_samples(true);
  const auto frozen = ask();
  ASSERT_TRUE(frozen);
  time.advance(499ms);
  EXPECT_EQ(sensor->state(), PrimaryStatus::ready);
  time.advance(1ms);
  EXPECT_EQ(sensor->state(), PrimaryStatus::failure);
  EXPECT_EQ(reported_status(), PrimaryStatus::failure);
  // The last known pose, with its own (old) time stamp.
  const auto stale = ask();
  ASSERT_TRUE(stale);
  EXPECT_EQ(stale->x_m, frozen->x_m);
  EXPECT_EQ(stale->y_m, frozen->y_m);
  EXPECT_EQ(stale->time_stamp, frozen->time_stamp);

  vehicle.freeze_samples(false);
  time.advance(125ms);  // one check period: 500 ms / 4
  EXPECT_EQ(sensor->state(), PrimaryStatus::ready);
  const auto fresh = ask();
  ASSERT_TRUE(fresh);
  EXPECT_GT(*fresh->y_m, *frozen->y_m + 0.5);  // it drove on meanwhile
}

// ---- service connections and Report Services --------------------------------------

TEST_F(LocalPoseSensorTest, ServiceConnectionReportsFollowTheVehicleAtTheSourcesRate) {
  make();
  outbox.clear();
  deliver(msg::CreateServiceConnection{{msg::ReportLocalPose::code, 1000, 0x0143}});  // x, y, yaw, time stamp
  const auto confirms = outbox.to<msg::ConfirmServiceConnection>(kOcuA);
  ASSERT_EQ(confirms.size(), 1u);
  EXPECT_EQ(confirms[0].response_code, 0);
  EXPECT_NEAR(confirms[0].confirmed_rate_hz, 50, 0.05);  // the vehicle's update rate

  outbox.clear();
  vehicle.apply_effort(effort(100));
  time.advance(1s);
  const auto reports = sc_reports();
  EXPECT_GE(reports.size(), 49u);
  EXPECT_LE(reports.size(), 51u);
  ASSERT_FALSE(reports.empty());
  for (const auto& r : reports) EXPECT_EQ(presence(r), 0x143u);
  EXPECT_LT(*reports.front().y_m, *reports.back().y_m);  // moving east
  EXPECT_NEAR(*reports.back().y_m, vehicle.sample()->local_position->y_m, 0.03);

  // Terminated: no more reports.
  deliver(msg::TerminateServiceConnection{{msg::ReportLocalPose::code, confirms[0].instance_id}});
  outbox.clear();
  time.advance(500ms);
  EXPECT_TRUE(sc_reports().empty());
}

std::map<std::uint16_t, std::uint32_t> presences(const std::vector<msg::ServiceMessageEntry>& entries) {
  std::map<std::uint16_t, std::uint32_t> out;
  for (const auto& e : entries) out[e.command_code] = e.presence_vector;
  return out;
}

TEST_F(LocalPoseSensorTest, ReportServicesListsQueryAndReportLocalPoseOnly) {
  make();
  rt::Component bare(config(kLocalPoseSensor), environment());
  const auto core = bare.service_entry();
  outbox.clear();
  deliver(msg::QueryServices{});
  const auto reports = outbox.to<msg::ReportServices>(kOcuA);
  ASSERT_EQ(reports.size(), 1u);
  ASSERT_EQ(reports[0].services.size(), 1u);
  const auto& listed = reports[0].services[0];
  EXPECT_EQ(listed.type, 41);
  auto inputs = presences(core.inputs);
  inputs[msg::QueryLocalPose::code] = kAllFields;
  auto outputs = presences(core.outputs);
  outputs[msg::ReportLocalPose::code] = kAllFields;
  EXPECT_EQ(presences(listed.inputs), inputs);
  EXPECT_EQ(presences(listed.outputs), outputs);
  EXPECT_FALSE(presences(listed.inputs).contains(msg::QueryGlobalPose::code));
}

// ---- the kind --------------------------------------------------------------------

struct NoDirectory final : rt::NodeDirectory {
  std::vector<const rt::Component*> local_components() const override { return {}; }
  std::vector<Address> known_subsystems() const override { return {}; }
  bool hosts_component(std::uint8_t) const override { return false; }
};

class LocalPoseSensorKindTest : public LocalPoseSensorTest {
 protected:
  Expected<std::unique_ptr<rt::Component>> make_kind(components::PoseSource* source,
                                                     std::map<std::string, std::string> values = {}) {
    rt::Backends backends;
    if (source != nullptr) backends.offer<components::PoseSource>(source);
    const NoDirectory directory;
    const auto& kind = components::local_pose_sensor_kind();
    return kind.make(rt::KindContext{config(kLocalPoseSensor), environment(), directory,
                                     rt::KindOptions{kind.name, values}, backends});
  }
};

TEST_F(LocalPoseSensorKindTest, ItsNameIdOptionsAndNeeds) {
  const auto& kind = components::local_pose_sensor_kind();
  EXPECT_EQ(kind.name, "local_pose_sensor");
  EXPECT_EQ(kind.default_id, 41);
  EXPECT_EQ(kind.options, std::vector<std::string_view>{"stale_after_s"});
  EXPECT_EQ(kind.needs, std::vector<std::string_view>{components::PoseSource::kInterface});
  EXPECT_FALSE(kind.moves_hardware);
  const std::map<std::string, std::string> good{{"stale_after_s", "0.25"}};
  EXPECT_TRUE(kind.check(rt::KindOptions{kind.name, good}));
  const std::map<std::string, std::string> bad{{"stale_after_s", "0"}};
  const auto checked = kind.check(rt::KindOptions{kind.name, bad});
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().message(), "local_pose_sensor option 'stale_after_s' must be a number > 0 and <= 60, got '0'");
}

TEST_F(LocalPoseSensorKindTest, MadeOnTheVehicleWithItsOptions) {
  auto made = make_kind(&vehicle, {{"stale_after_s", "0.25"}});
  ASSERT_TRUE(made) << made.error().message();
  auto* sensor_made = dynamic_cast<components::LocalPoseSensor*>(made->get());
  ASSERT_NE(sensor_made, nullptr);
  EXPECT_EQ(sensor_made->sensor_options().stale_after, 250ms);
  EXPECT_EQ(sensor_made->address(), kLocalPoseSensor);
}

TEST_F(LocalPoseSensorKindTest, RefusesAHostWithoutAPoseSourceOrASourceWithoutALocalFrame) {
  const auto none = make_kind(nullptr);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().message(), "local_pose_sensor needs a vehicle pose source and the host has none");

  auto flat = vehicle_config();
  flat.local_frame = false;
  components::SimulatedVehicle global_only(flat, time);
  const auto refused = make_kind(&global_only);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message(),
            "local_pose_sensor needs a pose source with a local frame (vehicle.local_frame: true)");
}

}  // namespace
}  // namespace jaus::test
