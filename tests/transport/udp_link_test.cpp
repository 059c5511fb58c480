// The UDP link on loopback with real sockets: a node behind it is found,
// queried and answered in the framing each peer speaks; what is not JAUS is
// dropped and counted by reason; floods leave it answering with bounded
// tables. Ports are ephemeral (bind to :0) so tests never collide with a
// running jausd; only order and presence are asserted, never durations.
#include <gtest/gtest.h>

#include <algorithm>

#include <boost/asio/ip/udp.hpp>
#include <atomic>
#include <functional>
#include <map>
#include <random>
#include <thread>
#include <unistd.h>

#include "../core/vector_file.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/node/node.hpp"
#include "jaus/components/communicator.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::transport {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

constexpr std::uint32_t kLoopback1 = 0x7F000001;
const Address kManager{1, 1, 1, 1};
const Address kOcu{2, 1, 40, 1};

std::vector<std::uint8_t> bytes_of(const std::string& hex) {
  auto out = parse_hex(hex);
  EXPECT_TRUE(out) << out.error().message();
  return out ? *out : std::vector<std::uint8_t>{};
}

template <class M>
std::vector<std::uint8_t> packet_of(const Address& from, const Address& to, const M& message) {
  std::vector<std::uint8_t> out(kHeaderSize + kMaxPayloadSize);
  auto size = wire::encode_payload(message, std::span(out).subspan(kHeaderSize));
  Header h;
  h.command_code = M::code;
  h.source = from;
  h.destination = to;
  h.data_size = static_cast<std::uint16_t>(*size);
  encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(out.data(), kHeaderSize));
  out.resize(kHeaderSize + *size);
  return out;
}

// Runs `io` until `done`, or 10 s pass: generous, since a loaded 2-core
// machine under ASan can stall this process for a while.
bool run_io_until(asio::io_context& io, const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    io.run_for(5ms);
  }
  return true;
}

// A packet handed to a link as the node hands it: its header and its bytes.
void transmit(UdpLink& link, std::span<const std::uint8_t> packet) { link.transmit(*decode_header(packet), packet); }

std::vector<std::uint8_t> framed(Framing framing, std::span<const std::uint8_t> message) {
  const FramePrefix prefix = frame_prefix(framing, message.size());
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), message.begin(), message.end());
  return out;
}

// A node host (node manager) behind a UDP link, and a bare socket playing the
// peer, on one io_context.
class UdpNodeTest : public ::testing::Test {
 protected:
  void SetUp() override { open_node({}); }

  void open_node(UdpLinkOptions options) {
    host::HostConfig config;
    config.link = options;
    config.link.bind = Ipv4Endpoint{kLoopback1, 0};
    config.components = {host::ComponentSpec{"node_manager", kManager.component, 1, 0, "node manager", {}, 0, {}}};
    // What jausd's default level (info) would print.
    auto opened = host::NodeHost::open(config, io, [this](rt::LogLevel level, const std::string& line) {
      if (level != rt::LogLevel::debug) logs.push_back(line);
    });
    ASSERT_TRUE(opened) << opened.error().message();
    node_host = std::move(*opened);
    link = node_host->udp_link();
    node = &node_host->node();
    manager = dynamic_cast<components::NodeManager*>(node->find(kManager));
    ASSERT_NE(manager, nullptr);
    peer.open(udp::v4());
    peer.bind(udp::endpoint(asio::ip::make_address_v4("127.0.0.1"), 0));
    peer.non_blocking(true);
  }

  udp::endpoint node_endpoint() const {
    return udp::endpoint(asio::ip::address_v4(link->local_endpoint().address), link->local_endpoint().port);
  }
  void send(std::span<const std::uint8_t> datagram) { peer.send_to(asio::buffer(datagram.data(), datagram.size()), node_endpoint()); }

  // Runs the io_context until `done`, or 10 s pass: generous, since a loaded
  // 2-core machine under ASan can stall this process for a while.
  bool run_until(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      io.run_for(5ms);
      drain_peer();
    }
    return true;
  }
  void drain_peer() {
    std::array<std::uint8_t, 9000> buffer;
    boost::system::error_code ec;
    for (;;) {
      udp::endpoint from;
      const std::size_t size = peer.receive_from(asio::buffer(buffer), from, 0, ec);
      if (ec) return;
      received.emplace_back(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(size));
    }
  }
  // Replies to the peer with this command code, in this framing.
  std::size_t replies(std::uint16_t code, Framing framing) const {
    std::size_t n = 0;
    for (const auto& datagram : received) {
      auto unframed = unframe(datagram);
      if (unframed && unframed->framing == framing && unframed->packet.header.command_code == code) ++n;
    }
    return n;
  }

  asio::io_context io;
  AsioRuntime runtime{io};
  std::vector<std::string> logs;
  std::unique_ptr<host::NodeHost> node_host;
  UdpLink* link = nullptr;
  node::Node* node = nullptr;
  components::NodeManager* manager = nullptr;
  udp::socket peer{io};
  std::vector<std::vector<std::uint8_t>> received;
};

TEST_F(UdpNodeTest, ABusyPortIsOneClearError) {
  UdpLinkOptions options;
  options.bind = link->local_endpoint();
  auto second = UdpLink::open(io, runtime, runtime, options);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::io);
  EXPECT_EQ(second.error().message(), to_string(link->local_endpoint()) + " is already in use");
  options.bind = Ipv4Endpoint{0xC0000201, 3794};  // 192.0.2.1 (TEST-NET): not ours
  auto foreign = UdpLink::open(io, runtime, runtime, options);
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.error().message(), "192.0.2.1:3794 is not an address of this machine");
}

TEST_F(UdpNodeTest, TheReceiveBufferIsWhatWasAskedWithinWhatTheKernelAllows) {
  UdpLinkOptions options;
  options.bind = Ipv4Endpoint{0x7F000001, 0};
  options.multicast.reset();
  options.receive_buffer_bytes = 0;  // the system's default
  auto by_default = UdpLink::open(io, runtime, runtime, options);
  ASSERT_TRUE(by_default) << by_default.error().message();
  const std::size_t system_default = (*by_default)->receive_buffer_bytes();
  EXPECT_GT(system_default, 0u);
  // 64 KiB is under any kernel's cap: granted (Linux keeps twice as much, for its bookkeeping).
  options.receive_buffer_bytes = 64 * 1024;
  auto small = UdpLink::open(io, runtime, runtime, options);
  ASSERT_TRUE(small);
  EXPECT_GE((*small)->receive_buffer_bytes(), 64u * 1024);
  EXPECT_LE((*small)->receive_buffer_bytes(), 2u * 64 * 1024);
  // The default asks 1 MiB: never less than the system's own default.
  EXPECT_GE(link->receive_buffer_bytes(), system_default);
}

TEST_F(UdpNodeTest, EachPeerIsAnsweredInTheFramingItUses) {
  const auto query = packet_of(kOcu, kManager, msg::QueryIdentification{});
  send(framed(Framing::judp, query));
  ASSERT_TRUE(run_until([&] { return replies(msg::ReportIdentification::code, Framing::judp) == 1; }));
  send(framed(Framing::opc, query));
  ASSERT_TRUE(run_until([&] { return replies(msg::ReportIdentification::code, Framing::opc) == 1; }));
  const auto route = link->routes().route(2, 1);
  ASSERT_TRUE(route);
  EXPECT_EQ(route->endpoint.port, peer.local_endpoint().port());
  EXPECT_EQ(link->counters().dropped_total(), 0u);
  const std::string told = "node 2.1 at 127.0.0.1:" + std::to_string(peer.local_endpoint().port()) + " (judp)";
  EXPECT_NE(std::find(logs.begin(), logs.end(), told), logs.end());
}

// Every vector of the other implementation, in both framings, addressed to
// the node manager: each is delivered, and each query the node manager
// answers gets its report back, in the framing it came in.
TEST_F(UdpNodeTest, VectorsAsDatagramsAreDecodedAndAnswered) {
  const auto answered = manager->input_codes();
  std::size_t sent = 0;
  for (const Framing framing : {Framing::opc, Framing::judp}) {
    received.clear();
    std::size_t expected_replies = 0;
    std::vector<std::uint16_t> queries;
    for (const auto& vector : test::all_vectors()) {
      auto message = bytes_of(vector.hex);
      Header header = *decode_header(message);
      header.destination = kManager;
      header.ack_nak = AckNak::none;
      encode_header_unchecked(header, std::span(message).first<kHeaderSize>());
      const std::uint16_t code = header.command_code;
      const bool is_query = code >= 0x2000 && code < 0x4000;
      if (is_query && std::find(answered.begin(), answered.end(), code) != answered.end()) {
        ++expected_replies;
        queries.push_back(code);
      }
      send(framed(framing, message));
      // A few at a time: a burst of all of them can overflow the node's socket
      // buffer on a loaded machine, and UDP would rightly drop the rest.
      if (++sent % 8 == 0) {
        ASSERT_TRUE(run_until([&] { return link->counters().packets_delivered >= sent; }));
      }
    }
    ASSERT_TRUE(run_until([&] {
      std::size_t n = 0;
      for (const auto q : queries) n += replies(static_cast<std::uint16_t>(q + 0x2000), framing) > 0;
      return n == queries.size();
    })) << to_string(framing) << ": " << received.size() << " datagrams back";
    EXPECT_GE(received.size(), expected_replies);
  }
  EXPECT_EQ(link->counters().dropped_total(), 0u);
  EXPECT_EQ(node->counters().malformed, 0u);
  EXPECT_EQ(manager->counters().decode_errors, 0u);
  EXPECT_EQ(link->counters().packets_delivered, 2 * test::all_vectors().size());
}

TEST_F(UdpNodeTest, NonJausDatagramsAreCountedByReasonAndTheNodeKeepsAnswering) {
  send(bytes_of("DEADBEEF"));
  send(bytes_of("4A41555330312E30060202"));  // OPC, header cut
  send(bytes_of("0100000030" "0602002B012101010128010201000B0A02"));  // JUDP length says 48, carries 17
  send(std::vector<std::uint8_t>(kMaxDatagramSize + 100, 0x4A));
  const auto query = packet_of(kOcu, kManager, msg::QueryIdentification{});
  send(framed(Framing::opc, query));
  ASSERT_TRUE(run_until([&] { return replies(msg::ReportIdentification::code, Framing::opc) == 1; }));
  const auto& c = link->counters();
  EXPECT_EQ(c.dropped_for(DropReason::unknown_framing), 1u);
  EXPECT_EQ(c.dropped_for(DropReason::truncated), 1u);
  EXPECT_EQ(c.dropped_for(DropReason::length_mismatch), 1u);
  EXPECT_EQ(c.dropped_for(DropReason::oversized), 1u);
  EXPECT_EQ(c.packets_delivered, 1u);
  bool logged_reason = false;
  for (const auto& line : logs) logged_reason |= line.find("JUDP length 48, datagram carries 17 bytes") != std::string::npos;
  EXPECT_TRUE(logged_reason);
}

TEST_F(UdpNodeTest, APeerUsingOurIdIsDroppedAndReported) {
  send(framed(Framing::opc, packet_of(Address{1, 1, 40, 1}, kManager, msg::QueryIdentification{})));
  ASSERT_TRUE(run_until([&] { return link->counters().dropped_for(DropReason::from_self) == 1; }));
  EXPECT_EQ(node->counters().packets_received, 0u);
  bool reported = false;
  for (const auto& line : logs) reported |= line.find("another node uses this node's ID 1.1.40.1") != std::string::npos;
  EXPECT_TRUE(reported);
}

TEST_F(UdpNodeTest, InvalidSourcesAndForeignClaimsOfAKnownIdAreDroppedAndCounted) {
  send(framed(Framing::opc, packet_of(Address{2, 1, 0, 1}, kManager, msg::QueryIdentification{})));    // octet 0
  send(framed(Framing::opc, packet_of(Address{2, 255, 40, 1}, kManager, msg::QueryIdentification{})));  // 255
  send(framed(Framing::opc, packet_of(kOcu, kManager, msg::QueryIdentification{})));
  ASSERT_TRUE(run_until([&] { return replies(msg::ReportIdentification::code, Framing::opc) == 1; }));
  EXPECT_EQ(link->counters().dropped_for(DropReason::invalid_source), 2u);
  EXPECT_EQ(node->counters().packets_received, 1u);

  // Another host claims the OCU's ID while the OCU is alive: dropped, the route stays.
  udp::socket stranger(io, udp::endpoint(asio::ip::make_address_v4("127.0.0.5"), 0));
  const auto claim = framed(Framing::opc, packet_of(kOcu, kManager, msg::QueryIdentification{}));
  stranger.send_to(asio::buffer(claim), node_endpoint());
  ASSERT_TRUE(run_until([&] { return link->counters().dropped_for(DropReason::route_claim) == 1; }));
  EXPECT_EQ(link->routes().route(2, 1)->endpoint.port, peer.local_endpoint().port());
  EXPECT_EQ(node->counters().packets_received, 1u);

  // The OCU restarted on the same host (a new port): followed, without a warning.
  udp::socket restarted(io, udp::endpoint(asio::ip::make_address_v4("127.0.0.1"), 0));
  restarted.send_to(asio::buffer(claim), node_endpoint());
  ASSERT_TRUE(run_until([&] { return link->routes().route(2, 1)->endpoint.port == restarted.local_endpoint().port(); }));
  const std::string moved = "node 2.1 moved to 127.0.0.1:" + std::to_string(restarted.local_endpoint().port());
  std::size_t move_lines = 0, claim_warnings = 0;
  for (const auto& line : logs) {
    move_lines += line.find(moved) != std::string::npos;
    claim_warnings += line.find("two peers with one ID") != std::string::npos;
  }
  EXPECT_EQ(move_lines, 1u);
  EXPECT_EQ(claim_warnings, 1u);  // the stranger's claim only
  EXPECT_EQ(link->routes().counters().moved, 1u);
}

// The warning is the node host's (NodeHost::open): a tool's link is open by
// design, and an operator's own node says nothing of it (issue 49).
TEST_F(UdpNodeTest, ANodeOpenToTheNetworkWithoutAnAllowListSaysSoAtStart) {
  const auto warned = [](const std::vector<std::string>& lines) {
    return std::any_of(lines.begin(), lines.end(),
                       [](const auto& l) { return l.find("with an empty allow-list and control_from") != std::string::npos; });
  };
  EXPECT_FALSE(warned(logs));  // loopback only
  std::vector<std::string> lines;
  const auto collect = [&](rt::LogLevel, const std::string& line) { lines.push_back(line); };
  const auto open_host = [&](const UdpLinkOptions& link_options) {
    host::HostConfig config;
    config.link = link_options;
    config.components.push_back(host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}});
    auto opened = host::NodeHost::open(config, io, collect);
    EXPECT_TRUE(opened) << opened.error().message();
    if (opened) (*opened)->stop("test");
  };
  UdpLinkOptions options;
  options.bind = Ipv4Endpoint{0, 0};  // every interface
  auto bare = UdpLink::open(io, runtime, runtime, options, collect);
  ASSERT_TRUE(bare) << bare.error().message();
  EXPECT_FALSE(warned(lines)) << "the link alone says nothing";
  open_host(options);
  EXPECT_TRUE(warned(lines));
  lines.clear();
  options.allow = {*parse_cidr("10.0.0.0/8")};
  open_host(options);
  EXPECT_FALSE(warned(lines));
  options.allow.clear();  // open to all, but only these may command
  options.control_from = {*parse_cidr("10.0.0.0/8")};
  open_host(options);
  EXPECT_FALSE(warned(lines));
}

TEST_F(UdpNodeTest, TheAllowListKeepsStrangersOut) {
  node_host.reset();
  peer.close();
  UdpLinkOptions options;
  options.allow = {*parse_cidr("10.0.0.0/8")};
  open_node(options);
  send(framed(Framing::opc, packet_of(kOcu, kManager, msg::QueryIdentification{})));
  ASSERT_TRUE(run_until([&] { return link->counters().dropped_for(DropReason::not_allowed) == 1; }));
  EXPECT_EQ(node->counters().packets_received, 0u);
  EXPECT_FALSE(link->routes().route(2, 1));
}

// Half garbage, half valid packets from ever-new JAUS sources (subsystems
// 100-249, never the OCU's), from another thread as fast as it can until the
// node has taken in kReceived of them (however many the kernel dropped on the
// way: a loaded machine drops more): the routes and the liveness table stay
// within their bounds, the log is rate-limited and the node still answers.
TEST_F(UdpNodeTest, AFloodLeavesTheNodeAnsweringWithBoundedTables) {
  constexpr std::uint64_t kReceived = 50000;
  const udp::endpoint target = node_endpoint();
  std::atomic<bool> stop{false};
  std::thread flooder([target, &stop] {
    asio::io_context flood_io;
    udp::socket socket(flood_io, udp::endpoint(asio::ip::make_address_v4("127.0.0.1"), 0));
    std::mt19937 random(7);
    const std::vector<std::uint8_t> garbage = {0xDE, 0xAD, 0xBE, 0xEF, 0x00, 0x01};
    for (int i = 0; !stop; ++i) {
      boost::system::error_code ec;
      if (i % 2) {
        socket.send_to(asio::buffer(garbage), target, 0, ec);
      } else {
        const Address source{static_cast<std::uint8_t>(100 + random() % 150), static_cast<std::uint8_t>(1 + random() % 250), 40, 1};
        socket.send_to(asio::buffer(framed(Framing::opc, packet_of(source, Address{1, 1, 35, 1}, msg::QueryHeartbeatPulse{}))), target, 0, ec);
      }
      if (i % 5000 == 0) std::this_thread::sleep_for(1ms);  // give the receiver a chance
    }
  });
  const auto& c = link->counters();
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + 120s;  // only if this machine can barely receive at all
  while (c.datagrams_received < kReceived && std::chrono::steady_clock::now() < deadline) io.run_for(20ms);
  stop = true;
  flooder.join();
  io.run_for(200ms);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(c.datagrams_received, kReceived);
  EXPECT_GT(c.dropped_for(DropReason::unknown_framing), 0u);
  EXPECT_LE(link->routes().route_count(), RouteTableOptions{}.max_entries);
  EXPECT_LE(link->routes().peers().size(), RouteTableOptions{}.max_entries);
  EXPECT_LE(node->liveness().size(), node::LivenessTable::Options{}.max_entries);
  // The log is rate-limited, not flooded: a few lines per owner and 10 s
  // window, so its bound grows with the windows a slow machine's flood spans.
  const auto windows = 1 + static_cast<std::size_t>(elapsed / rt::kRepeatedLogWindow);
  EXPECT_LT(logs.size(), 200u * windows) << std::chrono::duration<double>(elapsed).count() << " s";
  received.clear();
  send(framed(Framing::opc, packet_of(kOcu, kManager, msg::QueryIdentification{})));
  EXPECT_TRUE(run_until([&] { return replies(msg::ReportIdentification::code, Framing::opc) == 1; }))
      << "received " << c.datagrams_received << ", delivered " << c.packets_delivered << ", node queue drops "
      << node->counters().queue_dropped << ", sent " << c.datagrams_sent << ", send errors " << c.send_errors
      << ", replies seen " << received.size() << ", last log: " << (logs.empty() ? "" : logs.back());
}

TEST(UdpLinks, BroadcastsReachStaticPeersWhichThenLearnTheRouteBack) {
  asio::io_context io;
  AsioRuntime runtime(io);
  UdpLinkOptions options_b;
  options_b.subsystem = 2;
  options_b.node = 1;
  options_b.bind = Ipv4Endpoint{kLoopback1, 0};
  auto b = UdpLink::open(io, runtime, runtime, options_b);
  ASSERT_TRUE(b) << b.error().message();
  UdpLinkOptions options_a;
  options_a.subsystem = 1;
  options_a.node = 1;
  options_a.bind = Ipv4Endpoint{kLoopback1, 0};
  options_a.peers = {StaticPeer{(*b)->local_endpoint(), Framing::judp}};
  auto a = UdpLink::open(io, runtime, runtime, options_a);
  ASSERT_TRUE(a) << a.error().message();
  std::vector<Header> at_a, at_b;
  (*a)->on_packet([&](const PacketView& p, Framing, rt::SenderStanding) { at_a.push_back(p.header); });
  (*b)->on_packet([&](const PacketView& p, Framing, rt::SenderStanding) { at_b.push_back(p.header); });
  (*a)->start();
  (*b)->start();
  transmit(**a, packet_of(kManager, Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(io, [&] { return !at_b.empty(); }));
  ASSERT_EQ(at_b.size(), 1u);
  const auto route = (*b)->routes().route(1, 1);
  ASSERT_TRUE(route);
  EXPECT_EQ(route->endpoint, (*a)->local_endpoint());
  EXPECT_EQ(route->framing, Framing::judp);  // A spoke JUDP to B, so B answers in JUDP
  transmit(**b, packet_of(Address{2, 1, 1, 1}, kManager, msg::QueryIdentification{}));
  ASSERT_TRUE(run_io_until(io, [&] { return !at_a.empty(); }));
  ASSERT_EQ(at_a.size(), 1u);
  EXPECT_EQ(at_a[0].command_code, msg::QueryIdentification::code);
  // Unicast to a node nobody has heard of, with no static peer and no multicast: dropped, counted.
  transmit(**b, packet_of(Address{2, 1, 1, 1}, Address{9, 9, 1, 1}, msg::QueryIdentification{}));
  EXPECT_EQ((*b)->counters().no_route, 1u);
}

// Links on loopback, each with its own subsystem and node, recording what
// reaches them (docs/wire-format.md, "Liveness and discovery").
class SubsystemLinks : public ::testing::Test {
 protected:
  UdpLink& open(std::uint8_t subsystem, std::uint8_t node, std::vector<UdpLink*> peers = {}, bool relay = true) {
    UdpLinkOptions options;
    options.subsystem = subsystem;
    options.node = node;
    options.bind = Ipv4Endpoint{kLoopback1, 0};
    options.relay = relay;
    for (auto* peer : peers) options.peers.push_back(StaticPeer{peer->local_endpoint(), Framing::opc});
    auto opened = UdpLink::open(io, runtime, runtime, options);
    EXPECT_TRUE(opened) << opened.error().message();
    UdpLink& link = *links.emplace_back(std::move(*opened));
    auto& heard = at[&link];
    link.on_packet([&heard](const PacketView& p, Framing, rt::SenderStanding) { heard.push_back(p.header); });
    link.start();
    return link;
  }
  bool heard(UdpLink& link, const Address& from, const Address& to) {
    return std::any_of(at[&link].begin(), at[&link].end(),
                       [&](const Header& h) { return h.source == from && h.destination == to; });
  }
  bool heard_for_subsystem(UdpLink& link, std::uint8_t subsystem) {
    return std::any_of(at[&link].begin(), at[&link].end(),
                       [&](const Header& h) { return h.destination.subsystem == subsystem; });
  }

  asio::io_context io;
  AsioRuntime runtime{io};
  std::vector<std::unique_ptr<UdpLink>> links;
  std::map<UdpLink*, std::vector<Header>> at;  // the links' handlers hold references into it: never erased
};

// Another subsystem's node manager drops what is addressed to ours: a
// subsystem's broadcasts go only to peers heard as its nodes; (255, ...) to all.
TEST_F(SubsystemLinks, ASubsystemsBroadcastsReachOnlyItsOwnNodes) {
  UdpLink& other = open(1, 1);
  UdpLink& sibling = open(2, 2);
  UdpLink& self = open(2, 1, {&other, &sibling});
  const Address manager{2, 1, 1, 1};
  const Address our_subsystem{2, 255, 1, 1}, every_subsystem{255, 255, 1, 1};
  // Peers not heard yet may be of any subsystem: only (255, ...) goes to them.
  transmit(self, packet_of(manager, our_subsystem, msg::ReportHeartbeatPulse{}));
  transmit(self, packet_of(manager, every_subsystem, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(
      io, [&] { return heard(other, manager, every_subsystem) && heard(sibling, manager, every_subsystem); }));
  EXPECT_FALSE(heard_for_subsystem(other, 2));
  EXPECT_FALSE(heard_for_subsystem(sibling, 2));

  // Once each has spoken, the sibling (subsystem 2) gets subsystem 2's broadcasts.
  transmit(other, packet_of(Address{1, 1, 35, 1}, every_subsystem, msg::ReportHeartbeatPulse{}));
  transmit(sibling, packet_of(Address{2, 2, 1, 1}, every_subsystem, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(io, [&] { return self.routes().route(1, 1) && self.routes().route(2, 2); }));
  for (auto& [link, headers] : at) headers.clear();
  transmit(self, packet_of(manager, our_subsystem, msg::ReportHeartbeatPulse{}));
  transmit(self, packet_of(manager, every_subsystem, msg::ReportHeartbeatPulse{}));
  // Datagrams from one socket to one socket arrive in order: the second is the mark.
  ASSERT_TRUE(run_io_until(
      io, [&] { return heard(other, manager, every_subsystem) && heard(sibling, manager, every_subsystem); }));
  EXPECT_TRUE(heard(sibling, manager, our_subsystem));
  EXPECT_FALSE(heard_for_subsystem(other, 2));
}

// An OCU's configured peers are the vehicles it means to reach (issue 49): a
// stop to a subsystem (S.255.255.255) goes to them before they are heard;
// once a peer is heard as another subsystem's node, it gets only its own.
TEST_F(SubsystemLinks, AnOcusSubsystemBroadcastReachesAConfiguredPeerNotHeardYet) {
  UdpLink& vehicle = open(1, 1);
  UdpLink& other = open(2, 1);
  UdpLinkOptions options;
  options.subsystem = 254;
  options.node = 7;
  options.bind = Ipv4Endpoint{kLoopback1, 0};
  options.relay = false;
  options.broadcast_to_unheard_peers = true;
  options.peers = {StaticPeer{vehicle.local_endpoint(), Framing::opc}, StaticPeer{other.local_endpoint(), Framing::opc}};
  auto opened = UdpLink::open(io, runtime, runtime, options);
  ASSERT_TRUE(opened) << opened.error().message();
  UdpLink& ocu = *links.emplace_back(std::move(*opened));
  ocu.start();
  const Address ocu_component{254, 7, 40, 1}, subsystem_1{1, 255, 255, 255};
  transmit(ocu, packet_of(ocu_component, subsystem_1, msg::SetEmergency{{1}}));
  ASSERT_TRUE(run_io_until(io, [&] { return heard(vehicle, ocu_component, subsystem_1); }));
  ASSERT_TRUE(run_io_until(io, [&] { return heard(other, ocu_component, subsystem_1); }));  // not heard yet: may be of 1

  // Heard as subsystem 2's node: subsystem 1's broadcasts no longer go there.
  transmit(other, packet_of(Address{2, 1, 1, 1}, Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(io, [&] { return ocu.routes().route(2, 1).has_value(); }));
  for (auto& [link, headers] : at) headers.clear();
  transmit(ocu, packet_of(ocu_component, subsystem_1, msg::SetEmergency{{1}}));
  transmit(ocu, packet_of(ocu_component, Address{255, 255, 1, 1}, msg::QueryIdentification{}));  // the mark
  ASSERT_TRUE(run_io_until(io, [&] { return heard(other, ocu_component, Address{255, 255, 1, 1}); }));
  EXPECT_FALSE(heard_for_subsystem(other, 1));
  EXPECT_TRUE(heard(vehicle, ocu_component, subsystem_1));
}

// An OCU that reaches one node reaches the subsystems that node has heard:
// the node relays to where each was heard, and the replies come back the same way.
TEST_F(SubsystemLinks, AMessageForAnotherSubsystemIsRelayedToWhereItsNodeWasHeard) {
  UdpLink& remote = open(1, 1, {}, /*relay=*/false);
  UdpLink& node = open(2, 1, {&remote});
  UdpLink& ocu = open(254, 1, {&node}, /*relay=*/false);
  const Address remote_manager{1, 1, 1, 1}, ocu_component{254, 1, 40, 1};
  remote.send_to(node.local_endpoint(), Framing::opc,
                 packet_of(Address{1, 1, 35, 1}, Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(io, [&] { return node.routes().route(1, 1).has_value(); }));

  // The OCU knows no route to subsystem 1: its static peer, the node, gets it and relays it.
  transmit(ocu, packet_of(ocu_component, remote_manager, msg::QueryIdentification{}));
  ASSERT_TRUE(run_io_until(io, [&] { return heard(remote, ocu_component, remote_manager); }));
  EXPECT_EQ(node.counters().relayed, 1u);
  EXPECT_EQ(remote.routes().route(254, 1)->endpoint, node.local_endpoint());  // the OCU lives behind the node
  transmit(remote, packet_of(remote_manager, ocu_component, msg::ReportIdentification{}));
  ASSERT_TRUE(run_io_until(io, [&] { return heard(ocu, remote_manager, ocu_component); }));
  EXPECT_EQ(node.counters().relayed, 2u);
  EXPECT_EQ(ocu.routes().route(1, 1)->endpoint, node.local_endpoint());

  // Its own subsystem's messages, broadcasts, and what has nowhere known to go are not relayed.
  transmit(ocu, packet_of(ocu_component, Address{2, 7, 1, 1}, msg::QueryIdentification{}));
  transmit(ocu, packet_of(ocu_component, Address{1, 255, 1, 1}, msg::QueryIdentification{}));
  transmit(ocu, packet_of(ocu_component, Address{3, 1, 1, 1}, msg::QueryIdentification{}));
  transmit(ocu, packet_of(ocu_component, remote_manager, msg::QueryIdentification{}));  // the mark
  ASSERT_TRUE(run_io_until(io, [&] { return node.counters().relayed == 3; }));
  EXPECT_EQ(at[&remote].size(), 2u);  // the two queries to 1.1.1.1, nothing else
}

TEST(UdpLinks, BroadcastsGoToTheMulticastGroupAndOwnOnesAreNotTakenBack) {
  asio::io_context io;
  AsioRuntime runtime(io);
  // A group port of our own, so parallel test runs do not hear each other.
  const auto port = static_cast<std::uint16_t>(30000 + ::getpid() % 20000);
  const Ipv4Endpoint group{*parse_ipv4("224.1.0.1"), port};
  std::vector<std::string> logs;
  auto open_member = [&](std::uint8_t subsystem, const char* address) {
    UdpLinkOptions options;
    options.subsystem = subsystem;
    options.node = 1;
    options.bind = Ipv4Endpoint{*parse_ipv4(address), 0};
    options.multicast = group;
    options.broadcast_to_peers = false;
    return UdpLink::open(io, runtime, runtime, options,
                         [&](rt::LogLevel, const std::string& line) { logs.push_back(line); });
  };
  auto a = open_member(1, "127.0.0.1");
  auto b = open_member(2, "127.0.0.2");
  ASSERT_TRUE(a && b);
  for (const auto& line : logs)
    if (line.find("broadcasts go to known peers only") != std::string::npos)
      GTEST_SKIP() << "no multicast on this host's loopback: " << line;
  std::vector<Header> at_a, at_b;
  (*a)->on_packet([&](const PacketView& p, Framing, rt::SenderStanding) { at_a.push_back(p.header); });
  (*b)->on_packet([&](const PacketView& p, Framing, rt::SenderStanding) { at_b.push_back(p.header); });
  (*a)->start();
  (*b)->start();
  transmit(**a, packet_of(kManager, Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}));
  ASSERT_TRUE(run_io_until(io, [&] { return !at_b.empty(); }));
  ASSERT_EQ(at_b.size(), 1u);
  EXPECT_EQ(at_b[0].source, kManager);
  // Its own broadcast looped back is dropped (once it has come back).
  ASSERT_TRUE(run_io_until(io, [&] { return (*a)->counters().dropped_for(DropReason::from_self) > 0; }));
  EXPECT_TRUE(at_a.empty());
  EXPECT_EQ((*a)->counters().dropped_for(DropReason::from_self), 1u);
  // B learnt where A lives from the multicast datagram's source.
  ASSERT_TRUE((*b)->routes().route(1, 1));
  EXPECT_EQ((*b)->routes().route(1, 1)->endpoint, (*a)->local_endpoint());
}

// Issue 43: the group is shared with other subsystems (224.1.0.1 is every RA
// node's on the LAN), whose node managers reject what is addressed to another
// subsystem. So what A sends its own subsystem (heartbeats to 1.255.1.1, a
// node of 1 not heard yet) stays off the group, in the group's own framing
// what goes there; and a sender heard through the group is what its address
// makes it: outside control_from, an observer, as by unicast.
TEST(UdpLinks, OwnSubsystemMessagesStayOffTheGroupAndTheGroupGrantsNoControl) {
  asio::io_context io;
  AsioRuntime runtime(io);
  const auto port = static_cast<std::uint16_t>(30000 + (::getpid() + 7) % 20000);
  const Ipv4Endpoint group{*parse_ipv4("224.1.0.1"), port};
  std::vector<std::string> logs;
  auto open_member = [&](std::uint8_t subsystem, const char* address, std::vector<Cidr> control_from) {
    UdpLinkOptions options;
    options.subsystem = subsystem;
    options.node = 1;
    options.bind = Ipv4Endpoint{*parse_ipv4(address), 0};
    options.multicast = group;
    options.multicast_framing = Framing::judp;
    options.broadcast_to_peers = false;
    options.control_from = std::move(control_from);
    return UdpLink::open(io, runtime, runtime, options,
                         [&](rt::LogLevel, const std::string& line) { logs.push_back(line); });
  };
  auto a = open_member(1, "127.0.0.1", {});
  auto b = open_member(2, "127.0.0.2", {*parse_cidr("10.0.0.0/8")});  // loopback may not command B
  ASSERT_TRUE(a && b);
  for (const auto& line : logs)
    if (line.find("broadcasts go to known peers only") != std::string::npos)
      GTEST_SKIP() << "no multicast on this host's loopback: " << line;
  struct Seen {
    Header header;
    Framing framing;
    rt::SenderStanding standing;
  };
  std::vector<Seen> at_b;
  (*b)->on_packet([&](const PacketView& p, Framing f, rt::SenderStanding s) { at_b.push_back({p.header, f, s}); });
  (*a)->start();
  (*b)->start();
  transmit(**a, packet_of(kManager, Address{1, 255, 1, 1}, msg::ReportHeartbeatPulse{}));   // own subsystem's broadcast
  transmit(**a, packet_of(kManager, Address{1, 7, 1, 1}, msg::QueryIdentification{}));     // own node not heard yet
  transmit(**a, packet_of(kManager, Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}));  // every subsystem: the mark
  ASSERT_TRUE(run_io_until(io, [&] { return !at_b.empty(); }));
  io.run_for(50ms);  // anything sent before the mark has arrived by now (one socket, in order)
  ASSERT_EQ(at_b.size(), 1u) << "own-subsystem messages reached the group";
  EXPECT_EQ(at_b[0].header.destination, (Address{255, 255, 1, 1}));
  EXPECT_EQ(at_b[0].framing, Framing::judp);
  EXPECT_EQ(at_b[0].standing, rt::SenderStanding::observer);
  EXPECT_EQ((*b)->counters().delivered_observer, 1u);
  // The query to a node of its own subsystem not heard yet had nowhere else to go: dropped, counted.
  EXPECT_EQ((*a)->counters().no_route, 1u);
}

}  // namespace
}  // namespace jaus::transport
