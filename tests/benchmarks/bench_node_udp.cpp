// Round trip and throughput of a real jausd on loopback, next to a bare UDP
// echo measured in the same run (what the kernel and the loop cost alone).
//   1. Query Component Status -> Report Component Status, one at a time:
//      p50 / p99 / max over N queries (default 10,000);
//   2. the same with a bare UDP echo thread;
//   3. queries per second jausd answers with up to 32 in flight, for 3 s.
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

  // The bare echo: the same datagrams bounced by a thread doing nothing else.
  std::atomic<bool> stop{false};
  udp::socket echo(io, udp::endpoint(asio::ip::make_address_v4(kEchoAddress), 0));
  echo.non_blocking(true);
  const udp::endpoint echo_at = echo.local_endpoint();
  std::thread echo_thread([&] {
    std::array<std::uint8_t, 9000> buffer{};
    while (!stop) {
      udp::endpoint from;
      boost::system::error_code ec;
      const std::size_t size = echo.receive_from(asio::buffer(buffer), from, 0, ec);
      if (!ec) echo.send_to(asio::buffer(buffer.data(), size), from, 0, ec);
    }
  });

  std::printf("round trip over loopback, %d queries each (busy-polling client):\n", count);
  print("jausd Query/Report Component Status", round_trips(client, node, count, true), count);
  print("bare UDP echo", round_trips(client, echo_at, count, false), count);
  stop = true;
  echo_thread.join();

  std::printf("jausd answers %.0f Query Component Status per second (32 in flight, 3 s)\n",
              queries_per_second(client, node, 3s));

  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  return 0;
}
