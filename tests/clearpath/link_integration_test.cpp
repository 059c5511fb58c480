// Client link <-> simulator server over real loopback UDP and a PTY pair.
// Generous timeouts; assertions are about behaviour, not timing figures.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <map>
#include <thread>

#include "jaus/clearpath/link.hpp"
#include "jaus/clearpath/sim/sim_server.hpp"
#include "jaus/transport/asio_runtime.hpp"

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
using namespace std::chrono_literals;

namespace {

using WallClock = std::chrono::steady_clock;

bool run_until(boost::asio::io_context& io, const std::function<bool()>& done, WallClock::duration limit = 10s) {
  const auto deadline = WallClock::now() + limit;
  while (!done() && WallClock::now() < deadline) {
    io.restart();
    io.run_for(10ms);
  }
  return done();
}

struct Received {
  std::map<std::uint16_t, std::size_t> count;
  std::size_t of(std::uint16_t type) const {
    const auto it = count.find(type);
    return it == count.end() ? 0 : it->second;
  }
};

void exercise(boost::asio::io_context& io, cp::ClearpathLink& link, Received& received) {
  std::optional<cp::CommandOutcome> ack;
  cp::SetMaxSpeed speed;
  speed.forward = 1.5;
  speed.reverse = 0.5;
  link.send(speed, [&](const cp::CommandOutcome& o) { ack = o; });
  ASSERT_TRUE(run_until(io, [&] { return ack.has_value(); }));
  EXPECT_TRUE(ack->ok());

  link.send(cp::RequestMaxSpeed{});
  ASSERT_TRUE(run_until(io, [&] { return received.of(0x8210) >= 1; }));

  cp::RequestEncoders encoders;
  encoders.subscription = 20;
  link.subscribe(encoders);
  const auto start = received.of(0x8800);
  ASSERT_TRUE(run_until(io, [&] { return received.of(0x8800) >= start + 10; }));
}

}  // namespace

TEST(ClearpathLinkUdp, CommandsRequestsSubscriptionsAndReconnect) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  sim::ServerEndpoint endpoint;
  endpoint.kind = sim::ServerEndpoint::Kind::udp;
  auto server = std::make_unique<sim::SimServer>(io, runtime, runtime, endpoint, sim::PlatformConfig{});
  ASSERT_TRUE(server->start());
  const auto port = server->udp_port();

  cp::PlatformEndpoint target;
  target.kind = cp::PlatformEndpoint::Kind::udp;
  target.port = port;
  cp::ClearpathLink link(io, runtime, runtime, target);
  Received received;
  link.on_data([&](const cp::Envelope& e) { ++received.count[e.header.type]; });
  link.start();
  exercise(io, link, received);

  // The simulator goes away: silence, link down; it comes back: data again.
  server.reset();
  ASSERT_TRUE(run_until(io, [&] { return link.core().state() == cp::ConnectionState::down; }));
  endpoint.port = port;
  server = std::make_unique<sim::SimServer>(io, runtime, runtime, endpoint, sim::PlatformConfig{});
  ASSERT_TRUE(server->start());
  const auto before = received.of(0x8800);
  ASSERT_TRUE(run_until(io, [&] { return received.of(0x8800) >= before + 10; }, 20s));
  EXPECT_GE(link.core().counters().reconnects, 1u);
  link.stop();
}

TEST(ClearpathLinkUdp, WatchdogStopsThePlatformWhenSetpointsCease) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  sim::SimServer server(io, runtime, runtime, {}, sim::PlatformConfig{});
  ASSERT_TRUE(server.start());
  cp::PlatformEndpoint target;
  target.kind = cp::PlatformEndpoint::Kind::udp;
  target.port = server.udp_port();
  auto link = std::make_unique<cp::ClearpathLink>(io, runtime, runtime, target);
  link->start();
  cp::SetVelocity v;
  v.translational = 0.5;
  link->set_setpoint(v);
  ASSERT_TRUE(run_until(io, [&] { return server.platform().vehicle().linear_speed() > 0.45; }));
  link->stop();
  link.reset();
  ASSERT_TRUE(run_until(io, [&] { return server.platform().vehicle().linear_speed() == 0.0; }));
  EXPECT_TRUE(server.platform().vehicle().safety_flags() & sim::kSafetyTimeout);
}

TEST(ClearpathLinkPty, CommandsRequestsAndSubscriptionsOverASerialLine) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  sim::ServerEndpoint endpoint;
  endpoint.kind = sim::ServerEndpoint::Kind::pty;
  sim::PlatformConfig platform;
  platform.bandwidth_bytes_per_second = sim::kSerialBytesPerSecond;
  sim::SimServer server(io, runtime, runtime, endpoint, platform);
  ASSERT_TRUE(server.start());
  ASSERT_FALSE(server.pty_path().empty());

  cp::PlatformEndpoint target;
  target.kind = cp::PlatformEndpoint::Kind::serial;
  target.device = server.pty_path();
  cp::ClearpathLink link(io, runtime, runtime, target);
  Received received;
  link.on_data([&](const cp::Envelope& e) { ++received.count[e.header.type]; });
  link.start();
  exercise(io, link, received);
  link.stop();
}

TEST(ClearpathLink, MissingSerialPortMeansRetryingNeverExit) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  cp::PlatformEndpoint target;
  target.device = "/dev/does-not-exist-clearpath";
  cp::ClearpathLink link(io, runtime, runtime, target);
  link.start();
  run_until(io, [] { return false; }, 400ms);
  EXPECT_EQ(link.core().state(), cp::ConnectionState::down);
  EXPECT_TRUE(link.core().wants_reconnect());
  link.stop();
}

// A serial line whose far end reads nothing until flush(): the link's
// frames fill the kernel's buffer and one is left half written. flush() must
// finish that frame before its own, so the far end parses every frame clean
// and the stop's zero velocity comes last.
TEST(ClearpathLinkPty, FlushFinishesAHalfWrittenFrameBeforeItsOwn) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const char* name = ::ptsname(master);
  ASSERT_NE(name, nullptr);
  termios raw{};
  ::tcgetattr(master, &raw);
  ::cfmakeraw(&raw);
  ::tcsetattr(master, TCSANOW, &raw);

  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  cp::PlatformEndpoint target;
  target.kind = cp::PlatformEndpoint::Kind::serial;
  target.device = name;
  cp::ClearpathLink link(io, runtime, runtime, target);
  std::size_t written = 0;
  link.on_written([&](std::span<const std::uint8_t>) { ++written; });
  link.start();  // opens at once; the io_context never runs in this test
  ASSERT_EQ(link.state(), cp::ConnectionState::connected);

  // Big fresh setpoints, each written at once, until the buffer is full.
  cp::SetAbsoluteJoints big;
  for (std::uint8_t j = 0; j < 80; ++j) big.joints.push_back({j, 0.001 * j});
  for (int i = 0; i < 4000 && link.counters().setpoints_replaced == 0; ++i) {
    big.joints[0].angle = 0.0001 * (i % 1000);
    link.set_setpoint(big);
  }
  ASSERT_GT(link.counters().setpoints_replaced, 0u) << "the PTY's buffer never filled";
  ASSERT_GT(written, 10u);  // whole frames went first: the buffer, not the link, held the rest
  cp::SetVelocity zero;
  zero.acceleration = 1.0;
  link.stop_setpoint(zero);

  // The far end starts reading while flush() waits for room.
  std::vector<std::uint8_t> received;
  std::thread reader([&] {
    std::this_thread::sleep_for(100ms);
    std::array<std::uint8_t, 4096> chunk{};
    pollfd p{master, POLLIN, 0};
    while (::poll(&p, 1, 300) > 0) {
      const auto n = ::read(master, chunk.data(), chunk.size());
      if (n <= 0) break;
      received.insert(received.end(), chunk.begin(), chunk.begin() + n);
    }
  });
  link.flush();
  reader.join();
  link.stop();
  ::close(master);

  cp::FrameParser parser;
  parser.feed(received);
  std::vector<cp::Frame> frames;
  while (auto event = parser.poll())
    if (const auto* f = std::get_if<cp::Frame>(&*event)) frames.push_back(*f);
  EXPECT_EQ(parser.counters().errors(), 0u);
  EXPECT_EQ(parser.counters().garbage_bytes, 0u);
  EXPECT_EQ(parser.pending(), 0u);
  // After the last frame pump() finished: the one it left half written, then
  // what flush() took from the client (the stop first, then the joints' setpoint).
  ASSERT_GE(frames.size(), written + 2);
  EXPECT_EQ(frames[written].header.type, cp::SetAbsoluteJoints::kType);
  EXPECT_EQ(frames[written + 1].header.type, cp::SetVelocity::kType);
}

TEST(ClearpathLink, ParsesEndpoints) {
  EXPECT_EQ(cp::parse_platform_endpoint("udp:127.0.0.1:7000")->port, 7000);
  EXPECT_EQ(cp::parse_platform_endpoint("serial:/dev/ttyS1@57600")->baud, 57600u);
  EXPECT_EQ(cp::parse_platform_endpoint("tcp:localhost:1")->kind, cp::PlatformEndpoint::Kind::tcp);
  EXPECT_FALSE(cp::parse_platform_endpoint("udp:127.0.0.1"));
  const auto unknown = cp::parse_platform_endpoint("carrier-pigeon:1");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, jaus::ErrorCode::invalid_argument);
  EXPECT_NE(unknown.error().message().find("'carrier-pigeon:1' is not a Clearpath endpoint (unknown scheme"),
            std::string::npos);
}
