// The suite's fixture: a lab of its own for each test (network_lab.hpp), the
// vehicles started in it, jausctl run from a host, and an in-process OCU in
// the `ocu` namespace (this thread moves there while the test runs). Without
// namespaces (not root, no iproute2) the test is skipped with the reason, and
// under CI=true it fails instead: CI must not pass a suite it never ran.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../system/clearpath_simulator.hpp"
#include "../system/kept_operator_id.hpp"
#include "in_namespace.hpp"
#include "jaus/ocu/control_hold.hpp"
#include "jaus/ocu/session.hpp"
#include "lab_jausd.hpp"
#include "link_loss.hpp"
#include "network_lab.hpp"
#include "vehicles.hpp"

namespace jaus::test::network {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::json;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A hold streaming Set Wrench Effort (already sent by send_while_held) held
// for `d`, then released, and what the simulator's true state showed meanwhile.
struct HeldDrive {
  jaus::ocu::ControlHold::End end{};
  double held_s = 0;
  std::size_t moving = 0;   // simulator states showing the vehicle moving...
  std::size_t counted = 0;  // ...of those from 3 s in (the vehicle accelerating) to the end
  double moving_percent() const {
    return counted == 0 ? 0 : 100.0 * static_cast<double>(moving) / static_cast<double>(counted);
  }
};
inline HeldDrive hold_and_watch(jaus::ocu::ControlHold& hold, const ClearpathSimulator& simulator,
                                std::chrono::seconds d) {
  constexpr std::size_t kAcceleratingStates = 30;  // 3 s at the simulator's 0.1 s status period
  HeldDrive drive;
  const auto states_before = simulator.states().size();
  const auto started = Clock::now();
  drive.end = hold.hold(d);
  drive.held_s = seconds_since(started);
  hold.release();
  const auto states = simulator.states();
  for (std::size_t i = states_before + kAcceleratingStates; i < states.size(); ++i, ++drive.counted)
    drive.moving += ClearpathSimulator::moving(states[i]) ? 1 : 0;
  return drive;
}

class NetworkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static int tests = 0;
    dir = std::filesystem::temp_directory_path() /
          ("jaus-network-" + std::to_string(::getpid()) + "-" + std::to_string(tests++));
    auto made = NetworkLab::create();
    if (!made) {
      const std::string reason =
          "network namespaces cannot be made (root, iproute2 and nftables are needed): " + made.error().message();
      const char* ci = std::getenv("CI");
      if (ci && std::string(ci) == "true") FAIL() << reason;
      GTEST_SKIP() << reason;
    }
    lab = std::move(*made);
    std::filesystem::create_directories(dir);
  }
  void TearDown() override {
    ocu.reset();
    in_ocu_namespace.reset();
    nodes.clear();
    simulator.reset();
    lab.reset();
    std::error_code ignored;
    const bool keep = HasFailure() || std::getenv("JAUS_NETWORK_KEEP_LOGS");
    if (keep && std::filesystem::exists(dir)) std::cout << "logs kept in " << dir << "\n";
    else std::filesystem::remove_all(dir, ignored);
  }

  // clearpath-sim in veh1, on veh1's loopback.
  void start_simulator() {
    simulator = std::make_unique<ClearpathSimulator>(ClearpathSimulator::Line::udp, dir, "veh1-clearpath-sim",
                                                     kSimulatorAddress, std::vector<std::string>{},
                                                     lab->exec_in(kVeh1));
    ASSERT_TRUE(simulator->started());
  }
  LabJausd& start_node(LabNodeSpec spec) {
    const std::string host = spec.host.name;
    auto node = std::make_unique<LabJausd>(*lab, std::move(spec), dir);
    EXPECT_TRUE(node->started());
    return *(nodes[host] = std::move(node));
  }
  // The simulator and the three vehicles' nodes.
  void start_vehicles(Finding finding, const std::string& more_veh1_transport = "",
                      const std::string& more_veh2a_transport = "") {
    start_simulator();
    start_node(veh1_spec(finding, more_veh1_transport));
    start_node(veh2a_spec(finding, more_veh2a_transport));
    start_node(veh2b_spec(finding));
  }
  LabJausd& node(const LabHost& host) { return *nodes.at(host.name); }

  // jausctl ARGS run in `host`'s namespace, its output in <dir>/<log_name>.log.
  std::unique_ptr<ChildProcess> jausctl(const LabHost& host, const std::string& log_name,
                                        const std::vector<std::string>& args) {
    std::vector<std::string> argv = lab->exec_in(host);
    argv.push_back(JAUSCTL_PATH);
    argv.insert(argv.end(), args.begin(), args.end());
    // Its own state directory (the kept operator ID), never the user's.
    const auto state_home = dir / "ocu-state";
    if (!std::filesystem::exists(state_home)) keep_operator_id_outside_named_ones(state_home, 0);
    auto child = std::make_unique<ChildProcess>(argv, (dir / (log_name + ".log")).string(), ChildProcess::Stdin::inherit,
                                                std::vector<std::string>{"XDG_STATE_HOME=" + state_home.string()});
    EXPECT_TRUE(child->started());
    return child;
  }
  // The primary status of a component ("ready") asked by jausctl from the OCU's host.
  std::optional<std::string> status_of(const std::string& component, const LabHost& node_host) {
    auto child = jausctl(kOcu, "status",
                         {"status", component, "--to", node_host.address, "--bind", std::string(kOcu.address) + ":0",
                          "--timeout", "1"});
    if (child->wait(20s) != 0) return std::nullopt;
    std::istringstream lines(child->output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json j = Json::parse(line, nullptr, false);
        if (!j.is_discarded()) return j.value("primary_status", "");
      }
    return std::nullopt;
  }
  bool wait_for_status(const std::string& component, const LabHost& node_host, const std::string& status,
                       std::chrono::seconds deadline) {
    const auto until = Clock::now() + deadline;
    while (Clock::now() < until) {
      if (status_of(component, node_host) == status) return true;
      std::this_thread::sleep_for(200ms);
    }
    return false;
  }

  // The OCU host's address, any free port.
  static jaus::transport::Ipv4Endpoint ocu_any_port() {
    return {jaus::transport::parse_endpoint(kOcu.address)->address, 0};
  }

  // An OCU in this process, in the `ocu` namespace (this thread stays there
  // until the test ends), talking to `to` (static peers); its node's log
  // lines kept. Null (and a failure) when it cannot be opened.
  jaus::ocu::OcuSession* open_ocu(const std::vector<LabHost>& to,
                                  jaus::Address self = {254, 10, 40, 1}) {
    std::vector<jaus::transport::Ipv4Endpoint> endpoints;
    for (const auto& host : to) endpoints.push_back(*jaus::transport::parse_endpoint(host.address));
    return open_ocu_at(endpoints, self);
  }
  // The same, talking to these endpoints (a delay line's, say).
  jaus::ocu::OcuSession* open_ocu_at(const std::vector<jaus::transport::Ipv4Endpoint>& to,
                                     jaus::Address self = {254, 10, 40, 1}) {
    if (!in_ocu_namespace) {
      auto entered = InNamespace::enter(lab->namespace_of(kOcu));
      EXPECT_TRUE(entered) << (entered ? "" : entered.error().message());
      if (entered) in_ocu_namespace = std::move(*entered);
    }
    jaus::ocu::SessionOptions options;
    options.self = self;
    options.to = to;
    options.bind = ocu_any_port();
    options.log = [this](jaus::rt::LogLevel, const std::string& line) {
      ocu_log.push_back({Clock::now(), line});
    };
    auto opened = jaus::ocu::OcuSession::open(options);
    EXPECT_TRUE(opened) << (opened ? "" : opened.error().message());
    if (!opened) return nullptr;
    ocu = std::move(*opened);
    return ocu.get();
  }

  std::filesystem::path dir;
  std::unique_ptr<NetworkLab> lab;
  std::unique_ptr<ClearpathSimulator> simulator;
  std::map<std::string, std::unique_ptr<LabJausd>> nodes;
  std::unique_ptr<InNamespace> in_ocu_namespace;
  std::unique_ptr<jaus::ocu::OcuSession> ocu;
  struct LogLine {
    Clock::time_point at;
    std::string text;
  };
  std::vector<LogLine> ocu_log;
};

}  // namespace jaus::test::network
