// The safety paths on real processes: a jausd (subsystem 9, node 1, on
// 127.0.0.94:3794) drives a separate clearpath-sim (127.0.0.95:7300) over UDP,
// and this program is the controller, an observer and a flooder (raw JAUS
// from 127.0.0.96, as a third-party OCU would send it). The times come from
// clearpath-sim's --events lines: their steady_ns is the steady clock this
// process reads too, so a send here and a frame received there compare.
//   1. Controller lost -> zero written: the controller drives (Set Wrench
//      Effort 60 % every 100 ms) and goes silent without a Release, as a
//      killed jausctl would; from the last effort sent to the platform's
//      zero_command. Goal: the driver's command timeout (0.5 s) + 50 ms, and
//      before the platform's own watchdog (0.5 s after the last frame it
//      heard; its bit 0x01 in the safety word), counted run by run.
//   2. Platform e-stop pressed -> wheels at zero: `estop on` on the
//      simulator's stdin while driving; from its input event to
//      wheels_stopped, and to the driver reporting Emergency (polled).
//   3. Set Emergency -> zero written while another socket floods the node
//      with Query Component Status (default 20,000 per second); then Clear
//      Emergency and the time until the driver is Ready again (the platform
//      must first confirm its emergency flag 0x08 clear).
// Each figure over N runs (default 20): p50 / p99 / max in milliseconds.
// Usage: bench_safety [runs] [flood queries per second] [jausd] [clearpath-sim].
// Prints figures; not a test. Exits 1 if a run found no stop at all.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.hpp"
#include "jaus/messages/all.hpp"
#include "piped_process.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using namespace jaus;

// Loopback addresses of their own: a jausd or clearpath-sim on 127.0.0.1 is left alone.
const char* kNodeIp = "127.0.0.94";
const char* kSimUdp = "127.0.0.95:7300";
const char* kClientIp = "127.0.0.96";
const Address kDriver{9, 1, 33, 1};
const Address kController{254, 1, 40, 1}, kObserver{254, 2, 40, 1}, kFlooder{254, 3, 40, 1};
constexpr std::uint8_t kAuthority = 10;
constexpr double kEffortPercent = 60;
constexpr auto kEffortPeriod = 100ms;
constexpr auto kDriveBefore = 800ms;  // driving at least this long before each stop: the wheels are moving
constexpr std::uint8_t kSafetyCriticalPriority = 12;
constexpr long long kWatchdogBit = 0x01;  // the platform's safety word: its command watchdog fired

constexpr std::uint8_t kReady = 1, kEmergency = 5;

const char* kConfig = R"(# bench_safety: the primitive driver on a clearpath-sim over UDP.
identification: {subsystem: 9, node: 1}
transport: {bind: 127.0.0.94:3794, multicast: null}
platform: {udp: 127.0.0.95:7300}
clearpath: {emergency_flags: 0x08}   # the driver's Emergency also sets the platform's e-stop bit
components:
  - kind: node_manager
  - kind: primitive_driver
    options: {command_timeout_s: 0.5}
logging: {level: info}
)";

double ms_between(Clock::time_point from, long long to_ns) {
  return static_cast<double>(to_ns -
                             std::chrono::duration_cast<std::chrono::nanoseconds>(from.time_since_epoch()).count()) /
         1e6;
}

// clearpath-sim's event lines, read without a JSON library: the number after `"key":`.
std::optional<long long> number_after(const std::string& line, const std::string& key) {
  const auto at = line.find("\"" + key + "\":");
  if (at == std::string::npos) return std::nullopt;
  return std::atoll(line.c_str() + at + key.size() + 3);
}
auto event_named(const std::string& name) {
  return [needle = "\"event\":\"" + name + "\""](const std::string& line) {
    return line.find(needle) != std::string::npos;
  };
}

// One JAUS address on its own UDP socket. Sends are locked: the effort
// thread and the main thread share the controller's.
class JausSocket {
 public:
  JausSocket(asio::io_context& io, Address self)
      : self_(self),
        socket_(io, udp::endpoint(asio::ip::make_address_v4(kClientIp), 0)),
        node_(asio::ip::make_address_v4(kNodeIp), 3794) {
    socket_.non_blocking(true);
  }
  template <class M>
  void send(const M& message, std::uint8_t priority = 6) {
    const auto bytes = bench::datagram(self_, kDriver, message, priority);
    std::lock_guard lock(send_mutex_);
    boost::system::error_code ec;
    socket_.send_to(asio::buffer(bytes), node_, 0, ec);
  }
  // The next M from the driver within `patience`; everything else is skipped
  // (the driver's liveness queries to its controller, late reports).
  template <class M>
  std::optional<M> receive(std::chrono::milliseconds patience) {
    const auto until = Clock::now() + patience;
    while (Clock::now() < until) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = socket_.receive_from(asio::buffer(buffer_), from, 0, ec);
      if (ec == asio::error::would_block) {
        std::this_thread::sleep_for(100us);
        continue;
      }
      if (ec) continue;
      const auto unframed = transport::unframe(std::span(buffer_).first(size));
      if (!unframed || unframed->packet.header.command_code != M::code || unframed->packet.header.source != kDriver)
        continue;
      if (auto decoded = wire::decode_payload<M>(unframed->packet.payload)) return *decoded;
    }
    return std::nullopt;
  }
  // The driver's primary status, or nothing within `patience`.
  std::optional<std::uint8_t> status(std::chrono::milliseconds patience = 200ms) {
    drain();
    send(msg::QueryComponentStatus{});
    const auto report = receive<msg::ReportComponentStatus>(patience);
    if (!report) return std::nullopt;
    return static_cast<std::uint8_t>(report->primary_status & 0x0F);
  }
  // Forget what arrived: the next answer is to the next question.
  void drain() {
    boost::system::error_code ec;
    udp::endpoint from;
    while (!ec) socket_.receive_from(asio::buffer(buffer_), from, 0, ec);
  }

 private:
  Address self_;
  udp::socket socket_;
  udp::endpoint node_;
  std::mutex send_mutex_;
  std::array<std::uint8_t, 9000> buffer_{};
};

// Polls the driver until it reports `wanted`: when the answer came, or nothing by `limit`.
std::optional<Clock::time_point> wait_for_status(JausSocket& observer, std::uint8_t wanted,
                                                 std::chrono::milliseconds limit,
                                                 std::chrono::milliseconds poll = 20ms) {
  const auto until = Clock::now() + limit;
  while (Clock::now() < until) {
    if (observer.status() == wanted) return Clock::now();
    std::this_thread::sleep_for(poll);
  }
  return std::nullopt;
}

// Control of the driver at authority 10 (a request while in control is confirmed again).
bool take_control(JausSocket& controller) {
  for (int attempt = 0; attempt < 10; ++attempt) {
    controller.drain();
    controller.send(msg::RequestComponentControl{{kAuthority}});
    if (const auto confirm = controller.receive<msg::ConfirmComponentControl>(300ms);
        confirm && confirm->response_code == 0)
      return true;
    std::this_thread::sleep_for(200ms);
  }
  return false;
}

// The controller driving: Set Wrench Effort 60 % every 100 ms on a thread
// of its own until stopped; stop() answers when the last one was sent.
class Driving {
 public:
  explicit Driving(JausSocket& controller)
      : thread_([this, &controller] {
          msg::SetWrenchEffort effort;
          effort.propulsive_linear_effort_x_percent = kEffortPercent;
          auto next = Clock::now();
          while (!stop_) {
            const auto now = Clock::now();
            controller.send(effort);
            last_sent_ = now;
            std::this_thread::sleep_until(next += kEffortPeriod);
          }
        }) {}
  ~Driving() { stop(); }
  Clock::time_point stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return last_sent_;
  }

 private:
  std::atomic<bool> stop_{false};
  Clock::time_point last_sent_{};  // written by the thread, read after the join
  std::thread thread_;
};

// Query Component Status to the driver at `rate` a second, from its own
// socket, until stopped or `limit` passes (bounded either way).
class QueryFlood {
 public:
  QueryFlood(double rate, std::chrono::milliseconds limit)
      : thread_([this, rate, limit] {
          asio::io_context io;
          udp::socket socket(io, udp::endpoint(asio::ip::make_address_v4(kClientIp), 0));
          const udp::endpoint node(asio::ip::make_address_v4(kNodeIp), 3794);
          const auto query = bench::datagram(kFlooder, kDriver, msg::QueryComponentStatus{});
          const long per_ms = std::max(1L, static_cast<long>(rate / 1000));  // a burst each millisecond
          const auto end = Clock::now() + limit;
          auto tick = Clock::now();
          while (!stop_ && Clock::now() < end) {
            for (long i = 0; i < per_ms; ++i) {
              boost::system::error_code ec;
              socket.send_to(asio::buffer(query), node, 0, ec);
            }
            sent_ += static_cast<std::uint64_t>(per_ms);
            std::this_thread::sleep_until(tick += 1ms);
          }
        }) {}
  ~QueryFlood() { stop(); }
  std::uint64_t stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return sent_;
  }

 private:
  std::atomic<bool> stop_{false};
  std::uint64_t sent_ = 0;
  std::thread thread_;
};

// Each run waits for Ready, which the driver reaches on one of the platform's
// 10 Hz safety reports; a fixed drive time would then put every stop at the
// same phase of those reports. A random part (0..100 ms) spreads them over it.
class DriveTime {
 public:
  Clock::duration next() { return kDriveBefore + std::chrono::microseconds(spread_(random_)); }

 private:
  std::mt19937 random_{27};
  std::uniform_int_distribution<int> spread_{0, 100'000};
};

void print(const char* what, const std::vector<double>& values, int runs) {
  const auto f = bench::figures(values);
  std::printf("  %-44s %2zu of %2d runs: p50 %7.1f ms, p99 %7.1f ms, max %7.1f ms\n", what, f.count, runs, f.p50, f.p99,
              f.max);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const double flood_rate = argc > 2 ? std::atof(argv[2]) : 20'000;
  const std::string jausd_path = argc > 3 ? argv[3] : JAUSD_PATH;
  const std::string sim_path = argc > 4 ? argv[4] : CLEARPATH_SIM_PATH;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  char dir_template[] = "/tmp/bench_safety_XXXXXX";
  if (!::mkdtemp(dir_template)) return 1;
  const std::filesystem::path dir = dir_template;
  std::ofstream(dir / "jausd.yaml") << kConfig;

  // The platform first: the driver stays in Initialize until it answers.
  bench::PipedProcess sim({sim_path, "--udp", kSimUdp, "--events", "--status-every", "0.1", "--log-level", "warn"}, {},
                          (dir / "clearpath-sim.log").string());
  bench::PipedProcess jausd({jausd_path, "--config", (dir / "jausd.yaml").string()}, (dir / "jausd.log").string());
  if (!sim.started() || !jausd.started()) {
    std::fprintf(stderr, "bench_safety: cannot start %s or %s\n", sim_path.c_str(), jausd_path.c_str());
    return 1;
  }
  asio::io_context io;
  JausSocket controller(io, kController), observer(io, kObserver);
  const auto started = Clock::now();
  if (!wait_for_status(observer, kReady, 15s)) {
    std::fprintf(stderr, "bench_safety: the driver %s is not Ready within 15 s (logs in %s)\n",
                 kDriver.to_string().c_str(), dir.c_str());
    return 1;
  }
  std::printf("bench_safety: jausd (driver %s on %s:3794) drives clearpath-sim on %s over UDP; Ready after %.0f ms\n",
              kDriver.to_string().c_str(), kNodeIp, kSimUdp,
              std::chrono::duration<double, std::milli>(Clock::now() - started).count());
  bool every_run_stopped = true;
  DriveTime drive_time;
  const auto not_ready = [&](const char* when) {
    std::printf("  the driver was not Ready again within 10 s %s: stopping this part\n", when);
    every_run_stopped = false;
  };

  // 1. Controller lost -> zero written, and which came first: it or the platform's watchdog.
  {
    std::vector<double> to_zero, to_wheels, to_watchdog;
    int zero_first = 0, watchdog_first = 0, no_zero = 0;
    for (int run = 0; run < runs; ++run) {
      if (!take_control(controller) || !wait_for_status(observer, kReady, 10s)) {
        not_ready("before a controller-lost run");
        break;
      }
      const auto mark = sim.line_count();
      Driving driving(controller);
      std::this_thread::sleep_for(drive_time.next());
      const auto last_sent = driving.stop();  // silent from here on, no Release: a killed controller
      const auto zero = sim.wait_for_line(mark, event_named("zero_command"), last_sent + 3s);
      // The platform's watchdog fires 0.5 s after the last frame it heard: wait past it, then look.
      std::this_thread::sleep_until(last_sent + 1500ms);
      const auto last_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(last_sent.time_since_epoch()).count();
      std::optional<long long> watchdog_ns;
      for (const auto& line : sim.lines_since(mark, event_named("safety"))) {
        const auto flags = number_after(line, "flags"), at = number_after(line, "steady_ns");
        if (flags && at && (*flags & kWatchdogBit) && *at > last_ns) {
          watchdog_ns = *at;
          break;
        }
      }
      if (watchdog_ns) to_watchdog.push_back(ms_between(last_sent, *watchdog_ns));
      if (zero) {
        const auto zero_ns = *number_after(*zero, "steady_ns");
        to_zero.push_back(ms_between(last_sent, zero_ns));
        (!watchdog_ns || zero_ns < *watchdog_ns ? zero_first : watchdog_first)++;
        if (const auto wheels = sim.wait_for_line(mark, event_named("wheels_stopped"), Clock::now()))
          to_wheels.push_back(ms_between(last_sent, *number_after(*wheels, "steady_ns")));
      } else {
        ++no_zero;
        every_run_stopped = false;
        if (watchdog_ns) ++watchdog_first;
      }
      controller.send(msg::ReleaseComponentControl{});
    }
    std::printf(
        "1. controller lost (silent, no Release) -> the platform's zero_command (goal: 0.5 s timeout + 50 ms = 550 "
        "ms)\n");
    print("last Set Wrench Effort -> zero_command", to_zero, runs);
    print("last Set Wrench Effort -> wheels_stopped", to_wheels, runs);
    print("last Set Wrench Effort -> platform watchdog", to_watchdog, runs);
    const auto over_goal = std::count_if(to_zero.begin(), to_zero.end(), [](double ms) { return ms > 550; });
    std::printf(
        "  over 550 ms: %td runs; zero before the platform's watchdog: %d runs; watchdog first: %d; "
        "no zero within 3 s: %d\n",
        over_goal, zero_first, watchdog_first, no_zero);
  }

  // 2. Platform e-stop pressed -> wheels at zero, and the driver in Emergency.
  {
    std::vector<double> to_wheels, to_emergency, release_to_ready;
    for (int run = 0; run < runs; ++run) {
      if (!take_control(controller) || !wait_for_status(observer, kReady, 10s)) {
        not_ready("before an e-stop run");
        break;
      }
      Driving driving(controller);
      std::this_thread::sleep_for(drive_time.next());
      const auto mark = sim.line_count();
      sim.write_stdin("estop on\n");
      const auto emergency_at = wait_for_status(observer, kEmergency, 3s, 1ms);
      const auto pressed = sim.wait_for_line(mark, event_named("input"), Clock::now() + 2s);
      const auto wheels = sim.wait_for_line(mark, event_named("wheels_stopped"), Clock::now() + 3s);
      driving.stop();  // before the release: a driver Ready again would move on the next effort
      if (pressed) {
        const auto pressed_ns = *number_after(*pressed, "steady_ns");
        const auto pressed_at = Clock::time_point(std::chrono::nanoseconds(pressed_ns));
        if (wheels) to_wheels.push_back(ms_between(pressed_at, *number_after(*wheels, "steady_ns")));
        if (emergency_at)
          to_emergency.push_back(std::chrono::duration<double, std::milli>(*emergency_at - pressed_at).count());
      }
      if (!pressed || !wheels) every_run_stopped = false;
      const auto released = Clock::now();
      sim.write_stdin("estop off\n");
      const auto ready = wait_for_status(observer, kReady, 10s, 5ms);
      if (!ready) {
        not_ready("after estop off");
        break;
      }
      release_to_ready.push_back(std::chrono::duration<double, std::milli>(*ready - released).count());
    }
    std::printf("2. platform e-stop pressed while driving (clearpath-sim stdin `estop on`)\n");
    print("e-stop input -> wheels_stopped", to_wheels, runs);
    print("e-stop input -> driver reports Emergency", to_emergency, runs);
    print("`estop off` written -> driver reports Ready", release_to_ready, runs);
  }

  // 3. Set Emergency -> zero written, under a flood of queries; Clear Emergency -> Ready.
  {
    std::vector<double> to_zero, clear_to_ready;
    std::uint64_t flooded = 0;
    double flooding_s = 0;
    for (int run = 0; run < runs; ++run) {
      if (!take_control(controller) || !wait_for_status(observer, kReady, 10s)) {
        not_ready("before a Set Emergency run");
        break;
      }
      Driving driving(controller);
      std::this_thread::sleep_for(kDriveBefore / 2);
      const auto flood_start = Clock::now();
      QueryFlood flood(flood_rate, 4s);
      std::this_thread::sleep_for(drive_time.next() - kDriveBefore / 2);
      const auto mark = sim.line_count();
      const auto sent = Clock::now();
      controller.send(msg::SetEmergency{{1}}, kSafetyCriticalPriority);
      const auto zero = sim.wait_for_line(mark, event_named("zero_command"), sent + 3s);
      flooded += flood.stop();
      flooding_s += std::chrono::duration<double>(Clock::now() - flood_start).count();
      driving.stop();
      if (zero)
        to_zero.push_back(ms_between(sent, *number_after(*zero, "steady_ns")));
      else
        every_run_stopped = false;
      const auto cleared = Clock::now();
      controller.send(msg::ClearEmergency{{1}}, kSafetyCriticalPriority);
      const auto ready = wait_for_status(observer, kReady, 10s, 5ms);
      if (!ready) {
        not_ready("after Clear Emergency");
        break;
      }
      clear_to_ready.push_back(std::chrono::duration<double, std::milli>(*ready - cleared).count());
    }
    std::printf(
        "3. Set Emergency (priority 12) while driving, under %.0f Query Component Status a second "
        "(%llu sent in %.1f s)\n",
        flooding_s > 0 ? static_cast<double>(flooded) / flooding_s : 0.0, static_cast<unsigned long long>(flooded),
        flooding_s);
    print("Set Emergency sent -> zero_command", to_zero, runs);
    print("Clear Emergency sent -> driver reports Ready", clear_to_ready, runs);
  }

  // jausd first: it stops the platform and drops control in order, then the platform.
  const auto jausd_exit = jausd.stop(5s);
  const auto sim_exit = sim.stop(5s);
  std::ofstream(dir / "clearpath-sim.out") << [&] {
    std::string all;
    for (const auto& line : sim.lines_since(0, [](const std::string&) { return true; })) all += line + '\n';
    return all;
  }();
  const bool clean = every_run_stopped && jausd_exit == 0 && sim_exit == 0;
  std::printf("exit status: jausd %d, clearpath-sim %d", jausd_exit.value_or(-1), sim_exit.value_or(-1));
  if (clean) {
    std::filesystem::remove_all(dir);
    std::printf("\n");
  } else {
    std::printf(" (config, logs and the simulator's lines kept in %s)\n", dir.c_str());
  }
  return clean ? 0 : 1;
}
