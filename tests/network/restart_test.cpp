// A node restarted: veh2b's jausd (node 2.2: camera and arm) killed with
// SIGKILL and started again. The others forget it within the liveness
// timeout (node_timeout_s, 5 s, plus the housekeeping period): veh2a, veh1
// and the in-process OCU log "node 2.2... silent: lost". After the restart
// they learn it again: veh1 (relay: true) forwards a query from an OCU that
// reaches only veh1 to node 2.2 again (its route to it), and the OCU's
// service connection on 2.2.37.1 delivers reports again, each within a
// stated time. (veh2a's relearning is not visible from outside: a node logs
// nothing when a forgotten node is heard again at the same endpoint, a node
// manager's Report Configuration lists only its own node, and a relay does
// not forward within its own subsystem.)
#include <mutex>

#include "network_test.hpp"
#include "ocu_helpers.hpp"

namespace jaus::test::network {
namespace {

const jaus::Address kCamera{2, 2, 37, 1};
const jaus::Address kVeh2bNodeManager{2, 2, 1, 1};
constexpr double kForgetBoundSeconds = 8.0;    // node_timeout_s 5 + housekeeping + margin
constexpr double kRelearnBoundSeconds = 5.0;   // jausd's start and a heartbeat: measured 0.4 s
constexpr double kReportsBoundSeconds = 5.0;   // the client re-creates a silent connection: measured 0.5 s

// Lines of a node's log about node 2.2 ("node 2.2.0.0 silent: lost").
bool about_node_2_2(const std::string& line) {
  return line.find(" 2.2 ") != std::string::npos || line.find(" 2.2.") != std::string::npos;
}
int count_lines(const std::string& log, const std::string& what) {
  int n = 0;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    n += line.find(what) != std::string::npos && about_node_2_2(line) ? 1 : 0;
  return n;
}
constexpr const char* kLost = "silent: lost";

class Restart : public NetworkTest {
 protected:
  int ocu_lines(const std::string& what, Clock::time_point since) const {
    int n = 0;
    for (const auto& line : ocu_log) n += line.at > since && count_lines(line.text, what) > 0 ? 1 : 0;
    return n;
  }
  // Whether a query to veh2b's node manager from an OCU that reaches only one node is answered (it relays).
  bool reached(jaus::ocu::OcuSession& through) {
    return static_cast<bool>(through.request(kVeh2bNodeManager,
                                                  jaus::msg::QueryIdentification{{jaus::msg::identification::kNode}},
                                                  {jaus::msg::ReportIdentification::code}, 300ms));
  }
};

TEST_F(Restart, ANodeKilledAndRestartedIsForgottenAndRelearntAndItsServiceConnectionRecovers) {
  start_vehicles(Finding::multicast_and_peers, "relay: true");
  auto* session = open_ocu({kVeh1, kVeh2a, kVeh2b});
  ASSERT_NE(session, nullptr);
  // An OCU that reaches only veh1 (relay: true): its queries to 2.2 go through veh1's route.
  const auto open_through = [&](const LabHost& host, std::uint8_t node_id) {
    jaus::ocu::SessionOptions options;
    options.self = {254, node_id, 40, 1};
    options.to = {*jaus::transport::parse_endpoint(host.address)};
    options.bind = ocu_any_port();
    return jaus::ocu::OcuSession::open(options, session->io_context());
  };
  auto through_veh1_opened = open_through(kVeh1, 11);
  ASSERT_TRUE(through_veh1_opened) << through_veh1_opened.error().message();
  auto& through_veh1 = **through_veh1_opened;

  std::vector<Clock::time_point> reports;
  const auto subscription = session->component().subscribe<jaus::msg::ReportComponentStatus>(
      kCamera, 5, 0, [&](const jaus::Header&, const jaus::msg::ReportComponentStatus&) { reports.push_back(Clock::now()); });
  ASSERT_TRUE(session->run_until([&] { return reports.size() >= 5; }, 30s)) << node(kVeh2b).output();
  const auto until_routed = Clock::now() + 15s;
  bool veh1_routes = false;
  while (!veh1_routes && Clock::now() < until_routed) veh1_routes = reached(through_veh1);
  ASSERT_TRUE(veh1_routes) << "veh1 did not relay to 2.2 before the restart";

  // Killed: who forgets it, when.
  const auto killed = Clock::now();
  node(kVeh2b).kill();
  std::map<std::string, double> forgot_after_s;
  session->run_until(
      [&] {
        const auto note = [&](const std::string& who, bool lost) {
          if (lost && !forgot_after_s.count(who)) forgot_after_s[who] = seconds_since(killed);
        };
        note("veh2a", count_lines(node(kVeh2a).output(), kLost) > 0);
        note("veh1", count_lines(node(kVeh1).output(), kLost) > 0);
        note("ocu", ocu_lines(kLost, killed) > 0);
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
        const auto note = [&](const std::string& who, jaus::ocu::OcuSession& through) {
          if (!relearnt_after_s.count(who) && reached(through)) relearnt_after_s[who] = seconds_since(restarted);
        };
        note("veh1 (its route)", through_veh1);
        if (!reports_after_s && reports.size() > reports_before_restart + 2) reports_after_s = seconds_since(restarted);
        return relearnt_after_s.size() == 1 && reports_after_s;
      },
      std::chrono::milliseconds(static_cast<int>(kReportsBoundSeconds * 1000)) + 10s);
  for (const char* who : {"veh1 (its route)"}) {
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
