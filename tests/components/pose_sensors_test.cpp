// The global pose sensor and the velocity state sensor, with what they share
// (sensor_component.hpp): presence ANDed with what the sample has, the
// sample's own time stamp, service connections capped at the source's rate,
// and staleness -> Failure -> Ready.
#include <map>
#include <set>

#include "harness.hpp"
#include "jaus/components/global_pose_sensor.hpp"
#include "jaus/components/velocity_state_sensor.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using components::PoseSample;
using rt::PrimaryStatus;

const Address kPoseSensor{1, 1, 38, 1};
const Address kVelocitySensor{1, 1, 42, 1};

// 2024-05-17 13:45:12.345 UTC at virtual time zero.
const rt::UtcTime kUtcOrigin =
    rt::UtcTime{std::chrono::sys_days{std::chrono::year{2024} / 5 / 17}.time_since_epoch()} + 13h + 45min + 12s + 345ms;

// Presence bits of the three reports (Part 3: bit 0 = field 2 ... bit 8 = time stamp).
constexpr std::uint32_t kAllFields = 0x1FF;
constexpr std::uint32_t kPositionFields = 0x00F;  // latitude/x .. position RMS
constexpr std::uint32_t kAttitudeFields = 0x0F0;  // roll .. attitude RMS (velocity: roll rate .. rate RMS)
constexpr std::uint32_t kTimeStamp = 0x100;

class FakeSource final : public components::PoseSource {
 public:
  std::optional<PoseSample> sample() override { return current; }
  double update_rate_hz() const override { return rate_hz; }
  std::optional<PoseSample> current;
  double rate_hz = 50;
};

template <class Report>
std::uint32_t presence(const Report& report) {
  return wire::presence_of(static_cast<const typename Report::body_type&>(report));
}

class PoseSensorTest : public ::testing::Test {
 protected:
  PoseSensorTest() : time(kUtcOrigin) {
    outbox.clock = &time;
    source.current = full_sample();
  }

  // A sample taken now with every field.
  PoseSample full_sample() const {
    PoseSample s;
    s.taken_at = time.now();
    s.taken_utc = time.utc_now();
    s.position = components::GeoPosition{45.5, -73.6, 120.25};
    s.local_position = components::LocalPosition{10.5, -3.25, 0.5};
    s.position_rms_m = 0.75;
    s.attitude = components::EulerAngles{0.05, -0.1, 1.25};
    s.attitude_rms_rad = 0.02;
    s.velocity_mps = components::Axes{1.5, 0.1, -0.2};
    s.velocity_rms_mps = 0.05;
    s.rates_rps = components::Axes{0.01, -0.02, 0.3};
    s.rate_rms_rps = 0.01;
    return s;
  }
  // The source produces a new sample now.
  void refresh() {
    PoseSample s = source.current.value_or(full_sample());
    s.taken_at = time.now();
    s.taken_utc = time.utc_now();
    source.current = s;
  }

  rt::Environment environment() {
    return rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& line) { logs.push_back(line); }};
  }
  rt::ComponentConfig config(const std::string& name, const Address& address) {
    rt::ComponentConfig c;
    c.name = name;
    c.address = address;
    return c;
  }
  components::GlobalPoseSensor& make_pose(components::GlobalPoseSensorOptions options = {}) {
    pose = std::make_unique<components::GlobalPoseSensor>(config("global pose sensor", kPoseSensor), environment(),
                                                          source, options);
    pose->start();
    time.run_ready();  // the first staleness check
    return *pose;
  }
  components::VelocityStateSensor& make_velocity(components::SensorOptions options = {}) {
    velocity = std::make_unique<components::VelocityStateSensor>(config("velocity state sensor", kVelocitySensor),
                                                                 environment(), source, options);
    velocity->start();
    time.run_ready();
    return *velocity;
  }

  template <class M>
  void deliver(rt::Component& to, const Address& from, const M& message) {
    deliver_to(to, time, from, message);
  }

  // The one report answering `query`, sent by `to` to kOcuA.
  template <class Report, class Query>
  std::optional<Report> ask(rt::Component& to, std::uint16_t presence_vector) {
    outbox.clear();
    deliver(to, kOcuA, Query{{presence_vector}});
    const auto reports = outbox.to<Report>(kOcuA);
    if (reports.size() != 1) return std::nullopt;
    return reports.front();
  }
  std::optional<msg::ReportGlobalPose> ask_global_pose(std::uint16_t pv = 0xFFFF) {
    return ask<msg::ReportGlobalPose, msg::QueryGlobalPose>(*pose, pv);
  }
  std::optional<msg::ReportVelocityState> ask_velocity(std::uint16_t pv = 0xFFFF) {
    return ask<msg::ReportVelocityState, msg::QueryVelocityState>(*velocity, pv);
  }

  // The primary status Report Component Status gives.
  PrimaryStatus reported_status(rt::Component& of) {
    outbox.clear();
    deliver(of, kOcuA, msg::QueryComponentStatus{});
    const auto reports = outbox.to<msg::ReportComponentStatus>(kOcuA);
    EXPECT_EQ(reports.size(), 1u);
    return reports.empty() ? PrimaryStatus::initialize : static_cast<PrimaryStatus>(reports.back().primary_status);
  }

  // Reports M sent to kOcuA on a service connection since the last clear().
  template <class M>
  std::vector<M> sc_reports() const {
    std::vector<M> out;
    for (const auto& s : outbox.sent)
      if (s.header.command_code == M::code && s.header.destination == kOcuA && s.header.service_connection) {
        auto decoded = wire::decode_payload<M>(s.payload);
        EXPECT_TRUE(decoded);
        if (decoded) out.push_back(*decoded);
      }
    return out;
  }

  bool logged(const std::string& text) const { return any_line_contains(logs, text); }

  // What a component without services of its own lists (the core messages).
  msg::ServiceEntry core_services(const Address& address) {
    rt::Component bare(config("bare", address), environment());
    return bare.service_entry();
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  FakeSource source;
  std::vector<std::string> logs;
  std::unique_ptr<components::GlobalPoseSensor> pose;
  std::unique_ptr<components::VelocityStateSensor> velocity;
};

// ---- presence and values -------------------------------------------------------

TEST_F(PoseSensorTest, GlobalPoseCarriesTheSamplesValuesAndItsTimeStamp) {
  make_pose();
  time.advance(400ms);  // reported later than taken: the time stamp stays the sample's
  const auto report = ask_global_pose();
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kAllFields);
  EXPECT_NEAR(*report->latitude_deg, 45.5, 1e-6);
  EXPECT_NEAR(*report->longitude_deg, -73.6, 1e-6);
  EXPECT_NEAR(*report->elevation_m, 120.25, 1e-4);
  EXPECT_NEAR(*report->position_rms_m, 0.75, 1e-6);
  EXPECT_NEAR(*report->roll_rad, 0.05, 1e-3);
  EXPECT_NEAR(*report->pitch_rad, -0.1, 1e-3);
  EXPECT_NEAR(*report->yaw_rad, 1.25, 1e-3);
  EXPECT_NEAR(*report->attitude_rms_rad, 0.02, 1e-4);
  EXPECT_EQ(*report->time_stamp, (TimeStamp{345, 12, 45, 13, 17}));
}

TEST_F(PoseSensorTest, GlobalPoseLeavesOutWhatTheCurrentSampleLacks) {
  make_pose();
  source.current->attitude.reset();
  source.current->attitude_rms_rad.reset();
  const auto report = ask_global_pose(0xFFFF);
  ASSERT_TRUE(report);
  // Asked for everything: the attitude bits are absent, not echoed.
  EXPECT_EQ(presence(*report), kPositionFields | kTimeStamp);
  EXPECT_FALSE(report->yaw_rad);
}

TEST_F(PoseSensorTest, ASourceWithoutAttitudeNeverReportsOne) {
  source.current->attitude.reset();
  source.current->attitude_rms_rad.reset();
  make_pose();
  const auto report = ask_global_pose(0xFFFF);
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kPositionFields | kTimeStamp);
}

TEST_F(PoseSensorTest, GlobalPoseGivesOnlyTheFieldsAsked) {
  make_pose();
  const auto latitude = ask_global_pose(0x0001);
  ASSERT_TRUE(latitude);
  EXPECT_EQ(presence(*latitude), 0x001u);
  EXPECT_NEAR(*latitude->latitude_deg, 45.5, 1e-6);
  const auto stamp_and_yaw = ask_global_pose(0x0140);
  ASSERT_TRUE(stamp_and_yaw);
  EXPECT_EQ(presence(*stamp_and_yaw), 0x140u);
}

TEST_F(PoseSensorTest, AnRmsIsNeverReportedWithoutItsValue) {
  make_pose();
  source.current->position.reset();  // a local-only source still has its position RMS
  const auto report = ask_global_pose();
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kAttitudeFields | kTimeStamp);
}

// A report with presence vector 0 says "nothing known yet"; silence would pass for a lost component.
TEST_F(PoseSensorTest, WithoutASampleAQueryGetsAnEmptyReport) {
  source.current.reset();
  make_pose();
  make_velocity();
  const auto pose_report = ask_global_pose();
  ASSERT_TRUE(pose_report);
  EXPECT_EQ(presence(*pose_report), 0u);
  const auto velocity_report = ask_velocity();
  ASSERT_TRUE(velocity_report);
  EXPECT_EQ(presence(*velocity_report), 0u);
}

TEST_F(PoseSensorTest, LocalPoseFromTheSourcesLocalFrame) {
  make_pose();
  ASSERT_TRUE(pose->serves_local_pose());
  time.advance(100ms);
  const auto report = ask<msg::ReportLocalPose, msg::QueryLocalPose>(*pose, 0xFFFF);
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kAllFields);
  EXPECT_NEAR(*report->x_m, 10.5, 1e-3);
  EXPECT_NEAR(*report->y_m, -3.25, 1e-3);
  EXPECT_NEAR(*report->z_m, 0.5, 1e-3);
  EXPECT_NEAR(*report->yaw_rad, 1.25, 1e-3);
  EXPECT_EQ(*report->time_stamp, (TimeStamp{345, 12, 45, 13, 17}));

  const auto only_x = ask<msg::ReportLocalPose, msg::QueryLocalPose>(*pose, 0x0001);
  ASSERT_TRUE(only_x);
  EXPECT_EQ(presence(*only_x), 0x001u);
}

TEST_F(PoseSensorTest, LocalPoseIsUnsupportedWhenTurnedOff) {
  make_pose({{}, /*local_pose=*/false});
  EXPECT_FALSE(pose->serves_local_pose());
  EXPECT_FALSE((ask<msg::ReportLocalPose, msg::QueryLocalPose>(*pose, 0xFFFF)));
  EXPECT_EQ(pose->counters().unsupported, 1u);
}

TEST_F(PoseSensorTest, LocalPoseIsUnsupportedWhenTheSourceHasNoLocalFrame) {
  source.current->local_position.reset();
  make_pose();
  EXPECT_FALSE(pose->serves_local_pose());
  EXPECT_FALSE((ask<msg::ReportLocalPose, msg::QueryLocalPose>(*pose, 0xFFFF)));
  EXPECT_EQ(pose->counters().unsupported, 1u);
}

TEST_F(PoseSensorTest, VelocityStateCarriesTheSamplesValuesAndItsTimeStamp) {
  make_velocity();
  time.advance(250ms);
  const auto report = ask_velocity();
  ASSERT_TRUE(report);
  EXPECT_EQ(presence(*report), kAllFields);
  EXPECT_NEAR(*report->velocity_x_mps, 1.5, 1e-4);
  EXPECT_NEAR(*report->velocity_y_mps, 0.1, 1e-4);
  EXPECT_NEAR(*report->velocity_z_mps, -0.2, 1e-4);
  EXPECT_NEAR(*report->velocity_rms_mps, 0.05, 1e-4);
  EXPECT_NEAR(*report->roll_rate_rps, 0.01, 2e-3);
  EXPECT_NEAR(*report->pitch_rate_rps, -0.02, 2e-3);
  EXPECT_NEAR(*report->yaw_rate_rps, 0.3, 2e-3);
  EXPECT_NEAR(*report->rate_rms_rps, 0.01, 1e-4);
  EXPECT_EQ(*report->time_stamp, (TimeStamp{345, 12, 45, 13, 17}));
}

TEST_F(PoseSensorTest, VelocityStateLeavesOutWhatTheSampleLacksAndWhatWasNotAsked) {
  make_velocity();
  source.current->rates_rps.reset();
  source.current->rate_rms_rps.reset();
  const auto all = ask_velocity(0xFFFF);
  ASSERT_TRUE(all);
  EXPECT_EQ(presence(*all), kPositionFields | kTimeStamp);  // velocity x .. velocity RMS, time stamp
  const auto yaw_rate = ask_velocity(0x0040);
  ASSERT_TRUE(yaw_rate);
  EXPECT_EQ(presence(*yaw_rate), 0u);  // asked only for what the source lacks
  const auto velocity_x = ask_velocity(0x0001);
  ASSERT_TRUE(velocity_x);
  EXPECT_EQ(presence(*velocity_x), 0x001u);
}

// ---- service connections ------------------------------------------------------

TEST_F(PoseSensorTest, ServiceConnectionsAreCappedAtTheSourcesRate) {
  source.rate_hz = 50;
  make_pose();
  make_velocity();
  const auto expect_capped = [&](rt::Component& sensor, std::uint16_t report_code) {
    outbox.clear();
    deliver(sensor, kOcuA, msg::CreateServiceConnection{{report_code, 1000, 0xFFFF}});
    const auto confirms = outbox.to<msg::ConfirmServiceConnection>(kOcuA);
    ASSERT_EQ(confirms.size(), 1u);
    EXPECT_EQ(confirms[0].response_code, 0);
    EXPECT_NEAR(confirms[0].confirmed_rate_hz, 50, 0.05);
  };
  expect_capped(*pose, msg::ReportGlobalPose::code);
  expect_capped(*pose, msg::ReportLocalPose::code);
  expect_capped(*velocity, msg::ReportVelocityState::code);
}

TEST_F(PoseSensorTest, ReportsArriveOnTheServiceConnectionWithTheAndedPresence) {
  source.rate_hz = 50;
  make_pose();
  outbox.clear();
  deliver(*pose, kOcuA, msg::CreateServiceConnection{{msg::ReportGlobalPose::code, 1000, 0x0103}});
  for (int i = 0; i < 10; ++i) {
    time.advance(20ms);
    refresh();
  }
  const auto reports = sc_reports<msg::ReportGlobalPose>();
  EXPECT_GE(reports.size(), 10u);  // the first at once, then one per 20 ms
  EXPECT_LE(reports.size(), 11u);
  for (const auto& r : reports) EXPECT_EQ(presence(r), 0x103u);

  // The source loses its position: the SC's reports leave it out.
  source.current->position.reset();
  outbox.clear();
  time.advance(40ms);
  const auto without_position = sc_reports<msg::ReportGlobalPose>();
  ASSERT_FALSE(without_position.empty());
  EXPECT_EQ(presence(without_position.back()), kTimeStamp);
}

TEST_F(PoseSensorTest, VelocityReportsArriveOnTheServiceConnection) {
  source.rate_hz = 20;
  make_velocity();
  outbox.clear();
  deliver(*velocity, kOcuA, msg::CreateServiceConnection{{msg::ReportVelocityState::code, 100, 0xFFFF}});
  time.advance(1s);
  const auto reports = sc_reports<msg::ReportVelocityState>();
  EXPECT_GE(reports.size(), 20u);
  EXPECT_LE(reports.size(), 21u);
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(presence(reports.back()), kAllFields);
}

// ---- Report Services ----------------------------------------------------------

std::set<std::uint16_t> codes(const std::vector<msg::ServiceMessageEntry>& entries) {
  std::set<std::uint16_t> out;
  for (const auto& e : entries) out.insert(e.command_code);
  return out;
}

std::map<std::uint16_t, std::uint32_t> presences(const std::vector<msg::ServiceMessageEntry>& entries) {
  std::map<std::uint16_t, std::uint32_t> out;
  for (const auto& e : entries) out[e.command_code] = e.presence_vector;
  return out;
}

class ReportServicesTest : public PoseSensorTest {
 protected:
  msg::ServiceEntry services_of(rt::Component& component) {
    outbox.clear();
    deliver(component, kOcuA, msg::QueryServices{});
    const auto reports = outbox.to<msg::ReportServices>(kOcuA);
    EXPECT_EQ(reports.size(), 1u);
    EXPECT_EQ(reports.empty() ? 0u : reports[0].services.size(), 1u);
    return reports.empty() || reports[0].services.empty() ? msg::ServiceEntry{} : reports[0].services[0];
  }
  // The core entries plus `inputs` and `outputs` (code -> presence vector).
  void expect_exactly(const msg::ServiceEntry& listed, const Address& address, std::set<std::uint16_t> inputs,
                      std::map<std::uint16_t, std::uint32_t> outputs) {
    const auto core = core_services(address);
    inputs.merge(codes(core.inputs));
    outputs.merge(presences(core.outputs));
    EXPECT_EQ(listed.type, address.component);
    EXPECT_EQ(codes(listed.inputs), inputs);
    EXPECT_EQ(presences(listed.outputs), outputs);
  }
};

TEST_F(ReportServicesTest, GlobalPoseSensorListsItsQueriesAndReports) {
  make_pose();
  expect_exactly(services_of(*pose), kPoseSensor, {msg::QueryGlobalPose::code, msg::QueryLocalPose::code},
                 {{msg::ReportGlobalPose::code, kAllFields}, {msg::ReportLocalPose::code, kAllFields}});
}

TEST_F(ReportServicesTest, WithoutLocalPoseNeitherItsQueryNorItsReportIsListed) {
  make_pose({{}, /*local_pose=*/false});
  expect_exactly(services_of(*pose), kPoseSensor, {msg::QueryGlobalPose::code},
                 {{msg::ReportGlobalPose::code, kAllFields}});
}

TEST_F(ReportServicesTest, TheListedPresenceVectorIsWhatTheSourceHas) {
  source.current->attitude.reset();
  source.current->attitude_rms_rad.reset();
  make_pose();
  expect_exactly(services_of(*pose), kPoseSensor, {msg::QueryGlobalPose::code, msg::QueryLocalPose::code},
                 {{msg::ReportGlobalPose::code, kPositionFields | kTimeStamp},
                  {msg::ReportLocalPose::code, kPositionFields | kTimeStamp}});
}

TEST_F(ReportServicesTest, VelocityStateSensorListsItsQueryAndReport) {
  make_velocity();
  expect_exactly(services_of(*velocity), kVelocitySensor, {msg::QueryVelocityState::code},
                 {{msg::ReportVelocityState::code, kAllFields}});
}

// ---- staleness ------------------------------------------------------------------

TEST_F(PoseSensorTest, AStaleSourceIsAFailureAndAFreshOneReadyAgain) {
  make_pose();  // stale_after 1 s
  ASSERT_EQ(pose->state(), PrimaryStatus::ready);
  time.advance(999ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
  EXPECT_EQ(reported_status(*pose), PrimaryStatus::ready);
  time.advance(1ms);  // the sample is now 1 s old
  EXPECT_EQ(pose->state(), PrimaryStatus::failure);
  EXPECT_EQ(reported_status(*pose), PrimaryStatus::failure);
  EXPECT_TRUE(pose->source_stale());

  refresh();
  time.advance(250ms);  // one check period
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
  EXPECT_EQ(reported_status(*pose), PrimaryStatus::ready);
}

TEST_F(PoseSensorTest, NeverReadyWhileStale) {
  make_velocity();
  for (int step = 0; step < 300; ++step) {
    time.advance(10ms);
    const bool stale = time.now() - source.current->taken_at >= 1s;
    if (stale) {
      ASSERT_EQ(velocity->state(), PrimaryStatus::failure) << "at " << step;
      ASSERT_EQ(reported_status(*velocity), PrimaryStatus::failure) << "at " << step;
    }
  }
  // A source that keeps updating is never declared stale.
  refresh();
  time.advance(250ms);
  ASSERT_EQ(velocity->state(), PrimaryStatus::ready);
  for (int step = 0; step < 300; ++step) {
    time.advance(20ms);
    refresh();
    ASSERT_EQ(velocity->state(), PrimaryStatus::ready) << "at " << step;
  }
}

// The RA's Initialize lasts until the source's first fresh sample: never
// Ready -> Failure -> Ready at start.
TEST_F(PoseSensorTest, WithoutAnySampleTheSensorWaitsInInitializeUntilTheFirst) {
  source.current.reset();
  make_pose();
  EXPECT_EQ(pose->state(), PrimaryStatus::initialize);
  EXPECT_TRUE(logged("initialising: waiting for a fresh sample from its pose source"));
  time.advance(2s);
  EXPECT_EQ(pose->state(), PrimaryStatus::initialize);  // not a failure: it never was Ready
  source.current = full_sample();
  time.advance(250ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
}

TEST_F(PoseSensorTest, TheFirstSampleDuringAnEmergencyEndsTheWaitOnceItClears) {
  source.current.reset();
  make_pose();
  deliver(*pose, kOcuA, msg::SetEmergency{});
  ASSERT_EQ(pose->state(), PrimaryStatus::emergency);
  source.current = full_sample();
  time.advance(250ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::emergency);
  deliver(*pose, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
}

TEST_F(PoseSensorTest, TheStaleAfterOptionSetsTheLimit) {
  make_velocity({200ms});
  time.advance(199ms);
  EXPECT_EQ(velocity->state(), PrimaryStatus::ready);
  time.advance(1ms);
  EXPECT_EQ(velocity->state(), PrimaryStatus::failure);
  EXPECT_TRUE(logged("pose source stale: last sample 0.200 s old"));
  refresh();
  time.advance(50ms);  // the period: 200 ms / 4
  EXPECT_EQ(velocity->state(), PrimaryStatus::ready);
}

// A fault returns to the state it interrupted: a Standby survives a stale source.
TEST_F(PoseSensorTest, StandbyThenStaleThenFreshIsStandbyAgain) {
  make_pose();
  deliver(*pose, kOcuA, msg::Standby{});
  ASSERT_EQ(pose->state(), PrimaryStatus::standby);
  time.advance(1s);
  EXPECT_EQ(pose->state(), PrimaryStatus::failure);
  deliver(*pose, kOcuA, msg::Resume{});  // not the controller, and Failure refuses Resume anyway
  EXPECT_EQ(pose->state(), PrimaryStatus::failure);
  refresh();
  time.advance(250ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::standby);
}

TEST_F(PoseSensorTest, AnEmergencyWhileStaleDoesNotGetStuck) {
  make_pose();
  time.advance(1s);
  ASSERT_EQ(pose->state(), PrimaryStatus::failure);
  deliver(*pose, kOcuA, msg::SetEmergency{});
  ASSERT_EQ(pose->state(), PrimaryStatus::emergency);
  refresh();
  time.advance(500ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::emergency);  // fresh again, but the emergency holds
  deliver(*pose, kOcuA, msg::ClearEmergency{});
  // Back to the failure the emergency interrupted, and out of it at once: the source is fresh.
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
}

TEST_F(PoseSensorTest, GoingStaleDuringAnEmergencyFailsOnceItClears) {
  make_pose();
  deliver(*pose, kOcuA, msg::SetEmergency{});
  time.advance(2s);
  EXPECT_EQ(pose->state(), PrimaryStatus::emergency);
  deliver(*pose, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(pose->state(), PrimaryStatus::failure);  // never Ready with a stale source, not even briefly
  refresh();
  time.advance(250ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
}

TEST_F(PoseSensorTest, AResetRestartsTheWatch) {
  make_pose();
  time.advance(1s);
  ASSERT_EQ(pose->state(), PrimaryStatus::failure);
  deliver(*pose, kOcuA, msg::RequestComponentControl{{255}});
  deliver(*pose, kOcuA, msg::Reset{});  // Initialize, waiting for a fresh sample
  EXPECT_EQ(pose->state(), PrimaryStatus::initialize);
  refresh();
  time.advance(250ms);
  EXPECT_EQ(pose->state(), PrimaryStatus::ready);
  EXPECT_EQ(time.pending(), 2u);  // one watch, and the controller's liveness check
}

TEST_F(PoseSensorTest, AfterShutdownTheWatchDoesNothing) {
  make_pose();
  pose->shutdown("node stopping");
  logs.clear();
  time.advance(5s);
  EXPECT_EQ(pose->state(), PrimaryStatus::shutdown);
  EXPECT_TRUE(logs.empty());
  EXPECT_EQ(time.pending(), 0u);  // the watch ended at its first call after Shutdown
}

TEST_F(PoseSensorTest, DestroyingTheSensorCancelsItsWatch) {
  make_pose();
  make_velocity();
  ASSERT_GT(time.pending(), 0u);
  pose.reset();
  velocity.reset();
  EXPECT_EQ(time.pending(), 0u);
}

}  // namespace
}  // namespace jaus::test
