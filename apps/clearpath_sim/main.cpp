// clearpath-sim: a simulated Clearpath platform on UDP, a serial device or a
// PTY it opens itself (`pty: /dev/pts/N` is then its first line of output).
// Standard input takes the platform's physical inputs (`estop on`, `pause off`,
// `pause for 50`) and a one-way-line fault (`deaf on|off`), see console_lines.hpp;
// standard output carries JSON lines.
#include <csignal>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <variant>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "console_lines.hpp"
#include "jaus/base/version.hpp"
#include "jaus/clearpath/sim/sim_server.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "stdin_lines.hpp"

namespace sim = jaus::clearpath::sim;
namespace console = jaus::clearpath::sim::console;

int main(int argc, char** argv) {
  CLI::App app{"clearpath-sim: simulated Clearpath platform"};
  app.set_version_flag("--version", "clearpath-sim " + std::string(jaus::kVersion));
  std::string udp, serial, drive = "differential", log_level = "info";
  bool pty = false, events = false;
  sim::FaultConfig faults;
  double latency_ms = 0, disconnect_every_s = 0, disconnect_for_s = 1.5, deaf_after_s = 0, status_every_s = 0;
  auto* udp_opt = app.add_option("--udp", udp, "Serve UDP on HOST:PORT")->type_name("HOST:PORT");
  auto* serial_opt = app.add_option("--serial", serial, "Serve on a serial device (115200 8N1)")->type_name("DEVICE");
  auto* pty_opt = app.add_flag("--pty", pty, "Open a PTY and serve on it; prints `pty: PATH` first");
  udp_opt->excludes(serial_opt, pty_opt);
  serial_opt->excludes(pty_opt);
  app.add_option("--drive", drive, "Drivetrain: differential (default) or ackermann")
      ->check(CLI::IsMember({"differential", "ackermann"}));
  app.add_option("--corrupt-rate", faults.corrupt_rate, "Probability a frame gets a flipped bit")->check(CLI::Range(0.0, 1.0));
  app.add_option("--drop-rate", faults.drop_rate, "Probability an outgoing frame is dropped")->check(CLI::Range(0.0, 1.0));
  app.add_option("--latency-ms", latency_ms, "Delay added to every outgoing frame, in milliseconds")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--disconnect-every", disconnect_every_s, "Go silent every N seconds (0 = never)")->check(CLI::NonNegativeNumber);
  app.add_option("--disconnect-for", disconnect_for_s, "Seconds each silence lasts")->check(CLI::NonNegativeNumber);
  app.add_option("--deaf-after", deaf_after_s,
                 "A one-way line: after N seconds ignore every frame received (no ACK, no action; the watchdog "
                 "stops the wheels) while still sending subscribed data (0 = never; stdin `deaf off` ends it)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--seed", faults.seed, "Seed of the fault injector (the same seed, the same faults)");
  app.add_option("--status-every", status_every_s,
                 "Print the vehicle's true state as a JSON line every N seconds (0 = never)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--events", events,
               "Print events as JSON lines with steady_ns (steady clock, ns): zero_command, wheels_stopped, "
               "safety (its flags changed), input (estop/pause set or released)");
  app.add_option("--log-level", log_level, "Log level: trace, debug, info (default), warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  spdlog::set_level(spdlog::level::from_str(log_level));
  faults.latency = std::chrono::milliseconds(static_cast<long>(latency_ms));
  faults.disconnect_every = std::chrono::milliseconds(static_cast<long>(disconnect_every_s * 1000));
  faults.disconnect_for = std::chrono::milliseconds(static_cast<long>(disconnect_for_s * 1000));
  faults.deaf_after = std::chrono::milliseconds(static_cast<long>(deaf_after_s * 1000));

  sim::ServerEndpoint endpoint;
  sim::PlatformConfig platform;
  platform.vehicle.drive = drive == "ackermann" ? sim::Drive::ackermann : sim::Drive::differential;
  if (!udp.empty()) {
    const auto colon = udp.rfind(':');
    if (colon == std::string::npos) {
      std::cerr << "error: --udp expects HOST:PORT\n";
      return 2;
    }
    endpoint.kind = sim::ServerEndpoint::Kind::udp;
    endpoint.host = udp.substr(0, colon);
    try {
      endpoint.port = static_cast<std::uint16_t>(std::stoul(udp.substr(colon + 1)));
    } catch (const std::exception&) {
      std::cerr << "error: bad port in --udp " << udp << '\n';
      return 2;
    }
  } else if (!serial.empty()) {
    endpoint.kind = sim::ServerEndpoint::Kind::serial;
    endpoint.device = serial;
    // On a serial line, subscriptions are judged against 115200 baud.
    platform.bandwidth_bytes_per_second = sim::kSerialBytesPerSecond;
  } else if (pty) {
    endpoint.kind = sim::ServerEndpoint::Kind::pty;
    platform.bandwidth_bytes_per_second = sim::kSerialBytesPerSecond;
  } else {
    std::cerr << "error: give one of --udp HOST:PORT, --serial DEVICE or --pty\n";
    return 2;
  }

  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);  // the clock and scheduler a node runs on
  sim::SimServer server(io, runtime, runtime, endpoint, platform, faults);
  if (const auto started = server.start(); !started) {
    std::cerr << "error: " << started.error().message() << '\n';
    return 1;
  }
  if (endpoint.kind == sim::ServerEndpoint::Kind::pty) std::cout << "pty: " << server.pty_path() << std::endl;
  spdlog::info("clearpath-sim: {} drive, serving on {}", drive,
               endpoint.kind == sim::ServerEndpoint::Kind::udp ? udp : (pty ? server.pty_path() : serial));
  // The platform's true state, for an operator or a test watching what the
  // wheels really do (what its client is told is another matter).
  const auto print_status_now = [&] { std::cout << console::status_line(server.platform(), server.deaf()) << std::endl; };
  std::function<void()> print_status = [&] {
    print_status_now();
    runtime.call_at(runtime.now() + std::chrono::milliseconds(static_cast<long>(status_every_s * 1000)), print_status);
  };
  // The platform's time is AsioRuntime's, the steady clock: steady_ns is comparable across processes.
  if (events) server.on_event([](const sim::PlatformEvent& e) { std::cout << console::event_line(e) << std::endl; });
  sim::StdinLines input(io, [&](const std::string& text) {
    const auto line = console::parse_line(text);
    if (const auto* press = std::get_if<console::Press>(&line)) {
      server.press(press->input, press->on);
      std::cout << console::press_answer(*press, server.platform().vehicle().safety_flags()) << std::endl;
    } else if (const auto* deaf = std::get_if<console::Deaf>(&line)) {
      server.set_deaf(deaf->on);
      spdlog::warn("clearpath-sim: {}", deaf->on ? "deaf (stdin): every frame received is ignored, data still goes"
                                                   : "hears again (stdin)");
      std::cout << console::deaf_answer(*deaf) << std::endl;
    } else if (const auto* timed = std::get_if<console::PressFor>(&line)) {
      server.press(timed->input, true);
      std::cout << console::press_answer({timed->input, true}, server.platform().vehicle().safety_flags()) << std::endl;
      // On the runtime's timer, as the subscriptions are: a report due before
      // the release goes out first, however late this process runs.
      runtime.call_at(runtime.now() + timed->duration, [&server, input = timed->input] {
        server.press(input, false);
        std::cout << console::press_answer({input, false}, server.platform().vehicle().safety_flags()) << std::endl;
      });
    } else if (std::holds_alternative<console::StatusNow>(line)) {
      print_status_now();
    } else if (const auto* unknown = std::get_if<console::Unknown>(&line)) {
      std::cout << console::error_line(*unknown) << std::endl;
    }
  });
  if (!input.start()) spdlog::warn("clearpath-sim: standard input is closed; no estop/pause lines");
  if (status_every_s > 0) print_status();
  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code&, int) {
    server.stop();
    io.stop();
  });
  io.run();
  return 0;
}
