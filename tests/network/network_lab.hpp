// The network of the suite, made of Linux network namespaces: a `switch`
// namespace holding a bridge, and one namespace per host (ocu, veh1, veh2a,
// veh2b), each with lo up, a veth to the bridge (eth0 on the host's side),
// its own address on 10.77.0.0/24 and a multicast route on eth0. The names
// carry the test process's pid and a counter (jausnet-<pid>-<n>-<host>), so
// suites run side by side; labs of dead processes are removed when a new
// one is made (with the processes left in them), and a lab removes its
// namespaces when it goes (their veths go with them).
#pragma once

#include <signal.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"

namespace jaus::test::network {

inline constexpr const char* kIp = "/usr/sbin/ip";

struct LabHost {
  const char* name;
  const char* address;
};
inline constexpr LabHost kOcu{"ocu", "10.77.0.10"};
inline constexpr LabHost kVeh1{"veh1", "10.77.0.11"};
inline constexpr LabHost kVeh2a{"veh2a", "10.77.0.21"};
inline constexpr LabHost kVeh2b{"veh2b", "10.77.0.22"};
inline constexpr LabHost kHosts[] = {kOcu, kVeh1, kVeh2a, kVeh2b};
inline constexpr const char* kMulticastGroup = "224.1.0.1:3794";

class NetworkLab {
 public:
  static constexpr const char* kPrefix = "jausnet-";

  static jaus::Expected<std::unique_ptr<NetworkLab>> create() {
    remove_labs_of_dead_processes();
    static std::atomic<int> labs = 0;
    std::unique_ptr<NetworkLab> lab(
        new NetworkLab(std::string(kPrefix) + std::to_string(::getpid()) + "-" + std::to_string(labs++) + "-"));
    if (auto made = lab->build(); !made) return jaus::unexpected(made.error());
    return lab;
  }
  ~NetworkLab() {
    for (auto it = namespaces_.rbegin(); it != namespaces_.rend(); ++it) (void)run_command({kIp, "netns", "delete", *it});
  }
  NetworkLab(const NetworkLab&) = delete;
  NetworkLab& operator=(const NetworkLab&) = delete;

  std::string namespace_of(const LabHost& host) const { return prefix_ + host.name; }
  // What runs a program in the host's namespace (`ip netns exec` execs it in place: the pid is the program's).
  std::vector<std::string> exec_in(const LabHost& host) const { return {kIp, "netns", "exec", namespace_of(host)}; }

 private:
  explicit NetworkLab(std::string prefix) : prefix_(std::move(prefix)) {}

  static void remove_labs_of_dead_processes() {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator("/var/run/netns", error)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(kPrefix, 0) != 0) continue;
      const auto pid = std::atoi(name.c_str() + std::char_traits<char>::length(kPrefix));
      if (pid <= 0 || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
      // What a killed test left running there (jausd, clearpath-sim) goes with it.
      if (auto pids = run_command({kIp, "netns", "pids", name})) {
        std::istringstream lines(*pids);
        for (int left; lines >> left;) ::kill(left, SIGKILL);
      }
      (void)run_command({kIp, "netns", "delete", name});
    }
  }

  jaus::Expected<void> add_namespace(const std::string& name) {
    auto added = run_command({kIp, "netns", "add", name});
    if (!added) return jaus::unexpected(added.error());
    namespaces_.push_back(name);
    return ip(name, {"link", "set", "lo", "up"});
  }
  static jaus::Expected<void> ip(const std::string& ns, std::vector<std::string> args) {
    args.insert(args.begin(), {kIp, "-n", ns});
    auto done = run_command(args);
    if (!done) return jaus::unexpected(done.error());
    return {};
  }

  jaus::Expected<void> build() {
    const std::string bridge_ns = prefix_ + "switch";
    if (auto r = add_namespace(bridge_ns); !r) return r;
    // No multicast snooping: the bridge floods the group to every port, as a plain switch does.
    if (auto r = ip(bridge_ns, {"link", "add", "br0", "type", "bridge", "mcast_snooping", "0"}); !r) return r;
    if (auto r = ip(bridge_ns, {"link", "set", "br0", "up"}); !r) return r;
    for (const auto& host : kHosts) {
      const std::string ns = namespace_of(host);
      if (auto r = add_namespace(ns); !r) return r;
      // The bridge's end is named after the host in the switch namespace, the host's end eth0 in its own:
      // no name is shared with the root namespace or another lab.
      if (auto r = ip(bridge_ns, {"link", "add", host.name, "type", "veth", "peer", "name", "eth0", "netns", ns}); !r)
        return r;
      if (auto r = ip(bridge_ns, {"link", "set", host.name, "master", "br0", "up"}); !r) return r;
      if (auto r = ip(ns, {"addr", "add", std::string(host.address) + "/24", "dev", "eth0"}); !r) return r;
      if (auto r = ip(ns, {"link", "set", "eth0", "up"}); !r) return r;
      if (auto r = ip(ns, {"route", "add", "224.0.0.0/4", "dev", "eth0"}); !r) return r;
    }
    return {};
  }

  std::string prefix_;
  std::vector<std::string> namespaces_;  // made so far, removed in reverse
};

}  // namespace jaus::test::network
