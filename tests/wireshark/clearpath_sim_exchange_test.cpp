// A real Clearpath exchange: the test, as a host on 127.0.0.64:40001, sends
// requests and commands to clearpath-sim on 127.0.0.65:40002 and waits for
// each answer (data, or an ACK: ok, or "type not supported" for a gear on a
// differential platform); both directions become a capture, tshark dissects
// it with the generated plugin, and every frame is compared with `jausctl
// clearpath decode` (--from host for what the test sent, platform for the
// rest).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <set>

#include "../system/child_process.hpp"
#include "clearpath_frame_check.hpp"
#include "jaus/clearpath/codec.hpp"
#include "pcap_writer.hpp"

namespace jaus::test {
namespace clearpath_sim_exchange_test {  // named: the unity build mixes this file's names with others'

namespace cp = jaus::clearpath;

const UdpEndpoint kHost{{127, 0, 0, 64}, 40001};
const UdpEndpoint kPlatform{{127, 0, 0, 65}, 40002};

sockaddr_in address_of(const UdpEndpoint& e) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(e.port);
  a.sin_addr.s_addr = htonl(static_cast<std::uint32_t>(e.ip[0] << 24 | e.ip[1] << 16 | e.ip[2] << 8 | e.ip[3]));
  return a;
}

struct RecordedFrame {
  bool from_platform;
  std::vector<std::uint8_t> bytes;
};

struct Exchange {
  int fd = -1;
  std::vector<RecordedFrame> frames;
  ~Exchange() {
    if (fd >= 0) ::close(fd);
  }
  void send(const std::vector<std::uint8_t>& frame) {
    const auto to = address_of(kPlatform);
    ::sendto(fd, frame.data(), frame.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    frames.push_back({false, frame});
  }
  // Receives until a frame of `type` arrives or `deadline` passes.
  bool await(std::uint16_t type, std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    std::vector<std::uint8_t> buffer(2048);
    while (std::chrono::steady_clock::now() < until) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      const auto n = ::recv(fd, buffer.data(), buffer.size(), 0);
      if (n <= 0) continue;
      frames.push_back({true, {buffer.begin(), buffer.begin() + n}});
      const auto& f = frames.back().bytes;
      if (f.size() >= 11 && static_cast<std::uint16_t>(f[9] | (f[10] << 8)) == type) return true;
    }
    return false;
  }
};

std::vector<std::uint8_t> frame_of(cp::AnyMessage message, std::uint32_t timestamp) {
  auto bytes = cp::encode(cp::Envelope{cp::FrameHeader{0, timestamp, 0, 0}, std::move(message)});
  if (!bytes) throw std::runtime_error(bytes.error().message());
  return *bytes;
}

TEST(TsharkClearpathSim, EveryFrameOfAnExchangeShowsWhatJausctlDecodes) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("clearpath-sim");
  ChildProcess sim({CLEARPATH_SIM_PATH, "--udp", "127.0.0.65:40002"}, (session.dir() / "sim.log").string());
  ASSERT_TRUE(sim.started());
  Exchange exchange;
  exchange.fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  const auto host = address_of(kHost);
  ASSERT_EQ(::bind(exchange.fd, reinterpret_cast<const sockaddr*>(&host), sizeof host), 0)
      << "cannot bind 127.0.0.64:40001";

  // The simulator answers once it is up: ask until it does (generous deadline for a loaded machine).
  bool up = false;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  for (std::uint32_t t = 1; !up && std::chrono::steady_clock::now() < until; ++t) {
    exchange.send(frame_of(*cp::make_message(0x4001), t));
    up = exchange.await(0x8001, std::chrono::milliseconds(500));
  }
  ASSERT_TRUE(up) << "clearpath-sim did not answer: " << sim.output();

  // Requests answered with data (type + 0x4000): names, firmware (packed date-time), lists, column records.
  std::uint32_t t = 100;
  for (const std::uint16_t request : {0x4002, 0x4003, 0x4004, 0x4005, 0x4010, 0x4800}) {
    exchange.send(frame_of(*cp::make_message(request), ++t));
    EXPECT_TRUE(exchange.await(static_cast<std::uint16_t>(request + 0x4000), std::chrono::seconds(10))) << request;
  }
  // Commands answered with an ACK of their type: ok, and "type not supported" (no gear on a differential platform).
  cp::AnyMessage velocity = *cp::make_message(0x0204);
  velocity.get<cp::SetVelocity>().translational = 0.5;
  velocity.get<cp::SetVelocity>().acceleration = 1.0;
  exchange.send(frame_of(velocity, ++t));
  EXPECT_TRUE(exchange.await(0x0204, std::chrono::seconds(10)));
  exchange.send(frame_of(*cp::make_message(0x0212), ++t));
  EXPECT_TRUE(exchange.await(0x0212, std::chrono::seconds(10)));

  PcapWriter pcap((session.dir() / "sim.pcap").string());
  for (const auto& f : exchange.frames)
    pcap.add(f.from_platform ? kPlatform : kHost, f.from_platform ? kHost : kPlatform, f.bytes);
  pcap.close();
  std::string failure;
  const auto layers = session.dissect(session.dir() / "sim.pcap", {"clearpath.platform_port:40002"}, failure);
  ASSERT_EQ(layers.size(), exchange.frames.size()) << failure;
  std::set<std::string> names;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    SCOPED_TRACE("packet " + std::to_string(i + 1));
    const auto& f = exchange.frames[i];
    ASSERT_TRUE(cp::decode_frame(f.bytes)) << "one frame per datagram expected";
    ASSERT_TRUE(layers[i].is_object()) << "not Clearpath to tshark: " << layers[i].dump();
    for (const auto& problem : check_clearpath_frame(session, layers[i], f.bytes, f.from_platform))
      ADD_FAILURE() << problem;
    names.insert(layers[i]["clearpath.name"].get<std::string>());
  }
  for (const char* name : {"platform_info", "firmware_info", "system_status", "power_status", "encoders", "ack"})
    EXPECT_EQ(names.count(name), 1u) << name;
}

}  // namespace clearpath_sim_exchange_test
}  // namespace jaus::test
