// The SAE JAUS (JSS) baselines of issue 44, which makes JSS a dialect of the
// one message description and folds the JSS receive path into the RA one,
// and must leave both no slower:
// - BM_Jss*_EncodeDecode: jss::encode_contents + jss::decode_contents (message
//   ID, then the body) of a full message (every presence bit set), the JSS
//   twin of bench_codec. encode_contents returns a new vector: one heap
//   allocation per message today.
// - BM_JssQueryWrenchEffort_ThroughNode: one AS5669A datagram through a
//   node's whole receive path in process, as tests/load/flood_test.cpp
//   drives it: UdpLink::receive_datagram -> JSS face -> RA Query Wrench
//   Effort -> node queue -> primitive driver -> Report Wrench Effort -> face
//   -> a real datagram to the client's loopback socket.
// Each checks once, before timing, that the path it times works (the round
// trip is exact, the queries are answered), so it cannot time a failure.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <benchmark/benchmark.h>

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdlib>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "allocation_count.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"

namespace {

using namespace jaus;
using namespace std::chrono_literals;

// ---- Contents encode + decode ------------------------------------------------

// The same values as bench_codec's RA messages where the messages share fields.
jss::msg::SetWrenchEffort full_wrench_effort() {
  jss::msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = 46.24;
  m.propulsive_linear_effort_y_percent = -5.5;
  m.propulsive_linear_effort_z_percent = 0;
  m.propulsive_rotational_effort_x_percent = 1;
  m.propulsive_rotational_effort_y_percent = -2;
  m.propulsive_rotational_effort_z_percent = -76.86;
  m.resistive_linear_effort_x_percent = 10;
  m.resistive_linear_effort_y_percent = 0;
  m.resistive_linear_effort_z_percent = 0;
  m.resistive_rotational_effort_x_percent = 0;
  m.resistive_rotational_effort_y_percent = 0;
  m.resistive_rotational_effort_z_percent = 5;
  return m;
}

jss::msg::ReportGlobalPose full_global_pose() {
  jss::msg::ReportGlobalPose m;
  m.latitude_deg = 41.616;
  m.longitude_deg = -100.332;
  m.elevation_m = 1893.5;
  m.position_rms_m = 1.87;
  m.roll_rad = 0.0123;
  m.pitch_rad = -0.0456;
  m.yaw_rad = 2.5;
  m.attitude_rms_rad = 0.01;
  m.time_stamp = TimeStamp{789, 42, 37, 13, 21};
  return m;
}

jss::msg::ReportLocalPose full_local_pose() {
  jss::msg::ReportLocalPose m;
  m.x_m = 125.25;
  m.y_m = -340.5;
  m.z_m = 1.5;
  m.position_rms_m = 0.42;
  m.roll_rad = 0.0123;
  m.pitch_rad = -0.0456;
  m.yaw_rad = 2.5;
  m.attitude_rms_rad = 0.01;
  m.time_stamp = TimeStamp{789, 42, 37, 13, 21};
  return m;
}

jss::msg::SetLocalWaypoint full_local_waypoint() {
  jss::msg::SetLocalWaypoint m;
  m.x_m = 125.25;
  m.y_m = -340.5;
  m.z_m = 1.5;
  m.roll_rad = 0.0123;
  m.pitch_rad = -0.0456;
  m.yaw_rad = 2.5;
  m.waypoint_tolerance_m = 0.5;
  m.path_tolerance_m = 2;
  return m;
}

// `message` as it comes back from the wire (its values on their scale's
// steps), so one round trip must give it back exactly; nullopt if it does not
// encode and decode, or has an optional field absent.
template <class M>
std::optional<M> quantised_full(const M& message) {
  using Body = typename M::body_type;
  const auto once = jss::decode_contents<M>(jss::encode_contents(message));
  if (!once || wire::presence_of<Body>(*once) != wire::optional_mask<Body>()) return std::nullopt;
  return *once;
}

template <class M>
void encode_decode(benchmark::State& state, const M& values) {
  const std::optional<M> message = quantised_full(values);
  if (!message) {
    state.SkipWithError("the message does not round trip with every field present");
    return;
  }
  if (const auto back = jss::decode_contents<M>(jss::encode_contents(*message)); !back || !(*back == *message)) {
    state.SkipWithError("decoded body differs from the encoded one");
    return;
  }
  const std::size_t allocations_before = bench::g_allocations;
  for (auto _ : state) {
    benchmark::DoNotOptimize(*message);
    const std::vector<std::uint8_t> contents = jss::encode_contents(*message);
    auto decoded = jss::decode_contents<M>(contents);
    benchmark::DoNotOptimize(decoded);
    benchmark::ClobberMemory();
  }
  bench::count_allocations_per_item(state, allocations_before);
}

void BM_JssSetWrenchEffort_EncodeDecode(benchmark::State& state) { encode_decode(state, full_wrench_effort()); }
void BM_JssReportGlobalPose_EncodeDecode(benchmark::State& state) { encode_decode(state, full_global_pose()); }
void BM_JssReportLocalPose_EncodeDecode(benchmark::State& state) { encode_decode(state, full_local_pose()); }
void BM_JssSetLocalWaypoint_EncodeDecode(benchmark::State& state) { encode_decode(state, full_local_waypoint()); }

BENCHMARK(BM_JssSetWrenchEffort_EncodeDecode);
BENCHMARK(BM_JssReportGlobalPose_EncodeDecode);
BENCHMARK(BM_JssReportLocalPose_EncodeDecode);
BENCHMARK(BM_JssSetLocalWaypoint_EncodeDecode);

// ---- One datagram through the node ---------------------------------------------

constexpr std::uint32_t kLoopback = 0x7F000001;
const jss::JssId kJssDriver{1, 1, 33};  // the RA driver 1.1.33 (the face keeps RA IDs by default)
const jss::JssId kClient{42, 1, 1};

// jausd's shape: node 1.1 with a node manager and a primitive driver on the
// simulated vehicle, the JSS face on. Endpoint verification is off, as in
// the flood test: the client would have to answer the link's challenge first.
host::HostConfig jss_node_config() {
  host::HostConfig config;
  config.node.subsystem = 1;
  config.node.node = 1;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  config.settings.identity.subsystem_name = "bench";
  config.settings.identity.node_name = "node";
  config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "node_manager", {}, 0, {}},
                       host::ComponentSpec{"primitive_driver", 33, 1, 0, "primitive_driver", {}, 0, {}}};
  config.jss.enabled = true;
  return config;
}

// A Query Wrench Effort (every field asked for) from kClient to the driver:
// a query, so every datagram is acted on (a command from a client not in
// control would only be refused) and answered, the reply sent for real.
std::vector<std::uint8_t> query_datagram() {
  jss::JudpHeader header;
  header.source = kClient;
  header.destination = kJssDriver;
  jss::msg::QueryWrenchEffort query;
  query.presence_vector = 0x0FFF;
  return jss::make_judp_datagram(header, jss::encode_contents(query));
}

// A real client numbers its messages; with no ACK requested the face acts on
// each whatever its number, so this costs the node nothing it would not pay.
void number(std::vector<std::uint8_t>& datagram, std::uint16_t sequence) {
  datagram[datagram.size() - 2] = static_cast<std::uint8_t>(sequence & 0xFF);
  datagram[datagram.size() - 1] = static_cast<std::uint8_t>(sequence >> 8);
}

// Reports of the driver's wrench effort read from the client's socket until
// `expected` came or 5 s passed, the node polled meanwhile.
int reports_received(boost::asio::io_context& io, boost::asio::ip::udp::socket& client, int expected) {
  int reports = 0;
  std::array<std::uint8_t, 2048> buffer{};
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (reports < expected && std::chrono::steady_clock::now() < deadline) {
    io.poll();
    boost::system::error_code error;
    const std::size_t size = client.receive(boost::asio::buffer(buffer), 0, error);
    if (error) {
      std::this_thread::sleep_for(1ms);
      continue;
    }
    const auto packets = jss::decode_judp_datagram(std::span(buffer).first(size));
    if (!packets) continue;
    for (const auto& packet : *packets) {
      reports += packet.header.source == kJssDriver && packet.header.destination == kClient &&
                 jss::decode_contents<jss::msg::ReportWrenchEffort>(packet.contents).has_value();
    }
  }
  return reports;
}

void BM_JssQueryWrenchEffort_ThroughNode(benchmark::State& state) {
  boost::asio::io_context io;
  auto opened = host::NodeHost::open(jss_node_config(), io);
  if (!opened) {
    state.SkipWithError(opened.error().message().c_str());
    return;
  }
  host::NodeHost& node = **opened;
  transport::UdpLink& link = *node.udp_link();
  // The client's socket: the node learns its endpoint from the datagrams and
  // sends the reports there. Not read while timing; once its buffer is full
  // the kernel drops them, after the node has paid for each.
  boost::asio::ip::udp::socket client(
      io, boost::asio::ip::udp::endpoint(boost::asio::ip::address_v4(kLoopback), 0));
  client.non_blocking(true);
  const transport::Ipv4Endpoint from{kLoopback, client.local_endpoint().port()};

  std::vector<std::uint8_t> datagram = query_datagram();
  std::uint16_t sequence = 0;
  constexpr int kChecked = 16;
  for (int i = 0; i < kChecked; ++i) {
    number(datagram, sequence++);
    link.receive_datagram(from, datagram);
  }
  if (const int reports = reports_received(io, client, kChecked); reports != kChecked) {
    state.SkipWithError(("the node answered " + std::to_string(reports) + " of " + std::to_string(kChecked) +
                         " queries before timing")
                            .c_str());
    return;
  }

  const auto& face = *node.jss_face();
  const std::uint64_t replies_before = face.counters().messages_to_jss;
  const std::size_t allocations_before = bench::g_allocations;
  std::size_t received = 0;
  for (auto _ : state) {
    number(datagram, sequence++);
    link.receive_datagram(from, datagram);
    // The node drains its queue (1024 messages) in io.poll(), as a node
    // reading its socket would between datagrams.
    if (++received % 256 == 0) io.poll();
  }
  io.poll();
  state.SetItemsProcessed(state.iterations());
  bench::count_allocations_per_item(state, allocations_before);
  // Should be 1: each query answered (fewer: the node dropped some, and the
  // figure above is not the whole path's).
  state.counters["replies_per_msg"] =
      benchmark::Counter(static_cast<double>(face.counters().messages_to_jss - replies_before) /
                         static_cast<double>(state.iterations()));
  state.counters["queue_dropped"] = static_cast<double>(node.node().counters().queue_dropped);
  node.stop("benchmark over");
}

BENCHMARK(BM_JssQueryWrenchEffort_ThroughNode);

}  // namespace

BENCHMARK_MAIN();
