// A JSS operator (ocu::JssSession, AS5669A) and an RA operator (the RA OCU
// library, OPC) compete for one real jausd's primitive driver, driving a
// separate clearpath-sim: one controller at a time by one authority rule,
// both dialects see the same controller (Report Control and Report
// Component Control), and either's Set Emergency stops the wheels while the
// other keeps commanding 60 % forward, resumes and tries to clear it;
// nothing moves until the one who set it clears it and a controller
// resumes. The checks read the simulator's true state.
#include <gtest/gtest.h>

#include <thread>

#include "clearpath_simulator.hpp"
#include "default_jausd.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/wire/message.hpp"
#include "jss_system.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
namespace m = jss::msg;

constexpr const char* kNode = "127.0.0.164";
constexpr const char* kSimAddress = "127.0.0.165";
constexpr const char* kRaHost = "127.0.0.166";
constexpr const char* kJssHost = "127.0.0.167";
constexpr int kSubsystem = 13;
const Address kRaDriver{kSubsystem, 1, 33, 1};
constexpr jss::JssId kJssDriver{kSubsystem, 1, 33};
constexpr jss::JssId kJssOperator{300, 2, 1};
const Address kRaOperator{254, 166, 40, 1};
constexpr std::uint8_t kAliasSubsystem = 250;  // FaceConfig::client_alias_subsystem
constexpr double kForwardPercent = 60;

class JssCompetition : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() / ("jaus-jss-competition-sim-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    sim = std::make_unique<ClearpathSimulator>(ClearpathSimulator::Line::udp, dir, "sim", kSimAddress);
    ASSERT_TRUE(sim->started());
    jausd = std::make_unique<DefaultJausd>("jss-competition", kSubsystem, kNode,
                                           std::string("platform: {udp: ") + kSimAddress + ":7300}\n" + jss_on_config());
    ASSERT_TRUE(jausd->started());
    // Both operators on one io_context: whichever waits, both are heard and answered.
    jss = open_jss_operator(kJssOperator, kJssHost, kNode, "jss operator", &io);
    ASSERT_TRUE(jss);
    ocu::SessionOptions options;
    options.self = kRaOperator;
    options.to = {*transport::parse_endpoint(std::string(kNode) + ":3794")};
    options.bind = *transport::parse_endpoint(kRaHost, 0);  // any free port
    auto opened = ocu::OcuSession::open(options, &io);
    ASSERT_TRUE(opened) << opened.error().message();
    ra = std::move(*opened);
    // The driver is Ready at the platform's first data.
    const auto until = std::chrono::steady_clock::now() + 30s;
    for (;;) {
      auto status = jss->query<m::ReportStatus>(kJssDriver, m::QueryStatus{}, 1s);
      if (status && (status->status & 0x0F) == 1) break;
      ASSERT_LT(std::chrono::steady_clock::now(), until) << jausd->output();
      jss->run_for(200ms);
    }
  }
  void TearDown() override {
    ra.reset();
    jss.reset();
    jausd.reset();
    sim.reset();
    if (!HasFailure()) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }

  // --- the RA operator ---
  std::optional<std::uint8_t> ra_request(std::uint8_t authority) {
    auto reply = ra->request(kRaDriver, msg::RequestComponentControl{{authority}},
                             {msg::ConfirmComponentControl::code}, 2s);
    if (!reply) return std::nullopt;
    msg::ConfirmComponentControl confirm{};
    if (!wire::decode_payload_into(reply->payload, confirm)) return std::nullopt;
    return confirm.response_code;
  }
  std::optional<msg::ReportComponentControl> ra_controller() {
    auto reply = ra->request(kRaDriver, msg::QueryComponentControl{}, {msg::ReportComponentControl::code}, 2s);
    if (!reply) return std::nullopt;
    msg::ReportComponentControl report{};
    if (!wire::decode_payload_into(reply->payload, report)) return std::nullopt;
    return report;
  }
  void ra_drive() {
    msg::SetWrenchEffort effort{};
    effort.propulsive_linear_effort_x_percent = kForwardPercent;
    ra->send(kRaDriver, effort);
  }

  // --- the JSS operator ---
  std::optional<std::uint8_t> jss_request(std::uint8_t authority) {
    auto confirm = jss->query<m::ConfirmControl>(kJssDriver, m::RequestControl{{authority}}, 2s);
    if (!confirm) return std::nullopt;
    return confirm->response_code;
  }
  std::optional<m::ReportControl> jss_controller() {
    auto report = jss->query<m::ReportControl>(kJssDriver, m::QueryControl{}, 2s);
    if (!report) return std::nullopt;
    return *report;
  }
  void jss_drive() {
    m::SetWrenchEffort effort{};
    effort.propulsive_linear_effort_x_percent = kForwardPercent;
    jss->send(kJssDriver, effort);
  }

  // `command` every 100 ms for `d`; true when the simulator moved (> 0.3 m/s) meanwhile.
  bool moved_while(rt::Duration d, const std::function<void()>& command) {
    bool moved = false;
    const auto until = std::chrono::steady_clock::now() + d;
    while (std::chrono::steady_clock::now() < until) {
      command();
      jss->run_for(100ms);
      if (const auto s = sim->state()) moved = moved || ClearpathSimulator::moving(*s);
    }
    return moved;
  }
  // Commands until the simulator moves (at most `d`).
  bool moves_within(rt::Duration d, const std::function<void()>& command) {
    const auto until = std::chrono::steady_clock::now() + d;
    while (std::chrono::steady_clock::now() < until) {
      command();
      jss->run_for(100ms);
      if (const auto s = sim->state(); s && ClearpathSimulator::moving(*s)) return true;
    }
    return false;
  }
  // Stops within 1 s of an emergency while `command` goes on.
  bool stops_within(rt::Duration d, const std::function<void()>& command) {
    const auto until = std::chrono::steady_clock::now() + d;
    while (std::chrono::steady_clock::now() < until) {
      command();
      jss->run_for(100ms);
      if (const auto s = sim->state(); s && ClearpathSimulator::stopped(*s)) return true;
    }
    return false;
  }

  boost::asio::io_context io;
  std::filesystem::path dir;
  std::unique_ptr<ClearpathSimulator> sim;
  std::unique_ptr<DefaultJausd> jausd;
  std::unique_ptr<ocu::JssSession> jss;
  std::unique_ptr<ocu::OcuSession> ra;
};

TEST_F(JssCompetition, OneControllerOneAuthorityRuleAndTheSameControllerSeenInBothDialects) {
  // The JSS operator takes the driver; the RA side sees its alias as the controller.
  ASSERT_EQ(jss_request(5), m::confirm_control::kControlAccepted) << jausd->output();
  auto seen_by_ra = ra_controller();
  ASSERT_TRUE(seen_by_ra) << jausd->output();
  EXPECT_EQ(seen_by_ra->controller.subsystem, kAliasSubsystem) << seen_by_ra->controller.to_string();
  EXPECT_EQ(seen_by_ra->authority, 5);
  auto seen_by_jss = jss_controller();
  ASSERT_TRUE(seen_by_jss);
  EXPECT_EQ(seen_by_jss->controller, kJssOperator);

  // The RA operator at the same authority is refused; the JSS operator keeps it.
  EXPECT_NE(ra_request(5), std::optional<std::uint8_t>(msg::control_response::kAccepted));
  seen_by_jss = jss_controller();
  ASSERT_TRUE(seen_by_jss);
  EXPECT_EQ(seen_by_jss->controller, kJssOperator);

  // Higher authority takes over, across dialects, both ways; the loser is told in its dialect.
  // What each is told is heard from now on (both run on one loop: it may come while the other waits).
  std::vector<std::uint8_t> jss_rejects;
  int ra_rejects = 0;
  const auto jss_listener = jss->listen([&](const ocu::JssReceived& r) {
    if (r.source() == kJssDriver && r.message_id() == m::RejectControl::code)
      if (auto reject = jss::decode_contents<m::RejectControl>(r.contents)) jss_rejects.push_back(reject->response_code);
  });
  const auto ra_listener = ra->listen([&](const ocu::Received& r) {
    ra_rejects += r.header.source == kRaDriver && r.header.command_code == msg::RejectComponentControl::code;
  });
  ASSERT_EQ(ra_request(6), std::optional<std::uint8_t>(msg::control_response::kAccepted));
  jss->run_until([&] { return !jss_rejects.empty(); }, 2s);
  ASSERT_EQ(jss_rejects, std::vector<std::uint8_t>{m::reject_control::kControlReleased})
      << "the JSS operator was not told it lost control (Reject Control 0)";
  seen_by_jss = jss_controller();
  ASSERT_TRUE(seen_by_jss);
  EXPECT_EQ(seen_by_jss->controller, (jss::JssId{kRaOperator.subsystem, kRaOperator.node, kRaOperator.component}));
  EXPECT_EQ(seen_by_jss->authority, 6);
  seen_by_ra = ra_controller();
  ASSERT_TRUE(seen_by_ra);
  EXPECT_EQ(seen_by_ra->controller, kRaOperator);

  ASSERT_EQ(jss_request(7), m::confirm_control::kControlAccepted);
  ra->run_until([&] { return ra_rejects > 0; }, 2s);
  EXPECT_EQ(ra_rejects, 1) << "the RA operator was not told it lost control (Reject Component Control)";
  jss->unlisten(jss_listener);
  ra->unlisten(ra_listener);
  seen_by_ra = ra_controller();
  ASSERT_TRUE(seen_by_ra);
  EXPECT_EQ(seen_by_ra->controller.subsystem, kAliasSubsystem);
  EXPECT_EQ(seen_by_ra->authority, 7);
  jss->send(kJssDriver, m::ReleaseControl{});
  jss->run_for(300ms);
}

TEST_F(JssCompetition, EithersSetEmergencyStopsTheVehicleWhateverTheOtherSends) {
  // --- The RA operator's emergency stops the JSS operator's driving. ---
  ASSERT_EQ(jss_request(7), m::confirm_control::kControlAccepted) << jausd->output();
  jss->send(kJssDriver, m::Resume{});
  ASSERT_TRUE(moves_within(5s, [&] { jss_drive(); })) << jausd->output();
  const auto ra_set_at = std::chrono::steady_clock::now();
  ra->send(kRaDriver, msg::SetEmergency{{1}});
  ASSERT_TRUE(stops_within(2s, [&] { jss_drive(); })) << "the RA operator's Set Emergency did not stop the wheels";
  const double ra_stop_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - ra_set_at).count();
  // The JSS operator keeps driving, resumes, asks control again and clears (not its emergency): nothing moves.
  int tick = 0;
  EXPECT_FALSE(moved_while(3s, [&] {
    jss_drive();
    if (++tick % 10 == 0) {
      jss->send(kJssDriver, m::Resume{});
      jss->send(kJssDriver, m::ClearEmergency{{1}});
      jss->send(kJssDriver, m::RequestControl{{7}});
    }
  })) << "the vehicle moved while the RA operator's emergency held";
  // Its holder clears it; a controller resumes; then the wheels turn again.
  ra->send(kRaDriver, msg::ClearEmergency{{1}});
  ra->run_for(300ms);
  ASSERT_EQ(jss_request(7), m::confirm_control::kControlAccepted);
  jss->send(kJssDriver, m::Resume{});
  EXPECT_TRUE(moves_within(5s, [&] { jss_drive(); })) << "not driving again after the holder's clear and Resume";
  jss->send(kJssDriver, m::SetWrenchEffort{});
  jss->send(kJssDriver, m::Standby{});

  // --- The JSS operator's emergency stops the RA operator's driving. ---
  ASSERT_EQ(ra_request(8), std::optional<std::uint8_t>(msg::control_response::kAccepted));
  ra->send(kRaDriver, msg::Resume{});
  ASSERT_TRUE(moves_within(5s, [&] { ra_drive(); })) << jausd->output();
  const auto jss_set_at = std::chrono::steady_clock::now();
  jss->send(kJssDriver, m::SetEmergency{{1}}, jss::JudpPriority::safety_critical);
  ASSERT_TRUE(stops_within(2s, [&] { ra_drive(); })) << "the JSS operator's Set Emergency did not stop the wheels";
  const double jss_stop_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - jss_set_at).count();
  tick = 0;
  EXPECT_FALSE(moved_while(3s, [&] {
    ra_drive();
    if (++tick % 10 == 0) {
      ra->send(kRaDriver, msg::Resume{});
      ra->send(kRaDriver, msg::ClearEmergency{{1}});
    }
  })) << "the vehicle moved while the JSS operator's emergency held";
  jss->send(kJssDriver, m::ClearEmergency{{1}});
  jss->run_for(300ms);
  ASSERT_EQ(ra_request(8), std::optional<std::uint8_t>(msg::control_response::kAccepted));
  ra->send(kRaDriver, msg::Resume{});
  EXPECT_TRUE(moves_within(5s, [&] { ra_drive(); })) << "not driving again after the holder's clear and Resume";
  ra->send(kRaDriver, msg::SetWrenchEffort{});
  ra->send(kRaDriver, msg::Standby{});
  ra->send(kRaDriver, msg::ReleaseComponentControl{});
  ra->run_for(300ms);
  std::cout << "[ stopped  ] RA Set Emergency -> wheels at zero in " << ra_stop_ms << " ms; JSS Set Emergency in "
            << jss_stop_ms << " ms (sim status every 100 ms)\n";
}

// Issue 42, finding 1: the JSS operator's RA alias (250.<slot>.<component>.1)
// written into RA headers from another host must not act in its name: not
// drive while it controls (thirty and more Set Wrench Effort), not release
// its control, not clear its emergency. jausd drops every RA datagram from
// the alias subsystem (alias_source); the operator's own messages go on.
TEST_F(JssCompetition, NobodyActsAsTheJssOperatorsAliasOverRa) {
  ASSERT_EQ(jss_request(7), m::confirm_control::kControlAccepted) << jausd->output();
  const auto report = jss_controller();
  ASSERT_TRUE(report);
  ASSERT_EQ(report->controller, kJssOperator);
  // Its alias, as the RA side names it (Report Component Control).
  const auto ra_report = ra_controller();
  ASSERT_TRUE(ra_report) << jausd->output();
  const Address alias = ra_report->controller;
  ASSERT_EQ(alias.subsystem, kAliasSubsystem);
  // Raw OPC datagrams from another host (an OCU library refuses component 1 as its own).
  namespace ip = boost::asio::ip;
  ip::udp::socket raw(io, ip::udp::endpoint(ip::make_address_v4(kRaHost), 0));
  const auto forge = [&](const auto& message) {
    Header h;
    h.source = alias;
    h.destination = kRaDriver;
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_message(h, message, packet);
    ASSERT_TRUE(size) << size.error().message();
    packet.resize(*size);
    const auto prefix = transport::frame_prefix(transport::Framing::opc, packet.size());
    std::vector<std::uint8_t> datagram(prefix.view().begin(), prefix.view().end());
    datagram.insert(datagram.end(), packet.begin(), packet.end());
    raw.send_to(boost::asio::buffer(datagram), ip::udp::endpoint(ip::make_address_v4(kNode), 3794));
  };
  jss->send(kJssDriver, m::Resume{});
  msg::SetWrenchEffort forward{};
  forward.propulsive_linear_effort_x_percent = kForwardPercent;
  int beat = 0;
  EXPECT_FALSE(moved_while(3s, [&] {
    forge(forward);
    if (++beat % 10 == 0) jss->send(kJssDriver, m::RequestControl{{7}});  // JSS keeps control by asking again
  }))
      << "RA Set Wrench Effort from the alias moved the JSS operator's vehicle";
  forge(msg::ReleaseComponentControl{});
  jss->run_for(500ms);
  const auto after = jss_controller();
  ASSERT_TRUE(after);
  EXPECT_EQ(after->controller, kJssOperator) << "a forged Release dropped the JSS operator's control";
  EXPECT_TRUE(moves_within(5s, [&] { jss_drive(); })) << "the JSS operator no longer drives";
  // Its emergency: a forged Clear releases nothing; its own Clear does.
  jss->send(kJssDriver, m::SetEmergency{{1}}, jss::JudpPriority::safety_critical);
  ASSERT_TRUE(stops_within(2s, [] {}));
  int tick = 0;
  EXPECT_FALSE(moved_while(3s, [&] {
    jss_drive();
    if (++tick % 5 == 0) {
      forge(msg::ClearEmergency{{1}});
      forge(msg::Resume{});
    }
  })) << "a forged Clear Emergency in the alias's name released the JSS operator's stop";
  const auto status = jss->query<m::ReportStatus>(kJssDriver, m::QueryStatus{}, 2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status->status & 0x0F, 5) << "not in Emergency";  // as RA's primary status
  EXPECT_TRUE(jausd->output_shows("source in the JSS clients' alias subsystem")) << jausd->output();
  jss->send(kJssDriver, m::ClearEmergency{{1}});
  jss->run_for(300ms);
  const auto cleared = jss->query<m::ReportStatus>(kJssDriver, m::QueryStatus{}, 2s);
  ASSERT_TRUE(cleared);
  EXPECT_NE(cleared->status & 0x0F, 5);
  jss->send(kJssDriver, m::Standby{});
  jss->send(kJssDriver, m::ReleaseControl{});
  jss->run_for(300ms);
}


// Issue 43: a JSS operator that restarts numbers its messages from 1 again
// (Jr does), within the node's duplicate window. The restarted run's Request
// Control, the same message under the same number as the first run's, is
// obeyed at once, not ACKed and dropped as a copy.
TEST_F(JssCompetition, ARestartedJssOperatorIsObeyedAtOnce) {
  constexpr jss::JssId kRestarting{300, 4, 1};
  const auto run = [&](const char* name) -> std::optional<std::uint8_t> {
    ocu::JssSessionOptions options;
    options.self = kRestarting;
    options.name = name;
    options.first_sequence = 1;
    options.to = {*transport::parse_endpoint(std::string(kNode) + ":3794")};
    options.bind = *transport::parse_endpoint(kJssHost, 0);
    auto opened = ocu::JssSession::open(options, &io);
    EXPECT_TRUE(opened) << (opened ? "" : opened.error().message());
    if (!opened) return std::nullopt;
    auto& session = **opened;
    std::optional<std::uint8_t> confirmed;
    session.listen([&](const ocu::JssReceived& r) {
      if (r.source() != kJssDriver || r.message_id() != m::ConfirmControl::code) return;
      if (auto confirm = jss::decode_contents<m::ConfirmControl>(r.contents)) confirmed = confirm->response_code;
    });
    // Sequence number 1, ACK requested, as Jr sends it.
    const auto arrival = session.send_must_arrive(kJssDriver, m::RequestControl{{5}});
    EXPECT_EQ(arrival.outcome, ocu::Arrival::acknowledged) << name;
    session.run_until([&] { return confirmed.has_value(); }, 2s);
    // And a query, as any operator goes on (sequence number 2).
    EXPECT_TRUE(session.query<m::ReportStatus>(kJssDriver, m::QueryStatus{}, 2s)) << name;
    return confirmed;
  };
  ASSERT_EQ(run("first run"), m::confirm_control::kControlAccepted) << jausd->output();
  const auto again = run("restarted run");  // at once: well within the window
  ASSERT_TRUE(again.has_value()) << "the restarted operator's Request Control was dropped as a copy\n"
                                 << jausd->output();
  EXPECT_EQ(*again, m::confirm_control::kControlAccepted);
  // The node says so, naming the operator by its JSS ID and host.
  EXPECT_TRUE(jausd->output_shows("JSS client 300.4.1 at 127.0.0.167:")) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("restarted (sequence number 1")) << jausd->output();
  // The driver's own lines name the operator by its JSS ID and host, not only its alias.
  const std::string output = jausd->output();
  bool named = false;
  for (std::size_t at = output.find("controlled by 250."); at != std::string::npos && !named;
       at = output.find("controlled by 250.", at + 1))
    named = output.substr(at, output.find('\n', at) - at).find("(JSS client 300.4.1 at 127.0.0.167:") != std::string::npos;
  EXPECT_TRUE(named) << output;
}

}  // namespace
}  // namespace jaus::test
