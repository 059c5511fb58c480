// The bridge on a real node: a NodeHost on 127.0.0.96:3794 whose platform is a
// Clearpath simulator on a PTY (a serial line; its own thread), and raw JAUS
// datagrams from 127.0.0.97, as a third-party OCU would send them:
//   1. Set Wrench Effort datagram sent -> its Set Differential Output frame
//      written to the serial line: p50 / p99 / max over N efforts (default 1,000);
//   2. Set Emergency sent -> the zero setpoint written, while another socket
//      floods the node with Query Global Pose (default 20,000 per second):
//      p50 / p99 / max over 100 emergencies, and how many were not acted on.
// Usage: bench_bridge [efforts] [flood queries per second]. Prints figures; not a test.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <algorithm>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/sim_server.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"

#include "bench_support.hpp"

namespace {

namespace asio = boost::asio;
namespace cp = jaus::clearpath;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using namespace jaus;

const Address kNode{1, 1, 0, 0};
const Address kDriver{1, 1, 33, 1}, kPoseSensor{1, 1, 38, 1};
const Address kOcu{254, 1, 40, 1}, kFlooder{254, 2, 40, 1};

using bench::datagram;
using bench::figures;

// The differential output frames the link writes: when the last one with
// these outputs went out (written on the node's thread, read here).
struct WrittenOutputs {
  std::atomic<double> wanted{-1};  // the left output to look for, percent
  std::atomic<Clock::rep> written_at{0};
  void frame(std::span<const std::uint8_t> bytes) {
    const auto f = cp::decode_frame(bytes);
    if (!f || f->header.type != cp::SetDifferentialOutput::kType) return;
    const auto m = cp::decode(*f, cp::Direction::to_platform);
    if (!m) return;
    const auto& out = m->message.get<cp::SetDifferentialOutput>();
    if (out.left == wanted.load()) written_at.store(Clock::now().time_since_epoch().count());
  }
  // Microseconds from `start` until the wanted frame was written, or none within `limit`.
  std::optional<double> wait(Clock::time_point start, std::chrono::milliseconds limit) {
    const auto until = Clock::now() + limit;
    while (written_at.load() < start.time_since_epoch().count()) {
      if (Clock::now() > until) return std::nullopt;
      std::this_thread::sleep_for(20us);
    }
    return std::chrono::duration<double, std::micro>(Clock::time_point(Clock::duration(written_at.load())) - start).count();
  }
};

}  // namespace

int main(int argc, char** argv) {
  const int efforts = argc > 1 ? std::atoi(argv[1]) : 1000;
  const double flood_rate = argc > 2 ? std::atof(argv[2]) : 20'000;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  // The platform: a simulator on a PTY, on its own thread and clock.
  asio::io_context sim_io;
  transport::AsioRuntime sim_runtime(sim_io);
  cp::sim::ServerEndpoint endpoint;
  endpoint.kind = cp::sim::ServerEndpoint::Kind::pty;
  cp::sim::PlatformConfig platform;
  platform.bandwidth_bytes_per_second = cp::sim::kSerialBytesPerSecond;
  cp::sim::SimServer server(sim_io, sim_runtime, sim_runtime, endpoint, platform);
  if (const auto started = server.start(); !started) {
    std::fprintf(stderr, "bench_bridge: %s\n", started.error().message().c_str());
    return 1;
  }
  auto sim_work = asio::make_work_guard(sim_io);
  std::thread sim_thread([&] { sim_io.run(); });

  asio::io_context io;
  host::HostConfig config;
  config.node.subsystem = kNode.subsystem;
  config.node.node = kNode.node;
  config.link.bind = *transport::parse_endpoint("127.0.0.96:3794");
  config.settings.defaults.controller_timeout = rt::Duration::zero();  // raw datagrams answer no liveness checks
  cp::PlatformEndpoint pty;
  pty.kind = cp::PlatformEndpoint::Kind::serial;
  pty.device = server.pty_path();
  config.platform = host::clearpath_platform_settings(pty);
  config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "node_manager", {}, 0, {}},
                       host::ComponentSpec{"global_pose_sensor", 38, 1, 0, "global_pose_sensor", {}, 0, {}}};
  auto opened = host::NodeHost::open(config, io);
  if (!opened) {
    std::fprintf(stderr, "bench_bridge: %s\n", opened.error().message().c_str());
    return 1;
  }
  auto& node = **opened;
  WrittenOutputs written;
  auto& clearpath = *node.platform_as<host::ClearpathPlatform>();
  clearpath.link()->on_written([&](std::span<const std::uint8_t> frame) { written.frame(frame); });
  components::PrimitiveDriverOptions options;
  options.command_timeout = rt::Duration::zero();  // efforts come one at a time, at the benchmark's pace
  node.emplace<components::PrimitiveDriver>(node.component_config("primitive_driver", 33), *clearpath.vehicle(),
                                            options);
  auto work = asio::make_work_guard(io);
  std::thread node_thread([&] { io.run(); });

  asio::io_context client_io;
  udp::socket ocu(client_io, udp::endpoint(asio::ip::make_address("127.0.0.97"), 0));
  const udp::endpoint node_endpoint(asio::ip::make_address("127.0.0.96"), 3794);
  std::this_thread::sleep_for(1s);  // the platform heard: the driver Ready
  ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::RequestComponentControl{{255}})), node_endpoint);
  std::this_thread::sleep_for(200ms);

  // 1. Set Wrench Effort in -> its frame written.
  std::vector<double> effort_us;
  for (int i = 0; i < efforts; ++i) {
    msg::SetWrenchEffort effort;
    effort.propulsive_linear_effort_x_percent = 10.0 + i % 50;
    written.wanted.store(10.0 + i % 50);
    const auto bytes = datagram(kOcu, kDriver, effort);
    const auto start = Clock::now();
    ocu.send_to(asio::buffer(bytes), node_endpoint);
    if (auto us = written.wait(start, 100ms)) effort_us.push_back(*us);  // lost: not counted
    std::this_thread::sleep_for(2ms);  // leave the serial line its time (115200 baud)
  }
  const auto e = figures(effort_us);
  std::printf("Set Wrench Effort datagram -> serial frame written: %zu of %d, p50 %7.1f us, p99 %7.1f us, max %8.1f us\n",
              e.count, efforts, e.p50, e.p99, e.max);

  // 2. Set Emergency -> zero setpoint written, under a flood of queries.
  std::atomic<bool> flooding{true};
  std::atomic<std::uint64_t> flooded{0};
  std::thread flooder([&] {
    asio::io_context flood_io;
    udp::socket socket(flood_io, udp::endpoint(asio::ip::make_address("127.0.0.98"), 0));
    const auto query = datagram(kFlooder, kPoseSensor, msg::QueryGlobalPose{{0x01FF}});
    const auto burst_period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(100.0 / flood_rate));
    auto next = Clock::now();
    while (flooding.load()) {
      for (int i = 0; i < 100; ++i) {
        boost::system::error_code ignored;
        socket.send_to(asio::buffer(query), node_endpoint, 0, ignored);
      }
      flooded.fetch_add(100);
      next += burst_period;
      std::this_thread::sleep_until(next);
    }
  });
  const auto flood_start = Clock::now();
  std::vector<double> stop_us;
  constexpr int kEmergencies = 100;
  int lost = 0;
  for (int i = 0; i < kEmergencies; ++i) {
    // Each trial from a driving vehicle: clear, then an effort (repeated: the flood may drop them).
    written.wanted.store(50);
    const auto driving_since = Clock::now();
    for (int attempt = 0; attempt < 20 && written.written_at.load() < driving_since.time_since_epoch().count(); ++attempt) {
      ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::ClearEmergency{{1}})), node_endpoint);
      msg::SetWrenchEffort effort;
      effort.propulsive_linear_effort_x_percent = 50;
      ocu.send_to(asio::buffer(datagram(kOcu, kDriver, effort)), node_endpoint);
      std::this_thread::sleep_for(10ms);
    }
    written.wanted.store(0);
    const auto start = Clock::now();
    ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::SetEmergency{{1}}, priority::kSafetyCritical)),
                node_endpoint);
    if (auto us = written.wait(start, 500ms)) stop_us.push_back(*us);
    else ++lost;  // dropped (a full socket buffer) or never acted on
  }
  flooding.store(false);
  flooder.join();
  const double flood_seconds = std::chrono::duration<double>(Clock::now() - flood_start).count();
  const auto s = figures(stop_us);
  std::printf("Set Emergency -> zero setpoint written, under %.0f queries/s sent: %zu of %d (%d not within 0.5 s), "
              "p50 %7.1f us, p99 %7.1f us, max %8.1f us\n",
              static_cast<double>(flooded.load()) / flood_seconds, s.count, kEmergencies, lost, s.p50, s.p99, s.max);

  asio::post(io, [&] {
    node.stop("benchmark done");
    io.stop();
  });
  node_thread.join();
  sim_io.stop();
  sim_thread.join();
  return 0;
}
