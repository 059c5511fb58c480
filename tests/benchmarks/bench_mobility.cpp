// The mobility components on a real node over loopback UDP (a NodeHost on
// 127.0.0.92:3794 running on its own thread; this program sends raw JAUS
// datagrams from 127.0.0.93, as a third-party OCU would):
//   1. Set Wrench Effort datagram sent -> Drive::apply_effort called:
//      p50 / p99 / max over N efforts (default 2,000), one at a time;
//   2. Set Emergency sent -> Drive::stop called, while another socket floods
//      the node with Query Global Pose (default 50,000 per second): p50 / p99
//      / max over 100 emergencies, and how many were not acted on;
//   3. Report Global Pose on a 100 Hz service connection, received for 5 s:
//      p50 / p99 / max of |period - 10 ms| as this program receives them.
// Usage: bench_mobility [efforts] [flood queries per second]. Prints figures; not a test.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <algorithm>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <thread>
#include <vector>

#include "jaus/components/primitive_driver.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"

#include "bench_support.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using namespace jaus;

const Address kNode{1, 1, 0, 0};
const Address kDriver{1, 1, 33, 1}, kPoseSensor{1, 1, 38, 1};
const Address kOcu{254, 1, 40, 1}, kFlooder{254, 2, 40, 1};

// The simulated vehicle, with the time of each call the driver makes.
class TimedDrive final : public components::Drive {
 public:
  explicit TimedDrive(components::Drive& inner) : inner_(inner) {}
  std::uint16_t effort_fields() const override { return inner_.effort_fields(); }
  components::DeviceSet devices() const override { return inner_.devices(); }
  components::PlatformSpecifications specifications() const override { return inner_.specifications(); }
  components::WrenchEffort apply_effort(const components::WrenchEffort& e) override {
    last_effort_at.store(Clock::now().time_since_epoch().count());
    efforts.fetch_add(1);
    return inner_.apply_effort(e);
  }
  components::DiscreteDevices set_devices(const components::DiscreteDevices& d) override {
    return inner_.set_devices(d);
  }
  void stop(double brake_percent) override {
    inner_.stop(brake_percent);
    last_stop_at.store(Clock::now().time_since_epoch().count());
    stops.fetch_add(1);
  }
  components::WrenchEffort applied_effort() const override { return inner_.applied_effort(); }
  components::DiscreteDevices device_state() const override { return inner_.device_state(); }
  components::OperationalData operational_data() override { return inner_.operational_data(); }

  std::atomic<std::uint64_t> efforts{0}, stops{0};
  std::atomic<Clock::rep> last_effort_at{0}, last_stop_at{0};

 private:
  components::Drive& inner_;
};

using bench::datagram;
using bench::figures;
double micros_since(Clock::time_point start, Clock::rep then) {
  return std::chrono::duration<double, std::micro>(Clock::time_point(Clock::duration(then)) - start).count();
}

// Waits until `counter` passes `before`, at most `limit`.
bool wait_past(const std::atomic<std::uint64_t>& counter, std::uint64_t before, std::chrono::milliseconds limit) {
  const auto until = Clock::now() + limit;
  while (counter.load() <= before) {
    if (Clock::now() > until) return false;
    std::this_thread::sleep_for(20us);  // leave the cores to the node and the flood
  }
  return true;
}

// Whether the driver is Ready with an effort applied, asked on the node's thread.
bool driving(asio::io_context& io, const components::PrimitiveDriver& driver, const components::Drive& drive) {
  std::promise<bool> answer;
  asio::post(io, [&] {
    const auto e = drive.applied_effort();
    answer.set_value(driver.state() == msg::PrimaryStatus::ready && e.propulsive_linear.x != 0);
  });
  return answer.get_future().get();
}

}  // namespace

int main(int argc, char** argv) {
  const int efforts = argc > 1 ? std::atoi(argv[1]) : 2000;
  const double flood_rate = argc > 2 ? std::atof(argv[2]) : 50'000;  // queries per second

  asio::io_context io;
  host::HostConfig config;
  config.node.subsystem = kNode.subsystem;
  config.node.node = kNode.node;
  config.link.bind = *transport::parse_endpoint("127.0.0.92:3794");
  config.settings.defaults.controller_timeout = rt::Duration::zero();  // raw datagrams answer no liveness checks
  config.vehicle.update_rate_hz = 200;  // so that a 100 Hz service connection is not capped by the source
  config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "node_manager", {}, 0, {}},
                       host::ComponentSpec{"global_pose_sensor", 38, 1, 0, "global_pose_sensor", {}, 0, {}}};
  auto opened = host::NodeHost::open(config, io);
  if (!opened) {
    std::fprintf(stderr, "bench_mobility: %s\n", opened.error().message().c_str());
    return 1;
  }
  auto& node = **opened;
  TimedDrive drive(*node.platform_as<host::ModelPlatform>()->vehicle());
  components::PrimitiveDriverOptions options;
  options.command_timeout = rt::Duration::zero();  // efforts come one at a time, at the benchmark's pace
  auto& driver =
      node.emplace<components::PrimitiveDriver>(node.component_config("primitive_driver", 33), drive, options);
  auto work = asio::make_work_guard(io);
  std::thread node_thread([&] { io.run(); });

  asio::io_context client_io;
  udp::socket ocu(client_io, udp::endpoint(asio::ip::make_address("127.0.0.93"), 0));
  const udp::endpoint node_endpoint(asio::ip::make_address("127.0.0.92"), 3794);
  ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::RequestComponentControl{{255}})), node_endpoint);
  std::this_thread::sleep_for(200ms);

  // 1. Set Wrench Effort in -> apply_effort.
  std::vector<double> effort_us;
  for (int i = 0; i < efforts; ++i) {
    msg::SetWrenchEffort effort;
    effort.propulsive_linear_effort_x_percent = 10.0 + i % 50;
    const auto bytes = datagram(kOcu, kDriver, effort);
    const auto before = drive.efforts.load();
    const auto start = Clock::now();
    ocu.send_to(asio::buffer(bytes), node_endpoint);
    if (!wait_past(drive.efforts, before, 100ms)) continue;  // lost: not counted
    effort_us.push_back(micros_since(start, drive.last_effort_at.load()));
  }
  const auto e = figures(effort_us);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // figures as they come, even into a pipe
  std::printf("Set Wrench Effort datagram -> drive called: %zu of %d, p50 %7.1f us, p99 %7.1f us, max %8.1f us\n",
              e.count, efforts, e.p50, e.p99, e.max);

  // 2. Set Emergency -> stop, under a flood of queries.
  std::atomic<bool> flooding{true};
  std::atomic<std::uint64_t> flooded{0};
  std::thread flooder([&] {
    asio::io_context flood_io;
    udp::socket socket(flood_io, udp::endpoint(asio::ip::make_address("127.0.0.94"), 0));
    const auto query = datagram(kFlooder, kPoseSensor, msg::QueryGlobalPose{{0x01FF}});
    // Paced in bursts of 100 every 100 / flood_rate seconds.
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
    // Each trial starts from a driving vehicle (Ready, effort applied): the
    // flood may drop a Clear Emergency or an effort too, so they are repeated.
    const auto ready_deadline = Clock::now() + 2s;
    while (!driving(io, driver, drive) && Clock::now() < ready_deadline) {
      ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::ClearEmergency{{1}})), node_endpoint);
      msg::SetWrenchEffort effort;
      effort.propulsive_linear_effort_x_percent = 50;
      ocu.send_to(asio::buffer(datagram(kOcu, kDriver, effort)), node_endpoint);
      std::this_thread::sleep_for(2ms);
    }
    const auto before = drive.stops.load();
    const auto start = Clock::now();
    ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::SetEmergency{{1}}, priority::kSafetyCritical)),
                node_endpoint);
    if (!wait_past(drive.stops, before, 500ms)) {
      ++lost;  // the datagram was dropped (a full socket buffer) or never acted on
      continue;
    }
    stop_us.push_back(micros_since(start, drive.last_stop_at.load()));
  }
  flooding.store(false);
  flooder.join();
  const double flood_seconds = std::chrono::duration<double>(Clock::now() - flood_start).count();
  const auto s = figures(stop_us);
  std::printf("Set Emergency -> drive stopped, under %.0f queries/s sent: %zu of %d (%d not acted on within "
              "0.5 s), p50 %7.1f us, p99 %7.1f us, max %8.1f us\n",
              static_cast<double>(flooded.load()) / flood_seconds, s.count, kEmergencies, lost, s.p50, s.p99, s.max);
  ocu.send_to(asio::buffer(datagram(kOcu, kDriver, msg::ClearEmergency{{1}})), node_endpoint);

  // 3. Report Global Pose on a 100 Hz service connection.
  udp::socket watcher(client_io, udp::endpoint(asio::ip::make_address("127.0.0.95"), 0));
  std::this_thread::sleep_for(500ms);  // the node works off what the flood left queued
  const auto create = datagram(Address{254, 3, 40, 1}, kPoseSensor,
                               msg::CreateServiceConnection{{msg::ReportGlobalPose::code, 100, 0x01FF}});
  watcher.send_to(asio::buffer(create), node_endpoint);
  std::vector<Clock::time_point> arrivals;
  std::array<std::uint8_t, 9000> buffer{};
  const auto until = Clock::now() + 5s;
  auto resend_at = Clock::now() + 200ms;
  watcher.non_blocking(true);
  while (Clock::now() < until) {
    if (arrivals.empty() && Clock::now() > resend_at) {  // the Create was lost: ask again
      watcher.send_to(asio::buffer(create), node_endpoint);
      resend_at = Clock::now() + 200ms;
    }
    boost::system::error_code ec;
    udp::endpoint from;
    const std::size_t size = watcher.receive_from(asio::buffer(buffer), from, 0, ec);
    if (ec) continue;
    auto unframed = transport::unframe(std::span(buffer).first(size));
    if (unframed && unframed->packet.header.command_code == msg::ReportGlobalPose::code)
      arrivals.push_back(Clock::now());
  }
  std::vector<double> period_error_us;
  for (std::size_t i = 1; i < arrivals.size(); ++i)
    period_error_us.push_back(
        std::abs(std::chrono::duration<double, std::micro>(arrivals[i] - arrivals[i - 1]).count() - 10'000.0));
  const auto p = figures(period_error_us);
  std::printf("Report Global Pose at 100 Hz for 5 s: %zu reports, period error p50 %7.1f us, p99 %7.1f us, "
              "max %8.1f us\n",
              arrivals.size(), p.p50, p.p99, p.max);

  // The node's own timers (heartbeats, liveness) never run out: stop the loop.
  asio::post(io, [&] {
    node.stop("benchmark done");
    io.stop();
  });
  node_thread.join();
  return 0;
}
