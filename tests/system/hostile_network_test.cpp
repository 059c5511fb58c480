// Issue 28 on real processes: jausd and jausctl (and raw sockets for what
// no well-behaved tool sends), every process on its own loopback address, so
// each is a host of its own to jausd. docs/safety.md, "Hostile network".
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <sstream>
#include <thread>

#include "../benchmarks/bench_support.hpp"
#include "default_jausd.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;

constexpr const char* kNode = "127.0.0.50";
constexpr int kSubsystem = 9;
constexpr const char* kDriver = "9.1.33.1";
constexpr const char* kHolderHost = "127.0.0.51";
constexpr const char* kOtherHost = "127.0.0.52";
constexpr const char* kStatusHost = "127.0.0.53";
constexpr const char* kPortsHost = "127.0.0.57";

class HostileNetwork : public ::testing::Test {
 protected:
  void start(const std::string& more_transport = "") {
    jausd = std::make_unique<DefaultJausd>("hostile", kSubsystem, kNode, "platform: model\n", more_transport);
    ASSERT_TRUE(jausd->started());
    ASSERT_TRUE(poll_status("ready", 30s)) << jausd->output();
  }
  // `jausctl ARGS` from `host` (any port) as `as`; its exit code and output.
  std::pair<int, std::string> run(const std::string& name, std::vector<std::string> args, const std::string& host,
                                  const std::string& as) {
    auto child = jausd->jausctl(name, std::move(args), host + ":0", as);
    EXPECT_TRUE(child->started());
    const int code = child->wait(20s).value_or(-1);
    return {code, child->output()};
  }
  std::optional<std::string> status() {
    const auto [code, output] = run("status", {"status", kDriver, "--timeout", "1"}, kStatusHost, "254.53.40.1");
    if (code != 0) return std::nullopt;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json j = Json::parse(line, nullptr, false);
        if (!j.is_discarded()) return j.value("primary_status", "");
      }
    return std::nullopt;
  }
  bool poll_status(const std::string& wanted, std::chrono::seconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    std::optional<std::string> last;
    while (std::chrono::steady_clock::now() < until) {
      last = status();
      if (last == wanted) return true;
      std::this_thread::sleep_for(200ms);
    }
    ADD_FAILURE() << kDriver << " not " << wanted << " within " << deadline.count()
                  << " s; last seen: " << last.value_or("(no answer)");
    return false;
  }

  std::unique_ptr<DefaultJausd> jausd;
};

// A one-shot `jausctl emergency set` leaves a holder whose ID another host
// could claim once it is silent, to send the Clear. The node keeps that ID
// at the holder's host while it holds the emergency; the operator's own
// host (a new jausctl, a new port) still clears it.
TEST_F(HostileNetwork, AHoldersIdCannotBeTakenFromAnotherHostToClearItsEmergency) {
  start();
  const std::string holder = "254.51.40.1";
  auto [set, set_output] = run("set", {"emergency", kDriver, "set", "--timeout", "5"}, kHolderHost, holder);
  ASSERT_EQ(set, 0) << set_output;
  EXPECT_NE(set_output.find("emergency set by " + holder), std::string::npos) << set_output;
  // Longer than the silence after which an unpinned ID may move to another host.
  std::this_thread::sleep_for(4s);

  auto [forged, forged_output] = run("forged", {"emergency", kDriver, "clear", "--timeout", "1"}, kOtherHost, holder);
  EXPECT_NE(forged, 0) << forged_output;  // its datagrams are dropped: not even the status query is answered
  EXPECT_EQ(status(), "emergency");
  EXPECT_TRUE(jausd->output_contains("spoofed, or two peers with one ID")) << jausd->output();

  auto [cleared, cleared_output] = run("clear", {"emergency", kDriver, "clear", "--timeout", "5"}, kHolderHost, holder);
  EXPECT_EQ(cleared, 0) << cleared_output;
  EXPECT_TRUE(poll_status("ready", 10s));
}

// Safe by default, shown with a control_from that leaves one loopback host
// out: that host may watch and stop the vehicle, never take control.
TEST_F(HostileNetwork, AHostOutsideControlFromMayWatchAndStopButNotTakeControl) {
  start(std::string("control_from: [") + kStatusHost + "/32, " + kHolderHost + "/32]");
  const std::string outsider = "254.52.40.1";
  auto [control, control_output] =
      run("control-outside", {"control", kDriver, "--authority", "5", "--for", "1", "--timeout", "2"}, kOtherHost,
          outsider);
  EXPECT_NE(control, 0) << control_output;
  EXPECT_NE(control_output.find("refused"), std::string::npos) << control_output;

  auto [set, set_output] = run("set-outside", {"emergency", kDriver, "set", "--timeout", "5"}, kOtherHost, outsider);
  EXPECT_EQ(set, 0) << set_output;  // anyone who may talk to the node may stop it
  auto [clear, clear_output] =
      run("clear-outside", {"emergency", kDriver, "clear", "--timeout", "5"}, kOtherHost, outsider);
  EXPECT_EQ(clear, 0) << clear_output;  // and release its own hold
  EXPECT_TRUE(poll_status("ready", 10s));

  auto [inside, inside_output] =
      run("control-inside", {"control", kDriver, "--authority", "5", "--for", "1", "--timeout", "2"}, kHolderHost,
          "254.51.40.1");
  EXPECT_EQ(inside, 0) << inside_output;
  EXPECT_NE(inside_output.find("granted to 254.51.40.1"), std::string::npos) << inside_output;
}

// One host with 300 ports (each a node ID of its own) cannot fill the node's
// table of endpoints: an OCU from another host is still answered.
TEST_F(HostileNetwork, OneHostWithManyPortsDoesNotLockOutAnotherOcu) {
  start();
  boost::asio::io_context io;
  std::vector<boost::asio::ip::udp::socket> sockets;
  const boost::asio::ip::udp::endpoint node(boost::asio::ip::make_address(kNode), 3794);
  for (int i = 0; i < 300; ++i) {
    auto& socket = sockets.emplace_back(
        io, boost::asio::ip::udp::endpoint(boost::asio::ip::make_address(kPortsHost), 0));
    const Address from{static_cast<std::uint8_t>(100 + i / 200), static_cast<std::uint8_t>(1 + i % 200), 40, 1};
    const auto bytes = bench::datagram(from, Address{kSubsystem, 1, 33, 1}, msg::QueryComponentStatus{});
    socket.send_to(boost::asio::buffer(bytes), node);
    if (i % 20 == 19) std::this_thread::sleep_for(5ms);  // no burst the kernel would drop
  }
  EXPECT_TRUE(poll_status("ready", 10s)) << jausd->output();
}

}  // namespace
}  // namespace jaus::test
