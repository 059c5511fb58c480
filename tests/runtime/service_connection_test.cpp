// Service connections, provider side, under virtual time.
#include "harness.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

class ServiceConnectionTest : public ComponentTest {
 protected:
  msg::ConfirmServiceConnection create(const Address& from, std::uint16_t code, double rate, std::uint32_t pv) {
    outbox.clear();
    msg::CreateServiceConnection m;
    m.command_code = code;
    m.periodic_rate_hz = rate;
    m.presence_vector = pv;
    deliver(from, m);
    const auto confirms = outbox.to<msg::ConfirmServiceConnection>(from);
    EXPECT_EQ(confirms.size(), 1u);
    return confirms.empty() ? msg::ConfirmServiceConnection{} : confirms.back();
  }
  // Reports are scheduled from ideal times: no drift over 10,000 periods.
  void expect_exact_rate(double requested_hz) {
    const auto confirm = create(kOcuA, msg::ReportGlobalPose::code, requested_hz, 0x1FF);
    ASSERT_EQ(confirm.response_code, msg::sc_response::kCreated);
    const double rate = confirm.confirmed_rate_hz;
    const rt::TimePoint start = time.now();
    time.advance(std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(10'000.5 / rate)));
    const auto reports = reports_to(kOcuA);
    ASSERT_EQ(reports.size(), 10'001u);
    const double period_ns = 1e9 / rate;
    double worst_offset_ns = 0;
    for (std::size_t k = 0; k < reports.size(); ++k) {
      const double ideal = static_cast<double>(k) * period_ns;
      const double actual = static_cast<double>((reports[k].at - start).count());
      worst_offset_ns = std::max(worst_offset_ns, std::abs(actual - ideal));
    }
    const double mean_period_ns =
        static_cast<double>((reports.back().at - reports.front().at).count()) / static_cast<double>(reports.size() - 1);
    EXPECT_LT(std::abs(mean_period_ns - period_ns) / period_ns, 0.001);
    EXPECT_LE(worst_offset_ns, 1.0);  // rounding to the nanosecond, never accumulated
  }

  std::vector<Sent> reports_to(const Address& to) const {
    std::vector<Sent> out;
    for (const auto& s : outbox.sent)
      if (s.header.command_code == msg::ReportGlobalPose::code && s.header.destination == to) out.push_back(s);
    return out;
  }
};

TEST_F(ServiceConnectionTest, ReportsCarryTheFlagASequenceAndTheAndedPresenceVector) {
  const auto confirm = create(kOcuA, msg::ReportGlobalPose::code, 10, 0x0181);  // lat, att RMS, time
  EXPECT_EQ(confirm.response_code, msg::sc_response::kCreated);
  EXPECT_EQ(confirm.instance_id, 0);
  EXPECT_NEAR(confirm.confirmed_rate_hz, 10, 0.02);
  time.advance(1050ms);
  const auto reports = reports_to(kOcuA);
  ASSERT_EQ(reports.size(), 11u);  // at 0, 0.1, ..., 1.0 s (the rate travels quantised: 9.998 Hz)
  for (std::size_t i = 0; i < reports.size(); ++i) {
    EXPECT_TRUE(reports[i].header.service_connection);
    EXPECT_EQ(reports[i].header.sequence, i);
    auto pose = wire::decode_payload<msg::ReportGlobalPose>(reports[i].payload);
    ASSERT_TRUE(pose);
    // Requested 0x0181 AND available 0x017F = 0x0101: latitude and time stamp.
    EXPECT_EQ(wire::presence_of(*pose), 0x0101u);
  }
}

TEST_F(ServiceConnectionTest, EveryComponentServesItsStatus) {
  // What a controlling OCU watches (about 5 Hz): the status follows the component.
  ASSERT_EQ(create(kOcuA, msg::ReportComponentStatus::code, 5, 0).response_code, msg::sc_response::kCreated);
  time.advance(450ms);
  deliver(kOcuA, msg::Standby{});
  time.advance(400ms);
  std::vector<std::uint8_t> states;
  for (const auto& s : outbox.sent)
    if (s.header.command_code == msg::ReportComponentStatus::code && s.header.service_connection)
      states.push_back(wire::decode_payload<msg::ReportComponentStatus>(s.payload)->primary_status);
  ASSERT_EQ(states.size(), 5u);  // 0, 0.2, 0.4, 0.6, 0.8 s
  EXPECT_EQ(states.front(), static_cast<std::uint8_t>(msg::PrimaryStatus::ready));
  EXPECT_EQ(states.back(), static_cast<std::uint8_t>(msg::PrimaryStatus::standby));
}

TEST_F(ServiceConnectionTest, RefusesWhatItCannotServe) {
  EXPECT_EQ(create(kOcuA, msg::ReportVelocityState::code, 10, 0xFF).response_code,
            msg::sc_response::kCommandNotSupported);
  EXPECT_EQ(create(kOcuA, msg::ReportGlobalPose::code, 0, 0xFF).response_code, msg::sc_response::kInvalidParameters);
  // A command SC needs control.
  EXPECT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kInsufficientAuthority);
  EXPECT_EQ(driver->service_connections().active(), 0u);
}

TEST_F(ServiceConnectionTest, ConfirmedRateIsCappedByTheLimit) {
  rt::ComponentConfig config;
  config.address = kDriver;
  config.service_connections.max_rate_hz = 50;
  config.service_connections.max_connections = 1;
  TestDriver d(config, rt::Environment{time, time, outbox});
  d.start();
  outbox.clear();
  msg::CreateServiceConnection m;
  m.command_code = msg::ReportGlobalPose::code;
  m.periodic_rate_hz = 200;
  m.presence_vector = 0x1FF;
  Header h;
  h.command_code = m.code;
  h.source = kOcuA;
  h.destination = kDriver;
  std::vector<std::uint8_t> payload(16);
  const auto size = wire::encode_payload(m, payload);
  d.receive(h, std::span(payload).first(*size));
  EXPECT_NEAR(outbox.to<msg::ConfirmServiceConnection>(kOcuA).at(0).confirmed_rate_hz, 50, 0.02);
  h.source = kOcuB;  // a second SC is beyond the limit
  d.receive(h, std::span(payload).first(*size));
  EXPECT_EQ(outbox.to<msg::ConfirmServiceConnection>(kOcuB).at(0).response_code, msg::sc_response::kRefused);
}

// The reports of all connections together stay within the budget: a flood of
// Create Service Connection at the top rate cannot make a component spend
// its time on reports, most of them for spoofed requesters.
TEST_F(ServiceConnectionTest, AllConnectionsTogetherStayWithinTheTotalRate) {
  rt::ComponentConfig config;
  config.address = kDriver;
  config.service_connections.max_total_rate_hz = 100;
  TestDriver d(config, rt::Environment{time, time, outbox});
  d.start();
  auto create_at = [&](const Address& from, double rate_hz, std::uint32_t presence) {
    msg::CreateServiceConnection m;
    m.command_code = msg::ReportGlobalPose::code;
    m.periodic_rate_hz = rate_hz;
    m.presence_vector = presence;
    Header h;
    h.command_code = m.code;
    h.source = from;
    h.destination = kDriver;
    std::vector<std::uint8_t> payload(16);
    const auto size = wire::encode_payload(m, payload);
    outbox.clear();
    d.receive(h, std::span(payload).first(*size));
    return outbox.to<msg::ConfirmServiceConnection>(from).at(0);
  };
  EXPECT_NEAR(create_at(kOcuA, 60, 0x1FF).confirmed_rate_hz, 60, 0.02);
  EXPECT_NEAR(create_at(kOcuB, 60, 0x1FF).confirmed_rate_hz, 40, 0.02);  // what is left
  EXPECT_EQ(create_at(kOcuC, 10, 0x1FF).response_code, msg::sc_response::kRefused);
  // Asking again gives the connection's own rate back first.
  EXPECT_NEAR(create_at(kOcuA, 50, 0x1FF).confirmed_rate_hz, 50, 0.02);
  EXPECT_NEAR(create_at(kOcuC, 30, 0x1FF).confirmed_rate_hz, 10, 0.02);
  EXPECT_EQ(d.service_connections().active(), 3u);
  // 100 reports a second in all, whatever was asked.
  outbox.clear();
  time.advance(10s);
  EXPECT_NEAR(static_cast<double>(outbox.count<msg::ReportGlobalPose>()), 1000, 3);
}

TEST_F(ServiceConnectionTest, SameCodeAndPresenceShareAnInstance) {
  const auto a = create(kOcuA, msg::ReportGlobalPose::code, 5, 0x0003);
  const auto b = create(kOcuB, msg::ReportGlobalPose::code, 2, 0x0003);
  const auto c = create(kOcuC, msg::ReportGlobalPose::code, 2, 0x0007);
  EXPECT_EQ(a.instance_id, b.instance_id);
  EXPECT_NE(a.instance_id, c.instance_id);
  // A repeat Create from the same requester updates its SC rather than adding one.
  const auto again = create(kOcuA, msg::ReportGlobalPose::code, 1, 0x0003);
  EXPECT_EQ(again.instance_id, a.instance_id);
  EXPECT_EQ(driver->service_connections().active(), 3u);
}

TEST_F(ServiceConnectionTest, TerminateSuspendAndRequesterLossEndReports) {
  const auto a = create(kOcuA, msg::ReportGlobalPose::code, 10, 0x1FF);
  const auto b = create(kOcuB, msg::ReportGlobalPose::code, 10, 0x1FF);
  create(kOcuC, msg::ReportGlobalPose::code, 10, 0x1FF);
  deliver(kOcuA, msg::TerminateServiceConnection{{msg::ReportGlobalPose::code, a.instance_id}});
  deliver(kOcuB, msg::SuspendServiceConnection{{msg::ReportGlobalPose::code, b.instance_id}});
  driver->peer_lost(kOcuC);
  outbox.clear();
  time.advance(2s);
  EXPECT_TRUE(reports_to(kOcuA).empty());
  EXPECT_TRUE(reports_to(kOcuB).empty());
  EXPECT_TRUE(reports_to(kOcuC).empty());
  EXPECT_EQ(driver->service_connections().active(), 1u);  // B's, suspended
}

TEST_F(ServiceConnectionTest, ShutdownEndsEveryConnection) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  create(kOcuB, msg::ReportGlobalPose::code, 10, 0x1FF);
  deliver(kOcuA, msg::Shutdown{});
  EXPECT_EQ(driver->service_connections().active(), 0u);
  outbox.clear();
  time.advance(1s);
  EXPECT_TRUE(outbox.sent.empty());
}

TEST_F(ServiceConnectionTest, RateIsExactAt1092Hz) { expect_exact_rate(1092); }
TEST_F(ServiceConnectionTest, RateIsExactAtOneReportAMinute) { expect_exact_rate(0.0167); }

TEST_F(ServiceConnectionTest, CommandServiceConnectionIsADeadman) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  ASSERT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kCreated);
  // The controller commands at 10 Hz for a second: the platform moves.
  for (int i = 0; i < 10; ++i) {
    drive(kOcuA, 40);
    time.advance(100ms);
  }
  ASSERT_TRUE(driver->moving);
  // Commands stop (the last one 100 ms ago); the controller is otherwise alive.
  const auto stops_before = driver->stops.size();
  time.advance(150ms);  // 250 ms of silence: within 3 periods
  EXPECT_TRUE(driver->moving);
  time.advance(200ms);  // 450 ms: more than 3 periods
  EXPECT_FALSE(driver->moving);
  EXPECT_GT(driver->stops.size(), stops_before);
  EXPECT_TRUE(logged("loss of command"));
  EXPECT_EQ(driver->service_connections().counters().commands_lost, 1u);
}

TEST_F(ServiceConnectionTest, DeadmanWaitsAtMostTheMaximumWhateverTheRate) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  // One command a minute: three periods would be three minutes on the last command.
  ASSERT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 0.0167, 0).response_code, msg::sc_response::kCreated);
  drive(kOcuA, 40);
  ASSERT_TRUE(driver->moving);
  time.advance(900ms);
  EXPECT_TRUE(driver->moving);
  time.advance(200ms);  // past the 1 s maximum
  EXPECT_FALSE(driver->moving);
  EXPECT_EQ(driver->service_connections().counters().commands_lost, 1u);
}

TEST_F(ServiceConnectionTest, DeadmanWatchesAgainOnceCommandsResume) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  ASSERT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kCreated);
  drive(kOcuA, 40);
  time.advance(400ms);
  ASSERT_FALSE(driver->moving);
  drive(kOcuA, 30);  // resumed: moves again, and is watched again
  EXPECT_TRUE(driver->moving);
  EXPECT_TRUE(logged("resumed"));
  time.advance(400ms);
  EXPECT_FALSE(driver->moving);
  EXPECT_EQ(driver->service_connections().counters().commands_lost, 2u);
}

TEST_F(ServiceConnectionTest, OnlyCommandsThatDecodeFeedTheDeadman) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  ASSERT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kCreated);
  drive(kOcuA, 40);
  ASSERT_TRUE(driver->moving);
  // A Set Wrench Effort whose presence vector announces every field and carries none.
  const std::vector<std::uint8_t> truncated{0xFF, 0xFF};
  Header h;
  h.command_code = msg::SetWrenchEffort::code;
  h.source = kOcuA;
  h.destination = kDriver;
  h.data_size = static_cast<std::uint16_t>(truncated.size());
  for (int i = 0; i < 5; ++i) {
    time.advance(100ms);
    driver->receive(h, truncated);
  }
  EXPECT_EQ(driver->counters().decode_errors, 5u);
  EXPECT_FALSE(driver->moving);  // 500 ms without a command that decoded
  EXPECT_EQ(driver->service_connections().counters().commands_lost, 1u);
}

TEST_F(ServiceConnectionTest, CommandConnectionEndsWhenControlChangesHands) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  ASSERT_EQ(create(kOcuA, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kCreated);
  create(kOcuC, msg::ReportGlobalPose::code, 1, 0x1FF);  // an inform SC is nobody's deadman
  drive(kOcuA, 40);
  ASSERT_EQ(driver->service_connections().active(), 2u);
  ASSERT_EQ(request_control(kOcuB, 20), 0);  // B takes control with a higher authority
  EXPECT_FALSE(driver->moving);
  EXPECT_EQ(driver->service_connections().active(), 1u);
  EXPECT_TRUE(logged("control changed hands"));
  // B announces its own command SC; releasing control ends it.
  ASSERT_EQ(create(kOcuB, msg::SetWrenchEffort::code, 10, 0).response_code, msg::sc_response::kCreated);
  EXPECT_EQ(driver->service_connections().active(), 2u);
  deliver(kOcuB, msg::ReleaseComponentControl{});
  EXPECT_EQ(driver->service_connections().active(), 1u);
  // Nothing of A's or B's is watched any more: no loss of command to report.
  time.advance(2s);
  EXPECT_EQ(driver->service_connections().counters().commands_lost, 0u);
}

}  // namespace
}  // namespace jaus::test

namespace jaus::test {
namespace {

// Requester side: two components wired back to back through a loopback outbox.
class Loopback : public rt::Outbox {
 public:
  void send(const Header& header, std::span<const std::uint8_t> payload) override {
    if (!connected) return;
    std::vector<std::uint8_t> copy(payload.begin(), payload.end());
    time->call_at(time->now(), [this, header, copy] {
      for (auto* c : components)
        if (header.destination.matches(c->address())) c->receive(header, copy);
    });
  }
  rt::VirtualTime* time = nullptr;
  std::vector<rt::Component*> components;
  bool connected = true;
};

class PoseUser : public rt::Component {
 public:
  using Component::Component;
  using Component::subscribe;
  using Component::unsubscribe;
};

TEST(ServiceConnectionClient, DeliversReportsAndRecreatesWhenTheyStop) {
  rt::VirtualTime time;
  Loopback wire_link;
  wire_link.time = &time;
  rt::ComponentConfig provider_config;
  provider_config.address = kDriver;
  auto provider = std::make_unique<TestDriver>(provider_config, rt::Environment{time, time, wire_link});
  rt::ComponentConfig user_config;
  user_config.address = kOcuA;
  PoseUser user(user_config, rt::Environment{time, time, wire_link});
  wire_link.components = {provider.get(), &user};
  provider->start();
  user.start();

  std::vector<double> latitudes;
  const auto id = user.subscribe<msg::ReportGlobalPose>(
      kDriver, 20, 0x0001, [&](const Header&, const msg::ReportGlobalPose& pose) {
        latitudes.push_back(pose.latitude_deg.value_or(-1));
      });
  time.advance(std::chrono::milliseconds(1020));
  ASSERT_NE(user.subscription(id), nullptr);
  EXPECT_TRUE(user.subscription(id)->confirmed);
  EXPECT_EQ(latitudes.size(), 21u);  // at 0, 50, ..., 1000 ms
  EXPECT_NEAR(latitudes.back(), 45.5, 1e-6);

  // The provider restarts and forgets the SC: reports stop, the user creates it again.
  wire_link.components = {&user};
  provider = std::make_unique<TestDriver>(provider_config, rt::Environment{time, time, wire_link});
  provider->start();
  wire_link.components = {provider.get(), &user};
  const auto before = latitudes.size();
  time.advance(std::chrono::seconds(3));
  EXPECT_GE(user.subscription(id)->recreated, 1u);
  EXPECT_GT(latitudes.size(), before + 20);

  // Unsubscribing terminates the provider's SC.
  user.unsubscribe(id);
  time.run_ready();
  EXPECT_EQ(provider->service_connections().active(), 0u);
  const auto after = latitudes.size();
  time.advance(std::chrono::seconds(1));
  EXPECT_EQ(latitudes.size(), after);
}

}  // namespace
}  // namespace jaus::test
