// A node in steady state allocates nothing per message: queries answered,
// service connection reports sent, datagrams received and dispatched, timers
// set and posted work run (issue 15, item 6). A node on a vehicle answers
// thousands of messages a second for hours; the allocator's locks, its
// fragmentation and its rare slow paths stay out of that loop.
//
// The node runs in this thread on real loopback sockets; a plain UDP socket
// asks and listens (synchronous calls on prepared datagrams, which allocate
// nothing). Every allocation this thread makes is counted by the replaced
// global operator new, which is why this test is an executable of its own.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstdlib>
#include <new>

#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"

namespace {
thread_local std::uint64_t allocations_on_this_thread = 0;
}  // namespace

// The replaceable allocation functions; the array, nothrow and sized forms
// of the standard library call these. Not inlined: inlined into a caller,
// GCC takes the free() below for a mismatched delete of new's pointer.
[[gnu::noinline]] void* operator new(std::size_t size) {
  ++allocations_on_this_thread;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace jaus::host {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

constexpr Address kManager{1, 1, 1, 1};
constexpr Address kDriver{1, 1, 33, 1};
constexpr Address kPose{1, 1, 38, 1};
constexpr Address kAsker{254, 1, 40, 1};
constexpr std::uint32_t kNodeAddress = 0x7F000026;   // 127.0.0.38 (ports chosen by the system)
constexpr std::uint32_t kAskerAddress = 0x7F000027;  // 127.0.0.39

template <class M>
std::vector<std::uint8_t> datagram(const Address& to, const M& message) {
  Header header;
  header.source = kAsker;
  header.destination = to;
  std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
  auto size = wire::encode_message(header, message, packet);
  if (!size) throw std::logic_error(size.error().message());
  const auto prefix = transport::frame_prefix(transport::Framing::opc, *size);
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(*size));
  return out;
}

class SteadyStateNode : public ::testing::Test {
 protected:
  void SetUp() override {
    HostConfig config;
    config.node.subsystem = 1;
    config.node.node = 1;
    config.link.bind = transport::Ipv4Endpoint{kNodeAddress, 0};
    config.settings.identity.subsystem_name = "steady";
    config.settings.identity.node_name = "node";
    auto spec = [](const char* kind, const Address& at) {
      return ComponentSpec{kind, at.component, 1, 0, kind, {}, 0, {}};
    };
    config.components = {spec("node_manager", kManager), spec("primitive_driver", kDriver),
                         spec("global_pose_sensor", kPose)};
    auto opened = NodeHost::open(config, io_);
    ASSERT_TRUE(opened) << opened.error().message();
    host_ = std::move(*opened);
    node_at_ = udp::endpoint(asio::ip::address_v4(kNodeAddress), host_->udp_link()->local_endpoint().port);
    asker_.open(udp::v4());
    asker_.bind(udp::endpoint(asio::ip::address_v4(kAskerAddress), 0));
    asker_.non_blocking(true);
  }

  void send(const std::vector<std::uint8_t>& bytes) { asker_.send_to(asio::buffer(bytes), node_at_); }

  // Runs the node until a datagram with `code` reaches the asker (others are
  // read and counted); false after 5 s.
  bool run_until_received(std::uint16_t code) {
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    while (std::chrono::steady_clock::now() < deadline) {
      io_.poll();
      boost::system::error_code ec;
      udp::endpoint from;
      const std::size_t size = asker_.receive_from(asio::buffer(buffer_), from, 0, ec);
      if (ec) continue;
      auto unframed = transport::unframe(std::span(buffer_).first(size));
      if (!unframed) continue;
      const Header& h = unframed->packet.header;
      if (h.service_connection) ++reports_;
      if (h.command_code == code) return true;
    }
    return false;
  }

  asio::io_context io_;
  std::unique_ptr<NodeHost> host_;
  udp::endpoint node_at_;
  udp::socket asker_{io_};
  std::array<std::uint8_t, 9000> buffer_{};
  std::size_t reports_ = 0;
};

TEST_F(SteadyStateNode, QueriesRepliesAndServiceConnectionReportsAllocateNothing) {
  // What the asker sends, made before anything is counted.
  const auto status = datagram(kDriver, msg::QueryComponentStatus{});
  const auto control = datagram(kDriver, msg::QueryComponentControl{});
  const auto heartbeat = datagram(kManager, msg::QueryHeartbeatPulse{});
  const auto pose = datagram(kPose, msg::QueryGlobalPose{{0x01FF}});
  msg::CreateServiceConnection create;
  create.command_code = msg::ReportGlobalPose::code;
  create.periodic_rate_hz = 50;  // the sensor's own rate: a report every 20 ms, beside the queries
  create.presence_vector = 0x01FF;
  const auto subscribe = datagram(kPose, create);

  send(subscribe);
  ASSERT_TRUE(run_until_received(msg::ConfirmServiceConnection::code));
  auto ask_each = [&](int rounds) {
    for (int i = 0; i < rounds; ++i) {
      send(status);
      if (!run_until_received(msg::ReportComponentStatus::code)) return false;
      send(control);
      if (!run_until_received(msg::ReportComponentControl::code)) return false;
      send(heartbeat);
      if (!run_until_received(msg::ReportHeartbeatPulse::code)) return false;
      send(pose);
      if (!run_until_received(msg::ReportGlobalPose::code)) return false;
    }
    return true;
  };
  // Warming up: routes and liveness entries made, buffers grown to the traffic.
  ASSERT_TRUE(ask_each(200));

  const std::size_t reports_before = reports_;
  const std::uint64_t before = allocations_on_this_thread;
  const auto started = std::chrono::steady_clock::now();
  // At least 1,000 rounds and 1.5 s: some 75 reports go out on the service
  // connection, and the node's housekeeping (every second) runs.
  bool answered = true;
  int rounds = 0;
  while (answered && (rounds < 1000 || std::chrono::steady_clock::now() - started < 1500ms)) {
    answered = ask_each(10);
    rounds += 10;
  }
  const std::uint64_t allocations = allocations_on_this_thread - before;
  ASSERT_TRUE(answered);
  EXPECT_GE(reports_ - reports_before, 10u) << "the service connection kept reporting";
  EXPECT_EQ(allocations, 0u) << "over " << 4 * rounds << " queries and " << reports_ - reports_before
                             << " service connection reports";
}

}  // namespace
}  // namespace jaus::host
