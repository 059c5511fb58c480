// Client link <-> simulator server over real loopback UDP and a PTY pair.
// Generous timeouts; assertions are about behaviour, not timing figures.
#include <gtest/gtest.h>

#include <functional>
#include <map>

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
  ASSERT_FALSE(server->start());
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
  ASSERT_FALSE(server->start());
  const auto before = received.of(0x8800);
  ASSERT_TRUE(run_until(io, [&] { return received.of(0x8800) >= before + 10; }, 20s));
  EXPECT_GE(link.core().counters().reconnects, 1u);
  link.stop();
}

TEST(ClearpathLinkUdp, WatchdogStopsThePlatformWhenSetpointsCease) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  sim::SimServer server(io, runtime, runtime, {}, sim::PlatformConfig{});
  ASSERT_FALSE(server.start());
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
  ASSERT_FALSE(server.start());
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
