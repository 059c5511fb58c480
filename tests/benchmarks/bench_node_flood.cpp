// A real jausd under a flood, as a hostile or broken network would send it,
// while an OCU keeps querying it. Prints: datagrams sent, the OCU's queries
// answered during the flood and their p50 / p99, how soon the node answers
// once the flood stops, the node's drops by reason (from its stop line),
// resident memory before and after, log lines written.
//
// The flood comes from 8 sockets on their own loopback addresses and mixes:
// garbage, truncated and malformed packets, valid queries and Resume /
// Request Control / Create Service Connection / Create Event / Set and Clear
// Emergency from ever-new spoofed JAUS sources, sources with invalid octets,
// and claims of the OCU's own ID from other hosts.
//   - At a given rate (default 100,000 datagrams a second, a third of what
//     jausd answers on 2 cores): the node must keep up, answer the OCU
//     throughout and keep the OCU's route against the forged claims.
//   - At rate 0, as fast as 8 threads can send: beyond any node's capacity on
//     the same 2 cores. The kernel drops most datagrams (the OCU's too) before
//     jausd sees them; what counts is flat memory, a bounded log, and how soon
//     the node answers again. An OCU silenced for 3 s loses its route to a
//     forged claim of its ID (the rule that lets a restarted tool come back),
//     so answers after such a flood can take up to 3 s.
// jausd runs on 127.0.0.89:3794 (a jausd on 127.0.0.1 is left alone), its log
// at info level in a temporary file.
// Usage: bench_node_flood [seconds (10)] [datagrams per second (100000; 0: as
// fast as possible)] [path to jausd]. Not a test.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <random>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "bench_support.hpp"
#include "jaus/messages/all.hpp"

extern char** environ;

namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using jaus::Address;

const char* kNodeAddress = "127.0.0.89";
const Address kOcu{254, 1, 40, 1};
const Address kManager{1, 1, 1, 1};
const Address kCommunicator{1, 1, 35, 1};

long resident_kib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

// One datagram of the flood, chosen and filled from `random`.
std::vector<std::uint8_t> flood_datagram(std::mt19937& random) {
  using namespace jaus;
  const Address spoofed{static_cast<std::uint8_t>(2 + random() % 250), static_cast<std::uint8_t>(1 + random() % 254),
                        static_cast<std::uint8_t>(1 + random() % 254), static_cast<std::uint8_t>(1 + random() % 254)};
  switch (random() % 12) {
    case 0: return {0xDE, 0xAD, 0xBE, 0xEF};                                            // not JAUS
    case 1: {                                                                          // header cut short
      auto d = bench::datagram(spoofed, kManager, msg::QueryIdentification{});
      d.resize(12);
      return d;
    }
    case 2: {  // a datagram shorter than its header says
      auto d = bench::datagram(spoofed, kManager, msg::QueryIdentification{});
      d.pop_back();
      return d;
    }
    case 3: return bench::datagram(spoofed, kCommunicator, msg::Resume{});
    case 4: return bench::datagram(spoofed, kCommunicator, msg::RequestComponentControl{{200}});
    case 5: {
      msg::CreateServiceConnection create;
      create.command_code = msg::ReportComponentStatus::code;
      create.periodic_rate_hz = 1092;
      return bench::datagram(spoofed, kCommunicator, create);
    }
    case 6: {
      msg::CreateEvent event;
      event.report_code = msg::ReportConfiguration::code;
      event.event_type = 0;
      event.requested_rate_hz = 1092;
      return bench::datagram(spoofed, kManager, event);
    }
    case 7: return bench::datagram(spoofed, kCommunicator, msg::SetEmergency{});
    case 8: return bench::datagram(spoofed, kCommunicator, msg::ClearEmergency{});
    case 9: return bench::datagram(Address{spoofed.subsystem, 0, 35, 255}, kManager, msg::QueryIdentification{});
    case 10: return bench::datagram(kOcu, kManager, msg::QueryServices{});  // the OCU's ID from another host
    default: return bench::datagram(spoofed, kManager, msg::QueryIdentification{{msg::identification::kSubsystem}});
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 10;
  const long rate = argc > 2 ? std::atol(argv[2]) : 100'000;
  const std::string jausd = argc > 3 ? argv[3] : JAUSD_PATH;

  char log_path[] = "/tmp/bench_node_flood_XXXXXX";
  const int log_fd = ::mkstemp(log_path);
  if (log_fd < 0) return 1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, log_fd, 1);
  posix_spawn_file_actions_adddup2(&actions, log_fd, 2);
  const std::string bind = std::string(kNodeAddress) + ":3794";
  const char* child_argv[] = {jausd.c_str(), "--bind", bind.c_str(), "--log-level", "info", nullptr};
  pid_t child = 0;
  const int spawned = posix_spawn(&child, jausd.c_str(), &actions, nullptr, const_cast<char**>(child_argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(log_fd);
  if (spawned != 0) {
    std::fprintf(stderr, "cannot start %s\n", jausd.c_str());
    return 1;
  }

  asio::io_context io;
  udp::socket ocu(io, udp::endpoint(asio::ip::make_address_v4("127.0.0.1"), 0));
  ocu.non_blocking(true);
  const udp::endpoint node(asio::ip::make_address_v4(kNodeAddress), 3794);
  std::array<std::uint8_t, 9000> buffer{};
  // One query, its round trip in microseconds, or nothing within `patience`.
  std::uint16_t sequence = 0;
  const auto ask = [&](std::chrono::milliseconds patience) -> std::optional<double> {
    auto query = jaus::bench::datagram(kOcu, kManager, jaus::msg::QueryComponentStatus{});
    const auto start = Clock::now();
    ocu.send_to(asio::buffer(query), node);
    ++sequence;
    while (Clock::now() - start < patience) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = ocu.receive_from(asio::buffer(buffer), from, 0, ec);
      if (ec == asio::error::would_block) {
        std::this_thread::sleep_for(20us);
        continue;
      }
      auto unframed = jaus::transport::unframe(std::span(buffer).first(ec ? 0 : size));
      if (unframed && unframed->packet.header.command_code == jaus::msg::ReportComponentStatus::code)
        return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    }
    return std::nullopt;
  };
  bool up = false;
  for (int attempt = 0; attempt < 50 && !up; ++attempt) up = ask(100ms).has_value();
  if (!up) {
    std::fprintf(stderr, "jausd at %s does not answer (log: %s)\n", bind.c_str(), log_path);
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    return 1;
  }
  std::this_thread::sleep_for(500ms);
  const long rss_before = resident_kib(child);

  // The flood: 8 sockets on their own addresses. Paced, one thread sends a
  // burst every millisecond; unbounded, a thread per socket sends as fast as
  // it can. The datagrams are made before, so the time goes to sending.
  constexpr int kSockets = 8;
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> sent{0};
  auto flood = [&](std::vector<int> sockets_of_thread) {
    asio::io_context flood_io;
    std::vector<udp::socket> sockets;
    std::vector<std::vector<std::vector<std::uint8_t>>> datagrams;
    for (int s : sockets_of_thread) {
      sockets.emplace_back(flood_io, udp::endpoint(asio::ip::make_address_v4("127.0.0." + std::to_string(100 + s)), 0));
      std::mt19937 random(static_cast<unsigned>(s + 1));
      auto& mine = datagrams.emplace_back();
      for (int i = 0; i < 4096; ++i) mine.push_back(flood_datagram(random));
    }
    const long per_tick = rate / 1000;  // a burst each millisecond (paced)
    auto tick = Clock::now();
    std::uint64_t count = 0;
    std::size_t next = 0;
    while (!stop) {
      const long burst = rate > 0 ? std::max(1L, per_tick) : 256;
      for (long i = 0; i < burst; ++i, ++next) {
        const std::size_t s = next % sockets.size();
        boost::system::error_code ec;
        sockets[s].send_to(asio::buffer(datagrams[s][(next / sockets.size()) % 4096]), node, 0, ec);
        ++count;
      }
      if (rate > 0) std::this_thread::sleep_until(tick += 1ms);
    }
    sent += count;
  };
  std::vector<std::thread> flooders;
  if (rate > 0) {
    flooders.emplace_back(flood, std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7});
  } else {
    for (int s = 0; s < kSockets; ++s) flooders.emplace_back(flood, std::vector<int>{s});
  }
  std::vector<double> answered;
  std::size_t unanswered = 0;
  const auto flood_end = Clock::now() + std::chrono::seconds(seconds);
  while (Clock::now() < flood_end) {
    if (auto micros = ask(500ms))
      answered.push_back(*micros);
    else
      ++unanswered;
    std::this_thread::sleep_for(10ms);
  }
  stop = true;
  for (auto& f : flooders) f.join();
  // How soon the node answers again (its queue drained, the OCU's route back).
  const auto flood_stopped = Clock::now();
  std::optional<double> answers_after_ms;
  while (!answers_after_ms && Clock::now() - flood_stopped < 10s)
    if (ask(200ms)) answers_after_ms = std::chrono::duration<double, std::milli>(Clock::now() - flood_stopped).count();
  std::this_thread::sleep_for(500ms);
  const long rss_after = resident_kib(child);

  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  std::ifstream log(log_path);
  std::string line, stop_line;
  std::size_t lines = 0;
  while (std::getline(log, line)) {
    ++lines;
    if (line.find("stopped (SIGTERM)") != std::string::npos) stop_line = line;
  }
  ::unlink(log_path);

  const auto f = jaus::bench::figures(answered);
  std::printf("flood of %d s from %d sockets (%s): %llu datagrams sent (%.0f per second)\n", seconds, kSockets,
              rate > 0 ? "paced" : "as fast as possible", static_cast<unsigned long long>(sent.load()),
              static_cast<double>(sent.load()) / seconds);
  std::printf("OCU queries during the flood: %zu answered, %zu not within 500 ms; p50 %.0f us, p99 %.0f us, max %.0f us\n",
              f.count, unanswered, f.p50, f.p99, f.max);
  if (answers_after_ms)
    std::printf("answers after the flood: yes, %.0f ms after it stopped\n", *answers_after_ms);
  else
    std::printf("answers after the flood: NO (not within 10 s)\n");
  std::printf("resident memory: %ld KiB before, %ld KiB after\n", rss_before, rss_after);
  std::printf("log lines written: %zu\n", lines);
  std::printf("jausd's stop line: %s\n", stop_line.empty() ? "(none)" : stop_line.c_str());
  std::printf("exit status: %d\n", WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
  return answers_after_ms ? 0 : 1;
}
