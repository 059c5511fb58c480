// Interoperability (issue 43): scripted peers that behave on the wire as the
// RA and SAE JAUS implementations in the field do, each on another host (the
// `ocu` namespace) than jausd, which runs with the DEFAULT configuration:
// its file says only which platform it drives (`platform: {udp: ...}`, the
// clearpath-sim on veh1's loopback); bind, multicast, peers, relay and
// control are the built-in defaults.
//
// - OpenJausNode: an RA node as OpenJAUS's node manager with an OCU on it
//   (scripted_ra_peer.hpp): JUDP, sends only to 224.1.0.1:3794, never ACKs.
//   It discovers the vehicle from its heartbeats on the group, queries every
//   component, takes control, drives, sets and clears an emergency and
//   releases; jausd keeps it while it talks only to the group, and nothing
//   addressed to jausd's own subsystem reaches the group.
// - A spec-written OCU behind a router (unicast, never ACKs): answered with
//   the defaults, in control once control_from names its network.
// - JrClient: a SAE JAUS (AS5669A) client as Jr Middleware based ones: its
//   sequence numbers start at 1 on every start; restarted within seconds, its
//   Request Control, queries and efforts are obeyed at once.
#include <thread>

#include "jaus/jss/all.hpp"
#include "jaus/ocu/jss_session.hpp"
#include "network_test.hpp"
#include "scripted_ra_peer.hpp"

namespace jaus::test::network {
namespace {

constexpr std::uint8_t kVehicle = 1;  // the default identification: subsystem 1, node 1
const Address kNodeManager{kVehicle, 1, 1, 1};
const Address kDriver{kVehicle, 1, 33, 1};
const Address kPoseSensor{kVehicle, 1, 38, 1};
const Address kVelocitySensor{kVehicle, 1, 42, 1};
const Address kOpenJausOcu{5, 1, 40, 1};  // subsystem 5: an OCU's node manager (5.1.1.1) and its OCU component
constexpr double kForwardPercent = 60;

class Interoperability : public NetworkTest {
 protected:
  // clearpath-sim on veh1's loopback and jausd beside it with the default
  // configuration (and `more`, a user's own lines, if any).
  void start_default_node(const std::string& more = "") {
    if (!simulator) start_simulator();
    const auto config = dir / "veh1-default.yaml";
    std::ofstream(config) << "# the default configuration; only the platform is this lab's\n"
                          << "platform: {udp: " << kSimulatorAddress << ":7300}\n"
                          << more;
    std::vector<std::string> argv = lab->exec_in(kVeh1);
    argv.insert(argv.end(), {JAUSD_PATH, "--config", config.string(), "--log-level", "debug"});
    jausd = std::make_unique<ChildProcess>(argv, (dir / "veh1-jausd.log").string());
    ASSERT_TRUE(jausd->started());
  }
  void enter_ocu_host() {
    auto entered = InNamespace::enter(lab->namespace_of(kOcu));
    ASSERT_TRUE(entered) << (entered ? "" : entered.error().message());
    in_ocu_namespace = std::move(*entered);
  }
  void TearDown() override {
    ra.reset();
    jss.reset();
    jausd.reset();
    NetworkTest::TearDown();
  }
  std::string node_log() const { return jausd ? jausd->output() : std::string("(no jausd)"); }

  // --- the OpenJAUS-like node ---
  // Efforts every 100 ms (the driver's command timeout is 0.5 s) until `done` or `d`; the peer pumped meanwhile.
  bool ra_drive_until(const std::function<bool()>& done, std::chrono::seconds d, double percent = kForwardPercent) {
    const auto until = Clock::now() + d;
    while (Clock::now() < until) {
      msg::SetWrenchEffort effort{};
      effort.propulsive_linear_effort_x_percent = percent;
      ra->send(kDriver, effort);
      ra->pump(100ms);
      if (done()) return true;
    }
    return false;
  }
  std::optional<msg::PrimaryStatus> ra_status(const Address& component) {
    const auto status = ra->request<msg::ReportComponentStatus>(component, msg::QueryComponentStatus{}, 5s);
    if (!status) return std::nullopt;
    return static_cast<msg::PrimaryStatus>(status->primary_status & 0x0F);
  }
  bool moving() const {
    const auto s = simulator->state();
    return s && ClearpathSimulator::moving(*s);
  }
  bool stopped() const {
    const auto s = simulator->state();
    return s && s->value("speed_mps", 1.0) < 0.05;
  }

  std::unique_ptr<ChildProcess> jausd;
  std::unique_ptr<ScriptedRaPeer> ra;
  std::unique_ptr<ocu::JssSession> jss;
};

TEST_F(Interoperability, OpenJausNodeFindsQueriesControlsAndDrivesTheDefaultNode) {
  ASSERT_NO_FATAL_FAILURE(start_default_node());
  ASSERT_NO_FATAL_FAILURE(enter_ocu_host());
  ra = std::make_unique<ScriptedRaPeer>(kOpenJausOcu, kOcu.address);
  ASSERT_TRUE(ra->opened()) << "cannot bind 0.0.0.0:3794 and join 224.1.0.1 in the ocu namespace";

  // Discovery as its node manager does it: the vehicle's heartbeat on the group, then its queries.
  std::optional<Address> heard;
  const auto until = Clock::now() + 30s;
  while (!heard && Clock::now() < until) {
    ra->pump(200ms);
    for (const auto& r : ra->inbox)
      if (r.header.command_code == msg::ReportHeartbeatPulse::code && r.header.source.subsystem == kVehicle)
        heard = r.header.source;
  }
  ASSERT_TRUE(heard) << "no heartbeat of subsystem 1 on 224.1.0.1 within 30 s of jausd's start\n" << node_log();
  const auto subsystem = ra->request<msg::ReportIdentification>(
      kNodeManager, msg::QueryIdentification{{msg::identification::kSubsystem}});
  ASSERT_TRUE(subsystem) << "no Report Identification (subsystem) to a peer that never ACKs\n" << node_log();
  EXPECT_EQ(subsystem->type, 10001);  // a vehicle
  const auto configuration =
      ra->request<msg::ReportConfiguration>(kNodeManager, msg::QueryConfiguration{{msg::identification::kSubsystem}});
  ASSERT_TRUE(configuration) << node_log();
  std::vector<Address> components;
  for (const auto& node : configuration->nodes)
    for (const auto& c : node.components) components.push_back(Address{kVehicle, node.node_id, c.component_id, c.instance});
  ASSERT_GE(components.size(), 10u) << "the default node's components";

  // Every component: identification, services, status.
  for (const auto& c : components) {
    SCOPED_TRACE(c.to_string());
    const auto id = ra->request<msg::ReportIdentification>(c, msg::QueryIdentification{{msg::identification::kComponent}});
    EXPECT_TRUE(id && !id->identification.empty());
    const auto services = ra->request<msg::ReportServices>(c, msg::QueryServices{});
    EXPECT_TRUE(services && !services->services.empty());
    EXPECT_TRUE(ra_status(c).has_value());
  }
  const auto pose = ra->request<msg::ReportGlobalPose>(kPoseSensor, msg::QueryGlobalPose{{0x0003}});
  ASSERT_TRUE(pose && pose->latitude_deg) << node_log();
  const auto velocity = ra->request<msg::ReportVelocityState>(kVelocitySensor, msg::QueryVelocityState{{0x0001}});
  EXPECT_TRUE(velocity && velocity->velocity_x_mps);

  // Control: Confirm Component Control arrives (its host is on the vehicle's LAN: control_from [local]).
  const auto confirm = ra->request<msg::ConfirmComponentControl>(kDriver, msg::RequestComponentControl{{10}});
  ASSERT_TRUE(confirm) << node_log();
  ASSERT_EQ(confirm->response_code, msg::control_response::kAccepted);
  EXPECT_TRUE(ra_drive_until([&] { return moving(); }, 20s)) << "the simulator never moved\n" << node_log();

  // Silent but for its heartbeats and status answers, on the group only, for longer than
  // the node timeout (5 s): still known, still in control.
  ra->pump(7s);
  const auto controller = ra->request<msg::ReportComponentControl>(kDriver, msg::QueryComponentControl{});
  ASSERT_TRUE(controller) << node_log();
  EXPECT_EQ(controller->controller, kOpenJausOcu) << "control lost while the OCU talked to the group only\n" << node_log();

  // Set Emergency stops the vehicle while efforts keep coming; Clear Emergency ends it.
  ASSERT_TRUE(ra_drive_until([&] { return moving(); }, 20s)) << node_log();
  ra->send(kDriver, msg::SetEmergency{{1}});
  EXPECT_TRUE(ra_drive_until([&] { return stopped(); }, 10s)) << "Set Emergency did not stop the vehicle\n" << node_log();
  EXPECT_EQ(ra_status(kDriver), msg::PrimaryStatus::emergency);
  ra->send(kDriver, msg::ClearEmergency{{1}});
  const auto cleared_until = Clock::now() + 10s;
  std::optional<msg::PrimaryStatus> after;
  while (Clock::now() < cleared_until && (after = ra_status(kDriver)) == msg::PrimaryStatus::emergency) ra->pump(200ms);
  EXPECT_TRUE(after && *after != msg::PrimaryStatus::emergency) << node_log();

  // Release (OpenJAUS expects no reply): nobody controls the driver.
  ra->send(kDriver, msg::ReleaseComponentControl{});
  ra->pump(500ms);
  const auto released = ra->request<msg::ReportComponentControl>(kDriver, msg::QueryComponentControl{});
  ASSERT_TRUE(released);
  EXPECT_NE(released->controller, kOpenJausOcu);

  // The node never sent the group what only its own subsystem may receive (S.255.1.1 heartbeats).
  std::string strays;
  for (const auto& h : ra->for_another_subsystem) strays += " " + h.destination.to_string();
  EXPECT_TRUE(ra->for_another_subsystem.empty()) << "for another subsystem:" << strays;
  EXPECT_EQ(ra->malformed, 0u);
  EXPECT_FALSE(jausd->output_contains("5.1.0.0 silent")) << node_log();
}

// An OCU written from the spec (unicast, never ACKs) on another network,
// behind a router: the ocu host also has 10.78.0.10/24, and veh1 reaches
// 10.78.0.0/24 through it, so the OCU's source is not one of veh1's networks.
// With the defaults it is answered but may not take control; with its
// network added to control_from as docs/running.md says, it drives and stops.
constexpr const char* kBehindRouterAddress = "10.78.0.10";
const Address kRoutedOcu{6, 1, 40, 1};

TEST_F(Interoperability, ASpecWrittenOcuBehindARouterIsAnsweredAndDrivesOnceControlFromNamesItsNetwork) {
  auto ip = [&](const LabHost& host, std::vector<std::string> args) {
    args.insert(args.begin(), {kIp, "-n", lab->namespace_of(host)});
    return run_command(args);
  };
  ASSERT_TRUE(ip(kOcu, {"addr", "add", std::string(kBehindRouterAddress) + "/24", "dev", "eth0"}));
  ASSERT_TRUE(ip(kVeh1, {"route", "add", "10.78.0.0/24", "via", kOcu.address}));
  ASSERT_NO_FATAL_FAILURE(start_default_node());
  ASSERT_NO_FATAL_FAILURE(enter_ocu_host());
  ra = ScriptedRaPeer::unicast(kRoutedOcu, kBehindRouterAddress, kVeh1.address);
  ASSERT_TRUE(ra->opened()) << "cannot bind " << kBehindRouterAddress << ":3794 in the ocu namespace";

  // Defaults: every query answered (it never ACKs); control refused (outside control_from: [local]).
  const auto status = ra_status(kDriver);
  ASSERT_TRUE(status) << "no Report Component Status for an OCU behind a router\n" << node_log();
  const auto id = ra->request<msg::ReportIdentification>(kNodeManager,
                                                         msg::QueryIdentification{{msg::identification::kSubsystem}});
  ASSERT_TRUE(id) << node_log();
  const auto pose = ra->request<msg::ReportGlobalPose>(kPoseSensor, msg::QueryGlobalPose{{0x0003}});
  ASSERT_TRUE(pose && pose->latitude_deg) << node_log();
  const auto refused = ra->request<msg::ConfirmComponentControl>(kDriver, msg::RequestComponentControl{{10}});
  ASSERT_TRUE(refused) << "a refused request gets its Confirm too\n" << node_log();
  EXPECT_NE(refused->response_code, msg::control_response::kAccepted);
  EXPECT_FALSE(ra_drive_until([&] { return moving(); }, 2s)) << "an OCU outside control_from drove\n" << node_log();

  // The fix docs/running.md gives: its network in control_from. Confirm arrives, it drives, Set Emergency stops it.
  jausd.reset();
  ASSERT_NO_FATAL_FAILURE(start_default_node("transport: {control_from: [local, 10.78.0.0/24]}\n"));
  const auto confirm = ra->request<msg::ConfirmComponentControl>(kDriver, msg::RequestComponentControl{{10}}, 30s);
  ASSERT_TRUE(confirm) << node_log();
  ASSERT_EQ(confirm->response_code, msg::control_response::kAccepted) << node_log();
  EXPECT_TRUE(ra_drive_until([&] { return moving(); }, 20s)) << "the simulator never moved\n" << node_log();
  ra->send(kDriver, msg::SetEmergency{{1}});
  EXPECT_TRUE(ra_drive_until([&] { return stopped(); }, 10s)) << "Set Emergency did not stop the vehicle\n" << node_log();
  EXPECT_EQ(ra_status(kDriver), msg::PrimaryStatus::emergency);
  ra->send(kDriver, msg::ClearEmergency{{1}});
  ra->send(kDriver, msg::ReleaseComponentControl{});
  ra->pump(300ms);
}

// --- the Jr-like SAE JAUS client ---

constexpr jss::JssId kJssDriver{kVehicle, 1, 33};
constexpr jss::JssId kJrClient{300, 2, 1};

class JrLike : public Interoperability {
 protected:
  // A Jr-like client: the same JSS ID on the same endpoint (port 3794) on every start,
  // numbering from 1; the node by its address and the JSS group.
  void start_client() {
    jss.reset();
    ocu::JssSessionOptions options;
    options.self = kJrClient;
    options.name = "jr client";
    options.first_sequence = 1;
    options.to = {*transport::parse_endpoint(std::string(kVeh1.address) + ":3794")};
    options.bind = *transport::parse_endpoint(std::string(kOcu.address) + ":3794");
    options.multicast = ocu::kJssMulticastGroup;
    auto opened = ocu::JssSession::open(options);
    ASSERT_TRUE(opened) << opened.error().message();
    jss = std::move(*opened);
  }
  std::optional<std::uint8_t> request_control() {
    auto confirm = jss->query<jss::msg::ConfirmControl>(kJssDriver, jss::msg::RequestControl{{7}}, 2s);
    if (!confirm) return std::nullopt;
    return confirm->response_code;
  }
  // Efforts every 100 ms, control asked again every second (how a JSS client keeps it), until `done` or `d`.
  bool drive_until(const std::function<bool()>& done, rt::Duration d, double percent = kForwardPercent) {
    const auto until = Clock::now() + d;
    int beat = 0;
    while (Clock::now() < until) {
      jss::msg::SetWrenchEffort effort{};
      effort.propulsive_linear_effort_x_percent = percent;
      jss->send(kJssDriver, effort);
      if (++beat % 10 == 0) jss->send(kJssDriver, jss::msg::RequestControl{{7}});
      jss->run_for(100ms);
      if (done()) return true;
    }
    return false;
  }
};

TEST_F(JrLike, RestartedClientNumberingFromOneIsObeyedAtOnce) {
  ASSERT_NO_FATAL_FAILURE(start_default_node());
  ASSERT_NO_FATAL_FAILURE(enter_ocu_host());
  ASSERT_NO_FATAL_FAILURE(start_client());
  // First run: the driver Ready, control, a drive and a stop, and many numbers used
  // (a burst of queries): everything the second run sends reuses one of them.
  const auto until = Clock::now() + 30s;
  for (;;) {
    const auto status = jss->query<jss::msg::ReportStatus>(kJssDriver, jss::msg::QueryStatus{}, 1s);
    if (status && (status->status & 0x0F) == 1) break;
    ASSERT_LT(Clock::now(), until) << "the driver never Ready for the JSS client\n" << node_log();
    jss->run_for(200ms);
  }
  ASSERT_EQ(request_control(), jss::msg::confirm_control::kControlAccepted) << node_log();
  jss->send(kJssDriver, jss::msg::Resume{});
  ASSERT_TRUE(drive_until([&] { return moving(); }, 20s)) << "first run: never moved\n" << node_log();
  ASSERT_TRUE(drive_until([&] { return stopped(); }, 10s, 0)) << node_log();
  for (int i = 0; i < 150; ++i) jss->send(kJssDriver, jss::msg::QueryStatus{});
  jss->run_for(300ms);

  // Restart: a new process, numbering from 1 again, within a second.
  ASSERT_NO_FATAL_FAILURE(start_client());
  const auto restarted = Clock::now();
  // Obeyed at once: well inside the 10 s a JSS node remembers numbers for.
  EXPECT_EQ(request_control(), jss::msg::confirm_control::kControlAccepted) << node_log();
  const auto status = jss->query<jss::msg::ReportStatus>(kJssDriver, jss::msg::QueryStatus{}, 2s);
  EXPECT_TRUE(status) << "restarted client's query unanswered\n" << node_log();
  jss->send(kJssDriver, jss::msg::Resume{});
  EXPECT_TRUE(drive_until([&] { return moving(); }, 5s))
      << "restarted client's efforts not obeyed within 5 s\n" << node_log();
  EXPECT_LT(seconds_since(restarted), 8.0);
  drive_until([&] { return stopped(); }, 5s, 0);
  jss->send(kJssDriver, jss::msg::ReleaseControl{});
  jss->run_for(200ms);
}

}  // namespace
}  // namespace jaus::test::network
