// A node under a flood: a million datagrams (a tenth of that under the
// sanitizers, which run the same paths some 40 times slower) from random
// sources and codes (queries, malformed and garbage packets, commands from
// non-controllers and from sources spoofing the controller, control requests,
// emergencies, event and service connection requests, invalid sources) go
// through the UDP link's whole receive path in process, while an OCU on real
// loopback sockets holds control of the driver and queries the node. Every
// table stays within its limit, the heap stops growing once the tables are
// full, the log stays a few hundred lines, and the OCU is answered and keeps
// control throughout.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <cstddef>
#include <cstdlib>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JAUS_FLOOD_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define JAUS_FLOOD_TEST_ASAN 1
#endif
#ifdef JAUS_FLOOD_TEST_ASAN
#if __has_include(<sanitizer/allocator_interface.h>)
#include <sanitizer/allocator_interface.h>
#else
// GCC ships no allocator_interface.h; its libasan has the function all the same.
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif
#else
#include <malloc.h>
#endif

#include "jaus/components/node_manager.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/ocu/control_hold.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::host {
namespace {

using namespace std::chrono_literals;

#ifdef JAUS_FLOOD_TEST_ASAN
constexpr int kDefaultDatagrams = 100'000;  // still fills every table many times over
#else
constexpr int kDefaultDatagrams = 1'000'000;
#endif

// JAUS_FLOOD_DATAGRAMS=N sends N instead (a million under the sanitizers
// takes about a minute on 2 cores).
int datagrams_to_send() {
  const char* text = std::getenv("JAUS_FLOOD_DATAGRAMS");
  if (text == nullptr) return kDefaultDatagrams;
  const int n = std::atoi(text);
  return n >= 10'000 ? n : kDefaultDatagrams;
}

// Bytes the program has allocated and not freed (ASan's own count under the
// sanitizer, glibc's otherwise).
std::size_t heap_in_use() {
#ifdef JAUS_FLOOD_TEST_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  return mallinfo2().uordblks;
#endif
}

constexpr Address kManager{1, 1, 1, 1};
constexpr Address kCommunicator{1, 1, 35, 1};
constexpr Address kDriver{1, 1, 33, 1};
constexpr Address kPose{1, 1, 38, 1};
constexpr Address kVelocity{1, 1, 42, 1};
constexpr Address kOcu{254, 1, 40, 1};
constexpr std::uint32_t kLoopback = 0x7F000001;

// The flood: each call makes the next datagram and says where it claims to
// come from (127.0.0.100-107, not the OCU's address, as other hosts would).
class Flood {
 public:
  explicit Flood(std::uint32_t seed) : random_(seed) {}

  std::span<const std::uint8_t> next(transport::Ipv4Endpoint& from) {
    from = transport::Ipv4Endpoint{kLoopback + 99 + pick(8), static_cast<std::uint16_t>(40000 + pick(1000))};
    const Address source = random_source();
    const Address to = random_destination();
    const std::uint32_t kind = pick(100);
    if (kind < 25) return query(source, to);
    if (kind < 35) return command(source, to);
    if (kind < 42) return command(kOcu, kDriver);  // spoofing the controller, from another host
    if (kind < 48) return message(source, to, msg::RequestComponentControl{{static_cast<std::uint8_t>(pick(256))}});
    if (kind < 50) return message(source, to, msg::ReleaseComponentControl{});
    if (kind < 54) return message(source, to, msg::SetEmergency{});
    if (kind < 57) return message(source, to, msg::ClearEmergency{});
    if (kind < 63) return event_request(source);
    if (kind < 69) return service_connection_request(source, to);
    if (kind < 72)
      return message(source, to,
                     msg::TerminateServiceConnection{
                         {static_cast<std::uint16_t>(pick(0x10000)), static_cast<std::uint8_t>(pick(256))}});
    if (kind < 80) return malformed(source, to);
    if (kind < 90) return garbage();
    Address invalid = source;  // a source no one can answer
    (pick(2) ? invalid.subsystem : invalid.component) = pick(2) ? 0 : 255;
    return query(invalid, to);
  }

 private:
  std::uint32_t pick(std::uint32_t n) { return static_cast<std::uint32_t>(random_() % n); }
  std::uint8_t octet() { return static_cast<std::uint8_t>(1 + pick(254)); }
  Address random_source() { return Address{static_cast<std::uint8_t>(2 + pick(200)), octet(), octet(), octet()}; }
  Address random_destination() {
    static constexpr Address kTargets[] = {
        kManager, kCommunicator, kDriver, kPose, kVelocity, Address{1, 1, 255, 255}, Address{255, 255, 255, 255}};
    return kTargets[pick(std::size(kTargets))];
  }

  template <class M>
  std::span<const std::uint8_t> message(const Address& source, const Address& to, const M& m) {
    Header header;
    header.source = source;
    header.destination = to;
    auto size = wire::encode_message(header, m, packet_);
    if (!size) throw std::logic_error(size.error().message());
    return framed(*size);
  }
  std::span<const std::uint8_t> framed(std::size_t packet_size) {
    const transport::FramePrefix prefix = transport::frame_prefix(transport::Framing::opc, packet_size);
    datagram_.assign(prefix.view().begin(), prefix.view().end());
    datagram_.insert(datagram_.end(), packet_.begin(), packet_.begin() + static_cast<std::ptrdiff_t>(packet_size));
    return datagram_;
  }

  std::span<const std::uint8_t> query(const Address& source, const Address& to) {
    switch (pick(6)) {
      case 0:
        return message(source, to, msg::QueryComponentStatus{});
      case 1:
        return message(source, to, msg::QueryHeartbeatPulse{});
      case 2:
        return message(source, to, msg::QueryIdentification{{static_cast<std::uint8_t>(1 + pick(4))}});
      case 3:
        return message(source, to, msg::QueryServices{});
      case 4:
        return message(source, to, msg::QueryGlobalPose{{static_cast<std::uint16_t>(pick(0x10000))}});
      default:
        return message(source, to, msg::QueryComponentControl{});
    }
  }
  std::span<const std::uint8_t> command(const Address& source, const Address& to) {
    switch (pick(4)) {
      case 0: {
        msg::SetWrenchEffort effort;
        effort.propulsive_linear_effort_x_percent = 100;
        effort.propulsive_rotational_effort_z_percent = -50;
        return message(source, to, effort);
      }
      case 1:
        return message(source, to, msg::Resume{});
      case 2:
        return message(source, to, msg::Standby{});
      default:
        return message(source, to, msg::SetComponentAuthority{{static_cast<std::uint8_t>(pick(256))}});
    }
  }
  std::span<const std::uint8_t> event_request(const Address& source) {
    msg::CreateEvent create;
    create.request_id = static_cast<std::uint8_t>(pick(256));
    create.report_code = pick(2) ? msg::ReportConfiguration::code : msg::ReportSubsystemList::code;
    create.event_type = static_cast<std::uint8_t>(pick(2));  // periodic or every change
    // The limits under test are counts; low rates keep the reports they start
    // from dominating a run under the sanitizers.
    create.requested_rate_hz = 0.1 + pick(10) / 10.0;
    return message(source, kManager, create);
  }
  std::span<const std::uint8_t> service_connection_request(const Address& source, const Address& to) {
    msg::CreateServiceConnection create;
    create.command_code = pick(2) ? msg::ReportGlobalPose::code : msg::ReportComponentStatus::code;
    create.periodic_rate_hz = 0.1 + pick(20) / 10.0;  // (as for events)
    create.presence_vector = pick(0x200);
    return message(source, pick(2) ? kPose : to, create);
  }
  // A valid header whose payload is cut short or runs on.
  std::span<const std::uint8_t> malformed(const Address& source, const Address& to) {
    msg::SetWrenchEffort effort;
    effort.propulsive_linear_effort_x_percent = 100;
    Header header;
    header.source = source;
    header.destination = to;
    auto size = wire::encode_message(header, effort, packet_);
    if (!size) throw std::logic_error(size.error().message());
    const std::size_t payload = *size - kHeaderSize;
    const std::size_t cut = pick(2) ? pick(static_cast<std::uint32_t>(payload)) : payload + 1 + pick(8);
    header.command_code = static_cast<std::uint16_t>(pick(2) ? msg::SetWrenchEffort::code : 0x0405 + pick(8));
    header.data_size = static_cast<std::uint16_t>(cut);
    encode_header_unchecked(header, std::span(packet_).first<kHeaderSize>());
    return framed(kHeaderSize + cut);
  }
  std::span<const std::uint8_t> garbage() {
    datagram_.resize(pick(64));
    for (auto& byte : datagram_) byte = static_cast<std::uint8_t>(random_());
    if (pick(2) && datagram_.size() > 8) std::copy_n("JAUS01.0", 8, datagram_.begin());  // framing, then junk
    return datagram_;
  }

  std::mt19937 random_;
  std::vector<std::uint8_t> packet_ = std::vector<std::uint8_t>(kHeaderSize + kMaxPayloadSize);
  std::vector<std::uint8_t> datagram_;
};

HostConfig flooded_node_config() {
  HostConfig config;
  config.node.subsystem = 1;
  config.node.node = 1;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  config.settings.identity.subsystem_name = "flooded";
  config.settings.identity.node_name = "node";
  auto spec = [](const char* kind, const Address& at) {
    return ComponentSpec{kind, at.component, 1, 0, kind, {}, 0, {}};
  };
  config.components = {spec("node_manager", kManager), spec("communicator", kCommunicator),
                       spec("primitive_driver", kDriver), spec("global_pose_sensor", kPose),
                       spec("velocity_state_sensor", kVelocity)};
  return config;
}

TEST(NodeUnderFlood, EveryTableStaysBoundedTheHeapFlatAndTheOcuAnsweredAndInControl) {
  const int datagrams = datagrams_to_send();
  constexpr int kCheckpoints = 10;
  boost::asio::io_context io;
  std::size_t log_lines = 0;
  std::map<std::string, std::size_t> lines_by_start;  // what the log says most, if it says too much
  std::vector<std::string> control_lines;              // who had control when, if the OCU loses it
  auto count_lines = [&](rt::LogLevel, const std::string& line) {
    ++log_lines;
    ++lines_by_start[line.substr(0, 60)];
    if (line.find("control") != std::string::npos && control_lines.size() < 20) control_lines.push_back(line);
  };
  auto host = NodeHost::open(flooded_node_config(), io, count_lines);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& node = **host;

  ocu::SessionOptions options;
  options.self = kOcu;
  options.authority = 255;  // no flooded request can take control over it
  options.to = {node.udp_link()->local_endpoint()};
  options.bind = transport::Ipv4Endpoint{kLoopback, 0};
  auto session = ocu::OcuSession::open(options, &io);
  ASSERT_TRUE(session) << session.error().message();
  ocu::ControlHold hold(**session, kDriver, 255);
  ASSERT_EQ(hold.request(2s).outcome, ocu::ControlHold::Outcome::granted);

  // Queries of the OCU, answered whatever the flood does.
  auto answered = [&](const Address& to, auto query, std::uint16_t reply) {
    auto received = (*session)->request(to, query, {reply}, 5s);
    return received.has_value();
  };
  auto controller_is_the_ocu = [&] {
    auto received = (*session)->request(kDriver, msg::QueryComponentControl{}, {msg::ReportComponentControl::code}, 5s);
    if (!received) return false;
    auto report = wire::decode_payload<msg::ReportComponentControl>(received->payload);
    return report && report->controller == kOcu;
  };

  auto* manager = dynamic_cast<components::NodeManager*>(node.node().find(kManager));
  ASSERT_NE(manager, nullptr);
  const auto& link = *node.udp_link();
  const auto& routes = transport::RouteTableOptions{};
  std::vector<std::size_t> heap;
  // 32,768 different datagrams (far more sources than any table holds),
  // made once and sent in turn: the time goes to the node, not the generator.
  struct Prepared {
    transport::Ipv4Endpoint from;
    std::vector<std::uint8_t> bytes;
  };
  std::vector<Prepared> pool(32768);
  Flood flood(20261124);
  for (auto& prepared : pool) {
    const auto datagram = flood.next(prepared.from);
    prepared.bytes.assign(datagram.begin(), datagram.end());
  }
  const auto started = std::chrono::steady_clock::now();
  constexpr auto kPollEvery = 20ms;
  auto last_poll = started;
  std::size_t next = 0;
  for (int checkpoint = 1; checkpoint <= kCheckpoints; ++checkpoint) {
    for (int i = 0; i < datagrams / kCheckpoints; ++i) {
      const Prepared& datagram = pool[next++ % pool.size()];
      node.udp_link()->receive_datagram(datagram.from, datagram.bytes);
      // The node drains its queue, timers run, the OCU's socket is read:
      // every 512 datagrams (the node's queue holds them) and at least every
      // kPollEvery, as a node reading its socket takes the OCU's datagrams
      // among the flood's. Under the sanitizers on a loaded 2-core machine
      // 512 datagrams can take over a second; the driver's queries to its
      // controller and the answers then wait that long at each end, and a CI
      // run saw the driver find its controller silent for its timeout (3 s).
      if (i % 512 == 0 || (i % 16 == 0 && std::chrono::steady_clock::now() - last_poll >= kPollEvery)) {
        io.poll();
        last_poll = std::chrono::steady_clock::now();
      }
    }
    io.poll();
    SCOPED_TRACE("after " + std::to_string(checkpoint * datagrams / kCheckpoints) + " datagrams");
    EXPECT_TRUE(answered(kManager, msg::QueryIdentification{{2}}, msg::ReportIdentification::code));
    EXPECT_TRUE(answered(kDriver, msg::QueryComponentStatus{}, msg::ReportComponentStatus::code));
    EXPECT_TRUE(controller_is_the_ocu()) << [&] {
      std::string lines;
      for (const auto& line : control_lines) lines += "\n  " + line;
      return "the node's log lines about control:" + lines;
    }();
    EXPECT_LE(link.routes().route_count(), routes.max_entries);
    EXPECT_LE(link.routes().peers().size(), routes.max_entries);
    EXPECT_LE(node.node().liveness().size(), node::LivenessTable::Options{}.max_entries);
    EXPECT_LE(manager->event_subscriptions(), 256u);  // one per event ID
    for (const auto& at : {kManager, kCommunicator, kDriver, kPose, kVelocity}) {
      const rt::Component* component = node.node().find(at);
      ASSERT_NE(component, nullptr);
      EXPECT_LE(component->emergency().holders().size(), rt::EmergencyLatch::kMaxHolders + 1);
      EXPECT_LE(component->service_connections().active(), rt::ComponentConfig{}.service_connections.max_connections);
    }
    heap.push_back(heap_in_use());
  }
  // The tables fill during the first checkpoints; after that the heap is flat.
  const std::size_t full = *std::max_element(heap.begin(), heap.begin() + 3);
  const std::size_t last = *std::max_element(heap.begin() + 3, heap.end());
  EXPECT_LT(last, full + (2u << 20)) << "heap in use at each checkpoint (bytes): " << [&] {
    std::string all;
    for (auto bytes : heap) all += std::to_string(bytes) + " ";
    return all;
  }();
  // The log: per component, service connection provider, node and link, at
  // most kOwnerLinesPerWindow + kOwnerNoteworthyLinesPerWindow lines and a
  // summary per level each 10 s window, whatever the flood.
  const auto windows =
      static_cast<std::size_t>(1 + (std::chrono::steady_clock::now() - started) / rt::kRepeatedLogWindow);
  constexpr std::size_t kOwners = 2 * 5 + 2;  // components and their service connections, node, link
  const std::size_t start_lines = 40;         // the node starting, control of the driver taken
  EXPECT_LE(log_lines,
            start_lines + windows * kOwners * (rt::kOwnerLinesPerWindow + rt::kOwnerNoteworthyLinesPerWindow + 3))
      << windows << " windows" << [&] {
           std::string most;
           for (const auto& [start, n] : lines_by_start)
             if (n > 5) most += "\n  " + std::to_string(n) + " x " + start;
           return most;
         }();
  std::printf("%d datagrams in %.1f s: %zu log lines in %zu windows of 10 s\n", datagrams,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), log_lines, windows);
  EXPECT_GT(link.counters().datagrams_received, static_cast<std::uint64_t>(datagrams) - 1);
  EXPECT_EQ(node.node().counters().queue_dropped, 0u);  // every datagram that passed the link was handled
  EXPECT_GT(link.counters().dropped_for(transport::DropReason::route_claim), 0u);
  EXPECT_GT(link.counters().dropped_for(transport::DropReason::invalid_source), 0u);
  hold.release();
}

}  // namespace
}  // namespace jaus::host
