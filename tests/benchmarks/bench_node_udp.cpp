// Round trip and throughput of a real jausd on loopback, next to bare UDP
// echoes measured in the same run (what the kernel and a loop cost alone).
//   1. Query Component Status -> Report Component Status, one at a time:
//      p50 / p99 / max over N queries (default 10,000), after 2,000 not
//      counted (routes learnt, caches and the scheduler settled);
//   2. the same with a blocking echo (a thread asleep in recvfrom, woken by
//      each datagram as jausd's event loop is) and a busy-polling echo (a
//      thread spinning on its socket: the floor, no wake-up at all);
//   3. queries per second jausd answers with up to 32 in flight, for 3 s.
// Where the kernel wakes a sleeping server decides most of a round trip: on
// the client's core it is a context switch, on the other core an
// inter-processor wake-up out of idle (some 15 us more). Left to itself the
// scheduler switches between the two within a run, so 1 and 2 are measured
// with the client and the server pinned both ways (one core, two cores), and
// once unpinned, as a user would run it; jausd is compared with the echo in
// the same placement.
// jausd is started as a child process on 127.0.0.90:3794 (its own loopback
// address, so a jausd already running on 127.0.0.1 is left alone).
// Usage: bench_node_udp [queries] [path to jausd]. Prints figures; not a test.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"

extern char** environ;

namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

const char* kNodeAddress = "127.0.0.90";
const char* kEchoAddress = "127.0.0.91";
constexpr int kWarmUp = 2000;

std::vector<std::uint8_t> query_status_datagram(std::uint16_t sequence) {
  jaus::Header h;
  h.command_code = jaus::msg::QueryComponentStatus::code;
  h.destination = jaus::Address{1, 1, 1, 1};
  h.source = jaus::Address{254, 1, 40, 1};
  h.sequence = sequence;
  std::vector<std::uint8_t> out(jaus::transport::kOpcPrefix.begin(), jaus::transport::kOpcPrefix.end());
  out.resize(out.size() + jaus::kHeaderSize);
  jaus::encode_header_unchecked(h, std::span<std::uint8_t, jaus::kHeaderSize>(out.data() + 8, jaus::kHeaderSize));
  return out;
}

bool is_status_report(std::span<const std::uint8_t> datagram) {
  auto unframed = jaus::transport::unframe(datagram);
  return unframed && unframed->packet.header.command_code == jaus::msg::ReportComponentStatus::code;
}

// jausd (transport.verify_endpoints, the default) sends an endpoint that has
// not shown it receives at its address what it sent plus an allowance of
// about 1 KiB a second: a few queries a second from a client that ignores
// ACK requests, not the thousands a second measured here. Like every JAUS
// node (and our OCU library), this client ACKs what asks for an ACK - the
// node's challenge (a Query Heartbeat Pulse) - and is then unlimited.
// Returns whether `datagram` was such a request (answered, not a reply).
bool answer_ack_request(udp::socket& socket, const udp::endpoint& from, std::span<const std::uint8_t> datagram) {
  auto unframed = jaus::transport::unframe(datagram);
  if (!unframed || unframed->packet.header.ack_nak != jaus::AckNak::ack_requested) return false;
  jaus::Header ack = unframed->packet.header;
  ack.ack_nak = jaus::AckNak::ack;
  std::swap(ack.source, ack.destination);
  ack.data_size = 0;
  ack.data_flag = jaus::DataFlag::single;
  std::vector<std::uint8_t> out(jaus::transport::kOpcPrefix.begin(), jaus::transport::kOpcPrefix.end());
  out.resize(out.size() + jaus::kHeaderSize);
  jaus::encode_header_unchecked(ack, std::span<std::uint8_t, jaus::kHeaderSize>(out.data() + 8, jaus::kHeaderSize));
  boost::system::error_code ec;
  socket.send_to(asio::buffer(out), from, 0, ec);
  return true;
}

cpu_set_t cpus(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (cpu < 0) {
    for (int c = 0; c < CPU_SETSIZE; ++c) CPU_SET(c, &set);  // unpinned: the kernel keeps what exists
  } else {
    CPU_SET(cpu, &set);
  }
  return set;
}

// Every thread of the process (jausd has its event loop and its log drain).
void pin_process(pid_t pid, int cpu) {
  const cpu_set_t set = cpus(cpu);
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec))
    sched_setaffinity(std::stoi(task.path().filename().string()), sizeof(set), &set);
}

void pin_thread(pthread_t thread, int cpu) {
  const cpu_set_t set = cpus(cpu);
  pthread_setaffinity_np(thread, sizeof(set), &set);
}

struct Figures {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::size_t lost = 0;
};

// One request at a time; a reply that does not come within 100 ms counts as lost.
Figures round_trips(udp::socket& socket, const udp::endpoint& to, int count, bool expect_status) {
  std::vector<double> micros;
  micros.reserve(static_cast<std::size_t>(count));
  std::array<std::uint8_t, 9000> buffer{};
  Figures f;
  for (int i = 0; i < count; ++i) {
    const auto datagram = query_status_datagram(static_cast<std::uint16_t>(i));
    const auto start = Clock::now();
    socket.send_to(asio::buffer(datagram), to);
    bool answered = false;
    while (!answered && Clock::now() - start < 100ms) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = socket.receive_from(asio::buffer(buffer), from, 0, ec);
      if (ec == asio::error::would_block) continue;
      if (ec) break;
      if (expect_status && answer_ack_request(socket, from, std::span(buffer).first(size))) continue;
      answered = !expect_status || is_status_report(std::span(buffer).first(size));
    }
    if (!answered) {
      ++f.lost;
      continue;
    }
    micros.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  if (micros.empty()) return f;
  std::sort(micros.begin(), micros.end());
  f.p50_us = micros[micros.size() / 2];
  f.p99_us = micros[micros.size() * 99 / 100];
  f.max_us = micros.back();
  return f;
}

double queries_per_second(udp::socket& socket, const udp::endpoint& to, std::chrono::seconds duration) {
  constexpr int kInFlight = 32;
  std::array<std::uint8_t, 9000> buffer{};
  std::size_t answered = 0;
  int in_flight = 0;
  std::uint16_t sequence = 0;
  auto last_reply = Clock::now();
  const auto start = Clock::now();
  while (Clock::now() - start < duration) {
    while (in_flight < kInFlight) {
      socket.send_to(asio::buffer(query_status_datagram(sequence++)), to);
      ++in_flight;
    }
    udp::endpoint from;
    boost::system::error_code ec;
    const std::size_t size = socket.receive_from(asio::buffer(buffer), from, 0, ec);
    if (!ec && answer_ack_request(socket, from, std::span(buffer).first(size))) continue;
    if (!ec && is_status_report(std::span(buffer).first(size))) {
      ++answered;
      --in_flight;
      last_reply = Clock::now();
    } else if (Clock::now() - last_reply > 50ms) {
      in_flight = 0;  // replies lost (a full socket buffer): refill the window
      last_reply = Clock::now();
    }
  }
  return static_cast<double>(answered) / std::chrono::duration<double>(Clock::now() - start).count();
}

void print(const char* what, const Figures& f, int count) {
  std::printf("%-34s p50 %7.1f us   p99 %7.1f us   max %8.1f us   lost %zu/%d\n", what, f.p50_us, f.p99_us,
              f.max_us, f.lost, count);
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 10000;
  const std::string jausd = argc > 2 ? argv[2] : JAUSD_PATH;

  // The node under test.
  const std::string bind = std::string(kNodeAddress) + ":3794";
  const char* child_argv[] = {jausd.c_str(), "--bind", bind.c_str(), "--log-level", "error", nullptr};
  pid_t child = 0;
  if (posix_spawn(&child, jausd.c_str(), nullptr, nullptr, const_cast<char**>(child_argv), environ) != 0) {
    std::fprintf(stderr, "cannot start %s\n", jausd.c_str());
    return 1;
  }

  asio::io_context io;
  udp::socket client(io, udp::endpoint(asio::ip::make_address_v4("127.0.0.1"), 0));
  client.non_blocking(true);
  const udp::endpoint node(asio::ip::make_address_v4(kNodeAddress), 3794);

  // Wait until the node answers (it needs a moment to start).
  bool up = false;
  for (int attempt = 0; attempt < 50 && !up; ++attempt) up = round_trips(client, node, 1, true).lost == 0;
  if (!up) {
    std::fprintf(stderr, "jausd at %s does not answer\n", bind.c_str());
    kill(child, SIGTERM);
    waitpid(child, nullptr, 0);
    return 1;
  }

  // The echoes: the same datagrams bounced by threads doing nothing else.
  std::atomic<bool> stop{false};
  udp::socket echo(io, udp::endpoint(asio::ip::make_address_v4(kEchoAddress), 0));
  echo.non_blocking(true);
  const udp::endpoint echo_at = echo.local_endpoint();
  udp::socket blocking_echo(io, udp::endpoint(asio::ip::make_address_v4(kEchoAddress), 0));
  const udp::endpoint blocking_echo_at = blocking_echo.local_endpoint();
  std::thread blocking_echo_thread([&] {
    std::array<std::uint8_t, 9000> buffer{};
    while (true) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = blocking_echo.receive_from(asio::buffer(buffer), from, 0, ec);
      if (ec || size == 0) return;  // an empty datagram ends it
      blocking_echo.send_to(asio::buffer(buffer.data(), size), from, 0, ec);
    }
  });

  auto measure = [&](const char* what, const udp::endpoint& to, bool expect_status) {
    round_trips(client, to, kWarmUp, expect_status);
    const Figures f = round_trips(client, to, count, expect_status);
    print(what, f, count);
    return f;
  };
  auto ratio = [](const Figures& of_node, const Figures& of_echo) {
    std::printf("  jausd / blocking echo:            p50 %.1fx   p99 %.1fx\n", of_node.p50_us / of_echo.p50_us,
                of_node.p99_us / of_echo.p99_us);
  };
  const bool two_cores = std::thread::hardware_concurrency() >= 2;
  std::printf("round trip over loopback, %d queries each (busy-polling client, %d not counted first):\n", count,
              kWarmUp);

  const int server_cores[] = {0, 1, -1};
  const char* placements[] = {"client and server on one core", "client and server on two cores",
                              "unpinned (the scheduler's choice)"};
  Figures node_on_two_cores;
  for (int p = 0; p < 3; ++p) {
    if (server_cores[p] == 1 && !two_cores) continue;
    pin_thread(pthread_self(), server_cores[p] < 0 ? -1 : 0);
    pin_process(child, server_cores[p]);
    pin_thread(blocking_echo_thread.native_handle(), server_cores[p]);
    std::printf("%s:\n", placements[p]);
    const Figures node_figures = measure("  jausd Query/Report Status", node, true);
    const Figures echo_figures = measure("  blocking UDP echo", blocking_echo_at, false);
    ratio(node_figures, echo_figures);
    if (server_cores[p] == 1) node_on_two_cores = node_figures;
  }
  // The floor, measured last: a spinning thread beside the others would
  // take a core from them.
  std::printf("floor, echo spinning on another core:\n");
  std::thread spinning_echo([&] {
    std::array<std::uint8_t, 9000> buffer{};
    while (!stop) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = echo.receive_from(asio::buffer(buffer), from, 0, ec);
      if (!ec) echo.send_to(asio::buffer(buffer.data(), size), from, 0, ec);
    }
  });
  pin_thread(pthread_self(), 0);
  pin_thread(spinning_echo.native_handle(), two_cores ? 1 : 0);
  const Figures floor = measure("  busy-polling UDP echo", echo_at, false);
  if (two_cores)
    std::printf("  jausd on two cores / floor:       p50 %.1fx   p99 %.1fx\n", node_on_two_cores.p50_us / floor.p50_us,
                node_on_two_cores.p99_us / floor.p99_us);
  stop = true;
  spinning_echo.join();
  client.send_to(asio::buffer(query_status_datagram(0).data(), 0), blocking_echo_at);
  blocking_echo_thread.join();
  pin_thread(pthread_self(), -1);
  pin_process(child, -1);

  std::printf("jausd answers %.0f Query Component Status per second (32 in flight, 3 s)\n",
              queries_per_second(client, node, 3s));

  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  return 0;
}
