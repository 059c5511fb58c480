// A node restarted: veh2b's jausd (node 2.2: camera and arm) killed with
// SIGKILL and started again. The others forget it within the liveness
// timeout (node_timeout_s, 5 s, plus the housekeeping period): veh2a and veh1
// (their logs: "node 2.2... silent: lost") and the in-process OCU (its node's
// log). After the restart they learn it again: veh2a's Report Configuration
// lists node 2 with its components, veh1 (relay: true) forwards a query from
// an OCU that reaches only veh1 to node 2.2 again (its route), and the OCU's
// service connection on 2.2.37.1 delivers reports again, each within a stated time.
#include <mutex>

#include "network_test.hpp"
#include "ocu_helpers.hpp"

namespace jaus::test::network {
namespace {

const jaus::Address kCamera{2, 2, 37, 1};
const jaus::Address kVeh2aNodeManager{2, 1, 1, 1};
const jaus::Address kVeh2bNodeManager{2, 2, 1, 1};
constexpr double kForgetBoundSeconds = 8.0;    // node_timeout_s 5 + housekeeping + margin
constexpr double kRelearnBoundSeconds = 10.0;  // jausd's start, a heartbeat, a query: about 2 s
constexpr double kReportsBoundSeconds = 12.0;  // the client re-creates a silent connection (ServiceConnectionClient)

bool lost_node_2_2(const std::string& log) {
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (line.find("silent: lost") != std::string::npos && line.find(" 2.2.") != std::string::npos) return true;
  return false;
}

class Restart : public NetworkTest {
 protected:
  // Whether veh2a's node manager lists node 2 of its subsystem with a component.
  bool veh2a_lists_node_2(jaus::ocu::OcuSession& session) {
    auto reply = session.request(kVeh2aNodeManager, jaus::msg::QueryConfiguration{{jaus::msg::identification::kSubsystem}},
                                 {jaus::msg::ReportConfiguration::code}, 300ms);
    if (!reply) return false;
    jaus::msg::ReportConfiguration report{};
    if (!jaus::wire::decode_payload_into(reply->payload, report, jaus::wire::Dialect::ra, jaus::kHeaderSize))
      return false;
    for (const auto& n : report.nodes)
      if (n.node_id == 2) {
        for (const auto& c : n.components)
          if (c.component_id == 37) return true;
      }
    return false;
  }
  // Whether a query to veh2b's node manager, sent only to veh1, is answered (veh1 relays it).
  bool reached_through_veh1(jaus::ocu::OcuSession& through_veh1) {
    return static_cast<bool>(through_veh1.request(kVeh2bNodeManager, jaus::msg::QueryIdentification{{jaus::msg::identification::kNode}},
                                                  {jaus::msg::ReportIdentification::code}, 300ms));
  }
};

TEST_F(Restart, ANodeKilledAndRestartedIsForgottenAndRelearntAndItsServiceConnectionRecovers) {
  start_vehicles(Finding::multicast_and_peers, "relay: true");
  auto* session = open_ocu({kVeh1, kVeh2a, kVeh2b});
  ASSERT_NE(session, nullptr);
  auto through_veh1_opened = [&] {
    jaus::ocu::SessionOptions options;
    options.self = {254, 11, 40, 1};
    options.to = {*jaus::transport::parse_endpoint(kVeh1.address)};
    options.bind = ocu_any_port();
    return jaus::ocu::OcuSession::open(options, &session->io_context());
  }();
  ASSERT_TRUE(through_veh1_opened) << through_veh1_opened.error().message();
  auto& through_veh1 = **through_veh1_opened;

  std::vector<Clock::time_point> reports;
  const auto subscription = session->component().subscribe<jaus::msg::ReportComponentStatus>(
      kCamera, 5, 0, [&](const jaus::Header&, const jaus::msg::ReportComponentStatus&) { reports.push_back(Clock::now()); });
  ASSERT_TRUE(session->run_until([&] { return reports.size() >= 5; }, 30s)) << node(kVeh2b).output();
  ASSERT_TRUE(session->run_until([&] { return veh2a_lists_node_2(*session); }, 15s));
  const auto until_routed = Clock::now() + 15s;
  bool routed_before = false;
  while (!routed_before && Clock::now() < until_routed) routed_before = reached_through_veh1(through_veh1);
  EXPECT_TRUE(routed_before) << "veh1 did not relay to 2.2 before the restart";

  // Killed: who forgets it, when.
  const auto killed = Clock::now();
  node(kVeh2b).kill();
  std::map<std::string, double> forgot_after_s;
  const auto ocu_log_lost = [&] {
    for (const auto& line : ocu_log)
      if (line.at > killed && line.text.find("silent: lost") != std::string::npos &&
          line.text.find(" 2.2.") != std::string::npos)
        return true;
    return false;
  };
  session->run_until(
      [&] {
        const auto note = [&](const std::string& who, bool lost) {
          if (lost && !forgot_after_s.count(who)) forgot_after_s[who] = seconds_since(killed);
        };
        note("veh2a", lost_node_2_2(node(kVeh2a).output()));
        note("veh1", lost_node_2_2(node(kVeh1).output()));
        note("ocu", ocu_log_lost());
        return forgot_after_s.size() == 3;
      },
      std::chrono::milliseconds(static_cast<int>(kForgetBoundSeconds * 1000)) + 5s);
  for (const char* who : {"veh2a", "veh1", "ocu"}) {
    EXPECT_TRUE(forgot_after_s.count(who)) << who << " did not forget node 2.2";
    if (forgot_after_s.count(who)) {
      EXPECT_LE(forgot_after_s[who], kForgetBoundSeconds) << who;
    }
  }

  // Restarted: who learns it again, when.
  const auto reports_before_restart = reports.size();
  node(kVeh2b).start();
  const auto restarted = Clock::now();
  std::map<std::string, double> relearnt_after_s;
  std::optional<double> reports_after_s;
  session->run_until(
      [&] {
        if (!relearnt_after_s.count("veh2a") && veh2a_lists_node_2(*session))
          relearnt_after_s["veh2a"] = seconds_since(restarted);
        if (!relearnt_after_s.count("veh1 (route)") && reached_through_veh1(through_veh1))
          relearnt_after_s["veh1 (route)"] = seconds_since(restarted);
        if (!reports_after_s && reports.size() > reports_before_restart + 2) reports_after_s = seconds_since(restarted);
        return relearnt_after_s.size() == 2 && reports_after_s;
      },
      std::chrono::milliseconds(static_cast<int>(kReportsBoundSeconds * 1000)) + 10s);
  for (const char* who : {"veh2a", "veh1 (route)"}) {
    EXPECT_TRUE(relearnt_after_s.count(who)) << who << " did not learn node 2.2 again";
    if (relearnt_after_s.count(who)) {
      EXPECT_LE(relearnt_after_s[who], kRelearnBoundSeconds) << who;
    }
  }
  EXPECT_TRUE(reports_after_s) << "the service connection on 2.2.37.1 did not recover: "
                               << session->component().subscription(subscription)->recreated << " re-creations";
  if (reports_after_s) {
    EXPECT_LE(*reports_after_s, kReportsBoundSeconds);
  }

  std::cout << "restart of node 2.2: forgotten after";
  for (const auto& [who, s] : forgot_after_s) std::cout << " " << who << " " << s << " s";
  std::cout << "; learnt again after";
  for (const auto& [who, s] : relearnt_after_s) std::cout << " " << who << " " << s << " s";
  std::cout << "; reports again after " << (reports_after_s ? std::to_string(*reports_after_s) + " s" : "never")
            << "\n";
  session->component().unsubscribe(subscription);
}

}  // namespace
}  // namespace jaus::test::network
