// clearpath-sim for the system tests: on UDP (a fixed loopback address) or a
// PTY, printing its true state every 0.1 s (--status-every) and its events
// (--events), its standard input a pipe for the hardware inputs (`estop on`,
// `pause off`, ...). The checks read what the wheels really do, not what
// jausd believes.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"

namespace jaus::test {

class ClearpathSimulator {
 public:
  using Json = nlohmann::json;
  enum class Line { udp, pty };

  // `address` is the UDP address (port 7300) for Line::udp. `run_in` goes
  // before the program (e.g. {"/usr/sbin/ip", "netns", "exec", NS}).
  ClearpathSimulator(Line line, const std::filesystem::path& dir, const std::string& name, std::string address,
                     std::vector<std::string> more = {}, std::vector<std::string> run_in = {})
      : line_(line), address_(std::move(address)) {
    std::vector<std::string> args = std::move(run_in);
    args.insert(args.end(), {CLEARPATH_SIM_PATH, "--status-every", "0.1", "--events", "--log-level", "warn"});
    if (line == Line::udp) args.insert(args.end(), {"--udp", address_ + ":7300"});
    else args.push_back("--pty");
    args.insert(args.end(), more.begin(), more.end());
    process_ = std::make_unique<ChildProcess>(args, (dir / (name + ".log")).string(), ChildProcess::Stdin::pipe);
  }
  bool started() const { return process_->started(); }
  ChildProcess& process() { return *process_; }

  // What jausd's `platform:` says to reach it (the PTY's path once it printed it).
  std::optional<std::string> platform_config() const {
    if (line_ == Line::udp) return "platform: {udp: " + address_ + ":7300}\n";
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < until) {
      std::istringstream lines(process_->output());
      for (std::string l; std::getline(lines, l);)
        if (l.rfind("pty: ", 0) == 0) return "platform: {serial: " + l.substr(5) + "}\n";
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return std::nullopt;
  }

  // A hardware input pressed (on) or released: "estop" or "pause".
  bool press(const std::string& input, bool on) { return process_->write_stdin(input + (on ? " on\n" : " off\n")); }
  // Pressed now, released `ms` later by the simulator's own timer (`pause for 50`).
  bool press_for(const std::string& input, int ms) {
    return process_->write_stdin(input + " for " + std::to_string(ms) + "\n");
  }

  // A one-way line, now: deaf (on) it ignores every frame it receives and
  // keeps sending its data; off it hears again.
  bool deafen(bool on) { return process_->write_stdin(on ? "deaf on\n" : "deaf off\n"); }

  // Every JSON line printed so far whose top-level key is `key` ("status"), oldest first.
  std::vector<Json> lines_of(const std::string& key) const {
    std::vector<Json> out;
    std::istringstream lines(process_->output());
    for (std::string l; std::getline(lines, l);) {
      if (l.empty() || l.front() != '{') continue;
      const Json j = Json::parse(l, nullptr, false);
      if (!j.is_discarded() && j.is_object() && j.contains(key)) out.push_back(key == "event" ? j : j[key]);
    }
    return out;
  }
  std::vector<Json> states() const { return lines_of("status"); }
  std::vector<Json> events() const { return lines_of("event"); }
  std::optional<Json> state() const {
    auto all = states();
    if (all.empty()) return std::nullopt;
    return all.back();
  }
  // Waits until the newest state satisfies `good`.
  bool wait_for(const std::function<bool(const Json&)>& good, std::chrono::milliseconds deadline) const {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (std::chrono::steady_clock::now() < until) {
      if (const auto s = state(); s && good(*s)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  static bool moving(const Json& s) { return s["speed_mps"].get<double>() > 0.3; }
  static bool stopped(const Json& s) { return s["left_mps"].get<double>() == 0.0 && s["right_mps"].get<double>() == 0.0; }

 private:
  Line line_;
  std::string address_;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace jaus::test
