// A jausd with its default components (vehicle, cameras, arm) on a loopback
// address, port 3794, in a temporary directory of its own (its configuration
// and every process's log); and jausctl run against it. Shared by the
// system tests, which each start their own daemon.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "kept_operator_id.hpp"

namespace jaus::test {

class DefaultJausd {
 public:
  // `name` names the directory; the node is `subsystem`.1 at `address`:3794;
  // `more_config` is appended to its configuration (e.g. a `platform:`),
  // `more_transport` to its `transport:` map (e.g. "control_from: [...]"),
  // `more_args` to its command line (e.g. --pid-file FILE).
  DefaultJausd(const std::string& name, int subsystem, std::string address, const std::string& more_config = "",
               const std::string& more_transport = "", const std::vector<std::string>& more_args = {})
      : dir_(std::filesystem::temp_directory_path() / ("jaus-" + name + "-" + std::to_string(::getpid()))),
        address_(std::move(address)) {
    std::filesystem::create_directories(dir_);
    keep_operator_id_outside_named_ones(state_home(), std::stoi(address_.substr(address_.rfind('.') + 1)));
    const auto config = dir_ / "jausd.yaml";
    // No RA multicast group (the default joins 224.1.0.1:3794): system tests
    // run side by side on one loopback, and must not hear each other's
    // heartbeats and broadcasts; a test that wants a group names its own.
    const bool group_given = more_transport.find("multicast:") != std::string::npos;
    std::ofstream(config) << "identification: {subsystem: " << subsystem << ", node: 1}\n"
                          << "transport: {bind: " << address_ << ":3794" << (group_given ? "" : ", multicast: null")
                          << (more_transport.empty() ? "" : ", " + more_transport) << "}\n"
                          << more_config;
    std::vector<std::string> argv{JAUSD_PATH, "--config", config.string(), "--log-level", "debug"};
    argv.insert(argv.end(), more_args.begin(), more_args.end());
    process_ = std::make_unique<ChildProcess>(argv, (dir_ / "jausd.log").string());
  }
  ~DefaultJausd() {
    process_.reset();  // stopped before its directory goes
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  DefaultJausd(const DefaultJausd&) = delete;
  DefaultJausd& operator=(const DefaultJausd&) = delete;

  bool started() const { return process_->started(); }
  ChildProcess& process() { return *process_; }
  std::string output() const { return process_->output(); }
  bool output_contains(const std::string& text) const { return process_->output_contains(text); }
  bool output_shows(const std::string& text, std::chrono::milliseconds within = std::chrono::seconds(3)) const {
    return process_->output_shows(text, within);
  }
  const std::filesystem::path& dir() const { return dir_; }
  const std::string& address() const { return address_; }

  // The same with an OCU ID of the bind address's own (127.0.0.30 -> --as
  // 254.30.40.1): the node answers an ID at the endpoint it last heard it
  // from, so a query beside a controller must not share the controller's ID.
  std::unique_ptr<ChildProcess> jausctl_own_id(const std::string& log_name, std::vector<std::string> args,
                                               const std::string& bind) const {
    const std::string octet = bind.substr(bind.rfind('.') + 1, bind.find(':') - bind.rfind('.') - 1);
    return jausctl(log_name, std::move(args), bind, "254." + octet + ".40.1");
  }

  // `jausctl ARGS --to <the node> --bind BIND [--as AS]`, its output in <dir>/<log_name>.log.
  // Where jausctl keeps its operator ID here (XDG_STATE_HOME).
  std::filesystem::path state_home() const { return dir_ / "ocu-state"; }

  std::unique_ptr<ChildProcess> jausctl(const std::string& log_name, std::vector<std::string> args,
                                        const std::string& bind, const std::optional<std::string>& as = {}) const {
    args.insert(args.begin(), JAUSCTL_PATH);
    for (const std::string& option : {std::string("--to"), address_, std::string("--bind"), bind})
      args.push_back(option);
    if (as) args.insert(args.end(), {"--as", *as});
    // Its own state directory (the kept operator ID, jaus/ocu/operator_identity.hpp), never the user's.
    return std::make_unique<ChildProcess>(args, (dir_ / (log_name + ".log")).string(), ChildProcess::Stdin::inherit,
                                          std::vector<std::string>{"XDG_STATE_HOME=" + state_home().string()});
  }

 private:
  std::filesystem::path dir_;
  std::string address_;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace jaus::test
