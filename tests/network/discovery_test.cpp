// Discovery across the bridge: from the `ocu` namespace, `jausctl discover
// --json` lists subsystems 1 and 2, both nodes of subsystem 2 and every
// component of each node (identified, with its services), the vehicles
// finding each other by multicast and static peers, by multicast only, or by
// static peers only. The figure is the shortest --wait that found all of it
// once the nodes were up (steps of kWaitSteps).
#include <set>

#include "network_test.hpp"

namespace jaus::test::network {
namespace {

// A complete discovery must take no longer than this --wait (the measured
// figures are about a second: docs in tests/network/README.md).
constexpr double kDiscoveryBoundSeconds = 3.0;
constexpr double kWaitSteps[] = {0.2, 0.3, 0.5, 1.0, 1.5, 2.0, 3.0};

class Discovery : public NetworkTest {
 protected:
  // jausctl discover from the OCU for `wait` seconds, reaching the vehicles as `how` says; null if it failed.
  Json discover(double wait, const std::vector<std::string>& how) {
    std::vector<std::string> args{"discover", "--json", "--wait", std::to_string(wait), "--bind",
                                  std::string(kOcu.address) + ":0"};
    args.insert(args.end(), how.begin(), how.end());
    auto child = jausctl(kOcu, "discover-" + std::to_string(runs_++), args);
    if (child->wait(std::chrono::seconds(static_cast<int>(wait) + 20)) != 0) {
      last_output_ = child->output();
      return nullptr;
    }
    const std::string out = child->output();
    last_output_ = out;
    // The JSON starts at the first line that starts with '{' (warnings may come before it).
    const auto line = out.rfind('{', 0) == 0 ? 0 : out.find("\n{");
    if (line == std::string::npos) return nullptr;
    const auto start = line == 0 ? 0 : line + 1;
    const Json j = Json::parse(out.substr(start), nullptr, false);
    return j.is_discarded() ? Json(nullptr) : j;
  }

  // What `found` lacks of the vehicles' configurations, one line each; empty when complete.
  std::vector<std::string> missing(const Json& found) {
    std::vector<std::string> out;
    if (!found.is_object() || !found.contains("subsystems")) return {"no JSON: " + last_output_};
    for (const auto& [host, node] : nodes) {
      const auto& spec = node->spec();
      const std::string where = std::to_string(spec.subsystem) + "." + std::to_string(spec.node);
      const Json* listed = nullptr;
      for (const auto& s : found["subsystems"])
        if (s["subsystem"] == spec.subsystem)
          for (const auto& n : s["nodes"])
            if (n["node"] == spec.node) listed = &n;
      if (!listed) {
        out.push_back("node " + where + " (" + host + ")");
        continue;
      }
      for (const auto& component : spec.components) {
        bool complete = false;
        for (const auto& c : (*listed)["components"])
          if (c["component"] == component.id)
            complete = !c["identification"].is_null() && !c["inputs"].empty();
        if (!complete) out.push_back(component.kind + " " + where + "." + std::to_string(component.id) + ".1");
      }
    }
    return out;
  }

  // Everything found (the nodes just started: up to 40 s), then the shortest --wait that finds it all.
  void discovers_everything(Finding finding, const std::vector<std::string>& how, const std::string& variant) {
    start_vehicles(finding);
    const auto until = Clock::now() + 40s;
    std::vector<std::string> lacking{"nothing asked yet"};
    while (!lacking.empty() && Clock::now() < until) lacking = missing(discover(kDiscoveryBoundSeconds, how));
    ASSERT_TRUE(lacking.empty()) << "not discovered within 40 s of the nodes' start: " << ::testing::PrintToString(lacking)
                                 << "\nlast output:\n" << last_output_;
    std::optional<double> shortest;
    for (const double wait : kWaitSteps) {
      if (missing(discover(wait, how)).empty()) {
        shortest = wait;
        break;
      }
    }
    ASSERT_TRUE(shortest) << variant << ": not everything within --wait " << kDiscoveryBoundSeconds
                          << ": " << ::testing::PrintToString(missing(discover(kDiscoveryBoundSeconds, how)));
    std::cout << "discovery, " << variant << ": 2 subsystems, 3 nodes, "
              << (veh1_spec(finding).components.size() + veh2a_spec(finding).components.size() +
                  veh2b_spec(finding).components.size())
              << " components complete with jausctl discover --wait " << *shortest << " s\n";
    RecordProperty("discovery_seconds", std::to_string(*shortest));
  }

  int runs_ = 0;
  std::string last_output_;
};

const std::vector<std::string> kStaticPeers{"--to", kVeh1.address, "--to", kVeh2a.address, "--to", kVeh2b.address};

TEST_F(Discovery, MulticastAndStaticPeersListEverySubsystemNodeAndComponent) {
  discovers_everything(Finding::multicast_and_peers, kStaticPeers, "multicast and static peers");
}

// The vehicles have no peers, the OCU no --to: everything is found through the group.
TEST_F(Discovery, MulticastOnlyListsEverySubsystemNodeAndComponent) {
  discovers_everything(Finding::multicast_only, {"--multicast", kMulticastGroup}, "multicast only");
}

TEST_F(Discovery, StaticPeersOnlyListEverySubsystemNodeAndComponent) {
  discovers_everything(Finding::peers_only, kStaticPeers, "static peers only");
}

}  // namespace
}  // namespace jaus::test::network
