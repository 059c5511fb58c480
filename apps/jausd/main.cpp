// jausd: the JAUS node daemon. Reads its YAML configuration, hosts the
// configured components behind the UDP transport, and runs until SIGINT,
// SIGTERM, SIGHUP or SIGQUIT, when it shuts every component down (platform
// stopped) and exits.
//
// Exit codes: 0 after an orderly stop or a good --check-config, 2 for a bad
// configuration or command line, or a transport that cannot open (busy port),
// 1 when an exception escaped the event loop (after stopping the platform).
#include <utility>  // Boost 1.74's Asio headers need it first

#include <CLI/CLI.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <optional>

#include <unistd.h>
#include <iostream>

#include "host_config.hpp"
#include "jaus/base/version.hpp"
#include "jaus/host/metrics.hpp"
#include "jaus/host/metrics_server.hpp"
#include "logging.hpp"
#include "pid_file.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitFailure = 1;

struct CommandLine {
  std::string config_path;
  std::string bind;
  int subsystem = 0;  // 0: as configured
  int node = 0;
  std::string log_level;
  bool check_config = false;
  std::string pid_file;
};

// jausd's signals (the host installs none). Every signal that asks a process
// to end (systemctl stop, Ctrl-C, Ctrl-\, a closed terminal) ends it the same
// orderly way: the host stops (every component's stop path run), then the
// loop ends. SIGUSR1 is the local clear of emergency holds: only someone on
// the vehicle can send it (to this jausd alone: its PID file, or systemctl
// kill for the service).
class Signals {
 public:
  Signals(boost::asio::io_context& io, jaus::host::NodeHost& host)
      : io_(io), host_(host), stop_(io, SIGINT, SIGTERM, SIGHUP), local_clear_(io, SIGUSR1) {
    stop_.add(SIGQUIT);
    stop_.async_wait([this](const boost::system::error_code& ec, int signal) {
      if (ec) return;
      host_.stop(name(signal));
      io_.stop();
    });
    wait_for_local_clear();
  }

 private:
  static std::string name(int signal) {
    switch (signal) {
      case SIGINT: return "SIGINT";
      case SIGTERM: return "SIGTERM";
      case SIGHUP: return "SIGHUP";
      case SIGQUIT: return "SIGQUIT";
      default: return "signal " + std::to_string(signal);
    }
  }
  void wait_for_local_clear() {
    local_clear_.async_wait([this](const boost::system::error_code& ec, int) {
      if (ec || host_.stopped()) return;
      host_.clear_emergency_holds_locally("SIGUSR1");
      wait_for_local_clear();
    });
  }

  boost::asio::io_context& io_;
  jaus::host::NodeHost& host_;
  boost::asio::signal_set stop_;
  boost::asio::signal_set local_clear_;
};

// The command line wins over the file; the result is checked again.
jaus::Expected<void> apply_overrides(jausd::JausdConfig& config, const CommandLine& cl) {
  if (!cl.bind.empty()) {
    auto endpoint = jaus::transport::parse_endpoint(cl.bind);
    if (!endpoint)
      return jaus::unexpected(
          jaus::make_error(jaus::ErrorCode::invalid_argument, "--bind: " + endpoint.error().message()));
    config.transport.bind = *endpoint;
  }
  if (cl.subsystem != 0) config.subsystem = static_cast<std::uint8_t>(cl.subsystem);
  if (cl.node != 0) config.node = static_cast<std::uint8_t>(cl.node);
  if (!cl.log_level.empty()) config.log_level = cl.log_level;
  return jausd::validate(config);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"jausd: JAUS RA 3.x node daemon"};
  app.set_version_flag("--version", "jausd " + std::string(jaus::kVersion));
  CommandLine cl;
  app.add_option("-c,--config", cl.config_path,
                 "YAML configuration (default: built-in defaults, as config/jausd.yaml; the service reads "
                 "/etc/jaus/jausd.yaml)")
      ->type_name("FILE");  // a missing file is load_config_file's one error: "FILE: cannot open FILE: why"
  app.add_option("--bind", cl.bind, "UDP address[:port] to bind (port 3794 when left out), overrides transport.bind")
      ->type_name("ADDR[:PORT]");
  app.add_option("--subsystem", cl.subsystem, "subsystem ID, overrides identification.subsystem")
      ->type_name("1..254")
      ->check(CLI::Range(1, 254));
  app.add_option("--node", cl.node, "node ID, overrides identification.node")
      ->type_name("1..254")
      ->check(CLI::Range(1, 254));
  app.add_option("--log-level", cl.log_level, "debug | info | warn | error, overrides logging.level")
      ->type_name("LEVEL")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--pid-file", cl.pid_file,
                 "write jausd's process ID here once it listens, for the local clear: kill -USR1 \"$(cat FILE)\" "
                 "(default: $RUNTIME_DIRECTORY/jausd.pid under systemd, else none)")
      ->type_name("FILE");
  app.add_flag("--check-config", cl.check_config,
               "validate the configuration and exit: 0 when good, 2 with 'file:line: what is wrong'");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadInput;
  }

  jausd::JausdConfig config;
  const std::string source = cl.config_path.empty() ? "(defaults)" : cl.config_path;
  if (!cl.config_path.empty()) {
    auto loaded = jausd::load_config_file(cl.config_path);
    if (!loaded) {
      std::cerr << loaded.error().message() << "\n";
      return kExitBadInput;
    }
    config = std::move(*loaded);
  }
  if (auto applied = apply_overrides(config, cl); !applied) {
    std::cerr << source << ": " << applied.error().message() << "\n";
    return kExitBadInput;
  }
  const auto warnings = jausd::posture_warnings(config);
  if (cl.check_config) {
    std::cout << source << ": ok (subsystem " << int{config.subsystem} << ", node " << int{config.node} << ", "
              << config.components.size() << " components, bind " << jaus::transport::to_string(config.transport.bind)
              << (config.jss.enabled ? ", JSS on" : ", JSS off") << ")\n";
    // Valid but open: said, not refused (an operator may mean it; docs/running.md, "Who may command it").
    for (const auto& warning : warnings) std::cerr << source << ": warning: " << warning << "\n";
    return kExitOk;
  }

  auto logger = jausd::make_logger(config.log_level);
  jausd::LogDrain drain_logs_at_exit;
  const jaus::rt::LogFn log = jausd::log_function(logger);
  boost::asio::io_context io;
  auto host = jaus::host::NodeHost::open(jausd::host_config(config), io, log);
  if (!host) {
    logger->error("{}", host.error().message());
    return drain_logs_at_exit.exiting_with(kExitBadInput);
  }
  const auto& link = *(*host)->udp_link();
  logger->info("node {}.{} listening on {} ({})", int{config.subsystem}, int{config.node},
               jaus::transport::to_string(link.local_endpoint()), jaus::transport::to_string(config.transport.framing));
  // Linux reports twice the data it holds for a socket; less than asked: net.core.rmem_max capped it.
  if (const std::size_t asked = config.transport.receive_buffer_bytes;
      asked > 0 && link.receive_buffer_bytes() / 2 < asked)
    logger->info("receive buffer {} KiB per socket, {} KiB asked: net.core.rmem_max caps it (docs/deployment.md)",
                 link.receive_buffer_bytes() / 2 / 1024, asked / 1024);
  if (const auto* face = (*host)->jss_face()) {
    const auto manager = face->jss_id_of(jaus::Address{config.subsystem, config.node, 1, 1});
    logger->info("JSS (SAE JAUS, AS5669A) on {} as subsystem {}, node manager {}, group {}",
                 jaus::transport::to_string(link.local_endpoint()),
                 int{config.jss.subsystem.value_or(config.subsystem)}, manager ? manager->to_string() : "?",
                 config.jss.multicast ? jaus::transport::to_string(*config.jss.multicast) : "none");
  }
  // The counters for Prometheus (off by default; docs/running.md, "Metrics").
  std::unique_ptr<jaus::host::MetricsServer> metrics;
  if (config.metrics.listen) {
    jaus::host::MetricsServerOptions options;
    options.listen = *config.metrics.listen;
    options.token = config.metrics.token;
    auto started = jaus::host::MetricsServer::start(
        io, options, [node_host = host->get()] { return jaus::host::metrics_text(*node_host); });
    if (!started) {
      logger->error("{}", started.error().message());
      (*host)->stop("metrics cannot be served");
      return drain_logs_at_exit.exiting_with(kExitBadInput);
    }
    metrics = std::move(*started);
    logger->info("metrics on http://{}:{}/metrics{}", jaus::transport::ipv4_to_string(options.listen.address),
                 metrics->port(), options.token.empty() ? "" : " (a bearer token is needed)");
  }
  logger->info("configuration {}", source);
  for (const auto& plugin : jausd::plugin_summaries(config)) logger->info("{}", plugin);
  for (const auto& warning : warnings) logger->warn("{}", warning);
  Signals signals(io, **host);
  // Once it listens, and SIGUSR1 is the local clear (not the default, which ends a
  // process): the file says this jausd is there, and which one to signal.
  std::optional<jausd::PidFile> pid_file;
  if (const auto path = jausd::pid_file_path(cl.pid_file, std::getenv("RUNTIME_DIRECTORY"))) {
    auto written = jausd::PidFile::write(*path);
    if (!written) {
      logger->error("{}", written.error().message());
      (*host)->stop("no PID file");
      return drain_logs_at_exit.exiting_with(kExitBadInput);
    }
    pid_file.emplace(std::move(*written));
    logger->info("process ID {} in {} (kill -USR1 \"$(cat {})\": the local clear of emergency holds)",
                 static_cast<long>(::getpid()), path->string(), path->string());
  }
  // Safety: NodeHost::run ends with every component's stop path run
  // (platform commanded to stop, the zero setpoint flushed), whether a stop
  // signal or an exception ended the loop.
  return drain_logs_at_exit.exiting_with((*host)->run(io) ? kExitOk : kExitFailure);
}
