// A jausd in a lab host's namespace, with a configuration written for it:
// its identification, the components listed (so a test knows every component
// the node must show), transport options and anything more (platform, ...).
// It can be killed (SIGKILL) and started again with the same configuration.
#pragma once

#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "../system/child_process.hpp"
#include "jaus/core/address.hpp"
#include "network_lab.hpp"

namespace jaus::test::network {

struct LabComponent {
  std::string kind;
  std::uint8_t id = 0;
  std::string more = "";  // more keys of its list entry, e.g. "authority: 1"
};

struct LabNodeSpec {
  LabHost host;
  std::uint8_t subsystem = 1;
  std::uint8_t node = 1;
  std::vector<LabComponent> components;
  std::string transport;  // more keys of `transport:`, e.g. "multicast: 224.1.0.1:3794, peers: [10.77.0.21]"
  std::string more;       // more configuration, e.g. "platform: {udp: 127.0.0.1:7300}\n"
};

class LabJausd {
 public:
  LabJausd(const NetworkLab& lab, LabNodeSpec spec, const std::filesystem::path& dir)
      : spec_(std::move(spec)), exec_(lab.exec_in(spec_.host)), config_(dir / (std::string(spec_.host.name) + ".yaml")) {
    {
      // Closed (flushed) before jausd starts: a file read half-written, or
      // empty, is a valid configuration too (the defaults: node 1.1 on
      // 0.0.0.0), and the test would run against the wrong node.
      std::ofstream out(config_);
      out << "identification: {subsystem: " << int{spec_.subsystem} << ", node: " << int{spec_.node}
          << ", subsystem_name: subsystem-" << int{spec_.subsystem} << ", node_name: " << spec_.host.name << "}\n"
          << "transport: {bind: " << spec_.host.address << ":3794"
          << (spec_.transport.empty() ? "" : ", " + spec_.transport) << "}\n"
          << "components:\n";
      for (const auto& c : spec_.components)
        out << "  - {kind: " << c.kind << (c.more.empty() ? "" : ", " + c.more) << "}\n";
      out << spec_.more;
    }
    log_ = dir / (std::string(spec_.host.name) + "-jausd");
    start();
  }
  LabJausd(const LabJausd&) = delete;
  LabJausd& operator=(const LabJausd&) = delete;

  void start() {
    std::vector<std::string> argv = exec_;
    argv.insert(argv.end(), {JAUSD_PATH, "--config", config_.string(), "--log-level", "debug"});
    process_ = std::make_unique<ChildProcess>(argv, log_.string() + "-" + std::to_string(starts_++) + ".log");
  }
  void kill() {
    process_->signal(SIGKILL);
    process_->wait(std::chrono::seconds(5));
  }

  bool started() const { return process_->started(); }
  bool running() { return !process_->wait(std::chrono::milliseconds(0)); }
  ChildProcess& process() { return *process_; }
  std::string output() const { return process_->output(); }
  const LabNodeSpec& spec() const { return spec_; }
  const std::filesystem::path& config() const { return config_; }
  jaus::Address address_of(std::uint8_t component) const { return {spec_.subsystem, spec_.node, component, 1}; }

 private:
  LabNodeSpec spec_;
  std::vector<std::string> exec_;
  std::filesystem::path config_;
  std::filesystem::path log_;
  int starts_ = 0;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace jaus::test::network
