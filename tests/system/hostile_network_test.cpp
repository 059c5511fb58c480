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
constexpr const char* kRawOcuHost = "127.0.0.54";

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
  EXPECT_TRUE(jausd->output_shows("spoofed, or two peers with one ID")) << jausd->output();

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


// Issue 43: an OCU written from the spec (OpenJAUS's, raw sockets here) that
// never ACKs anything, so never answers the node's challenge, against the
// DEFAULT configuration (verify_endpoints on): each of its queries is
// answered, its Request Component Control confirmed, its Set Wrench Effort
// drives the simulated platform, and its Set Emergency stops it.
class NeverAckingOcu {
 public:
  NeverAckingOcu(const std::string& host, const std::string& node)
      : socket_(io_, boost::asio::ip::udp::endpoint(boost::asio::ip::make_address(host), 0)),
        node_(boost::asio::ip::make_address(node), 3794) {
    socket_.non_blocking(true);
  }
  template <class M>
  void send(const Address& to, const M& message) {
    socket_.send_to(boost::asio::buffer(bench::datagram(kSelf, to, message)), node_);
  }
  // With an ACK request and this sequence number (it never ACKs, but it may ask).
  template <class M>
  void send_asking_ack(const Address& to, const M& message, std::uint16_t sequence) {
    socket_.send_to(boost::asio::buffer(bench::datagram(kSelf, to, message, 6, AckNak::ack_requested, sequence)),
                    node_);
  }
  // Sends `query` to `to` (again every second) until a `Report` from `to` arrives or the deadline.
  template <class Report, class Query>
  std::optional<Report> ask(const Address& to, const Query& query, std::chrono::seconds deadline = 10s) {
    return ask_until<Report>(to, query, [](const Report&) { return true; }, deadline);
  }
  template <class Report, class Query>
  std::optional<Report> ask_until(const Address& to, const Query& query, const std::function<bool(const Report&)>& good,
                                  std::chrono::seconds deadline, const std::function<void()>& meanwhile = {}) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    std::optional<Report> last;
    auto sent = std::chrono::steady_clock::time_point{}, ticked = sent;
    while (std::chrono::steady_clock::now() < until) {
      if (meanwhile && std::chrono::steady_clock::now() - ticked > 100ms) {
        meanwhile();
        ticked = std::chrono::steady_clock::now();
      }
      if (std::chrono::steady_clock::now() - sent > 250ms) {
        send(to, query);
        sent = std::chrono::steady_clock::now();
      }
      if (auto report = receive<Report>(to, 10ms)) {
        last = report;
        if (good(*report)) return report;
      }
    }
    return last;
  }
  // The next `M` from `from` within `wait`; challenges (ACK requested) are counted and ignored.
  template <class M>
  std::optional<M> receive(const Address& from, std::chrono::milliseconds wait) {
    const auto until = std::chrono::steady_clock::now() + wait;
    std::array<std::uint8_t, 9000> buffer{};
    while (std::chrono::steady_clock::now() < until) {
      boost::system::error_code ec;
      boost::asio::ip::udp::endpoint sender;
      const std::size_t size = socket_.receive_from(boost::asio::buffer(buffer), sender, 0, ec);
      if (ec) {
        std::this_thread::sleep_for(2ms);
        continue;
      }
      const auto unframed = transport::unframe(std::span(buffer).first(size));
      if (!unframed) continue;
      const Header& h = unframed->packet.header;
      if (h.ack_nak == AckNak::ack_requested) ++ack_requests_ignored;
      if (h.command_code != M::code || h.source != from) continue;
      if (auto m = wire::decode_payload<M>(unframed->packet.payload)) return *m;
    }
    return std::nullopt;
  }
  static constexpr Address kSelf{254, 54, 40, 1};
  int ack_requests_ignored = 0;

 private:
  boost::asio::io_context io_;
  boost::asio::ip::udp::socket socket_;
  boost::asio::ip::udp::endpoint node_;
};

// An RA operator unit that keeps no state numbers from 1 on every start (as
// Jr does in JSS) and asks ACKs of its commands. Restarted within the node's
// duplicate window, its Request Component Control is the same message under
// the same number as the first run's: the default jausd obeys it at once
// rather than ACK it and drop it as a copy.
TEST_F(HostileNetwork, ARestartedRaOperatorNumberingFromOneIsObeyedAtOnce) {
  jausd = std::make_unique<DefaultJausd>("restarted-ra-operator", kSubsystem, kNode);  // the default configuration
  ASSERT_TRUE(jausd->started());
  const Address driver{kSubsystem, 1, 33, 1};
  const auto run = [&](const char* name) -> std::optional<msg::ConfirmComponentControl> {
    NeverAckingOcu ocu(kRawOcuHost, kNode);  // a new port each run, as a restarted program gets
    // The daemon may still be starting (generous deadline).
    EXPECT_TRUE(ocu.ask<msg::ReportComponentStatus>(driver, msg::QueryComponentStatus{}, 30s)) << name;
    ocu.send_asking_ack(driver, msg::RequestComponentControl{{10}}, 1);
    auto confirm = ocu.receive<msg::ConfirmComponentControl>(driver, 3s);
    ocu.send_asking_ack(driver, msg::ReleaseComponentControl{}, 2);
    (void)ocu.receive<msg::RejectComponentControl>(driver, 1s);
    return confirm;
  };
  const auto first = run("first run");
  ASSERT_TRUE(first) << jausd->output();
  EXPECT_EQ(first->response_code, 0) << jausd->output();  // control accepted
  const auto again = run("restarted run");  // well within the 2 s window
  ASSERT_TRUE(again) << "the restarted operator's Request Component Control was dropped as a copy\n" << jausd->output();
  EXPECT_EQ(again->response_code, 0) << jausd->output();
  // The node says so (its first message after the restart is the status query, number 0).
  EXPECT_TRUE(jausd->output_shows("254.54.40.1 restarted (sequence number ")) << jausd->output();
}

TEST_F(HostileNetwork, AnOcuThatNeverAcksIsAnsweredControlsDrivesAndStops) {
  jausd = std::make_unique<DefaultJausd>("never-acks", kSubsystem, kNode);  // the default configuration
  ASSERT_TRUE(jausd->started());
  const Address manager{kSubsystem, 1, 1, 1}, driver{kSubsystem, 1, 33, 1}, pose{kSubsystem, 1, 38, 1},
      velocity{kSubsystem, 1, 42, 1};
  NeverAckingOcu ocu(kRawOcuHost, kNode);
  // The queries an OCU opens with; the daemon may still be starting (generous deadline).
  ASSERT_TRUE(ocu.ask<msg::ReportComponentStatus>(driver, msg::QueryComponentStatus{}, 30s)) << jausd->output();
  EXPECT_TRUE(ocu.ask<msg::ReportIdentification>(manager, msg::QueryIdentification{{msg::identification::kSubsystem}}));
  EXPECT_TRUE(ocu.ask<msg::ReportConfiguration>(manager, msg::QueryConfiguration{{msg::identification::kSubsystem}}));
  EXPECT_TRUE(ocu.ask<msg::ReportServices>(manager, msg::QueryServices{}));
  const auto start = ocu.ask_until<msg::ReportGlobalPose>(
      pose, msg::QueryGlobalPose{{0x0003}}, [](const auto& p) { return p.latitude_deg.has_value(); }, 10s);
  ASSERT_TRUE(start && start->latitude_deg) << jausd->output();

  ocu.send(driver, msg::RequestComponentControl{{10}});
  const auto confirm = ocu.receive<msg::ConfirmComponentControl>(driver, 5s);
  ASSERT_TRUE(confirm) << jausd->output();
  EXPECT_EQ(confirm->response_code, 0) << jausd->output();  // control accepted

  // Full ahead at 10 Hz (the driver's command timeout is 0.5 s) while it polls the pose: the platform moves.
  msg::SetWrenchEffort ahead;
  ahead.propulsive_linear_effort_x_percent = 100;
  const auto drive = [&] { ocu.send(driver, ahead); };
  constexpr double kMetresPerDegreeOfLatitude = 111'132;
  const auto moved = ocu.ask_until<msg::ReportGlobalPose>(
      pose, msg::QueryGlobalPose{{0x0003}},
      [&](const auto& p) {
        return p.latitude_deg && (*p.latitude_deg - *start->latitude_deg) * kMetresPerDegreeOfLatitude > 1.0;
      },
      20s, drive);
  ASSERT_TRUE(moved && moved->latitude_deg) << jausd->output();
  EXPECT_GT((*moved->latitude_deg - *start->latitude_deg) * kMetresPerDegreeOfLatitude, 1.0) << jausd->output();

  // Set Emergency from the same OCU, which goes on sending efforts: the drive stops.
  ocu.send(driver, msg::SetEmergency{});
  const auto emergency = ocu.ask_until<msg::ReportComponentStatus>(
      driver, msg::QueryComponentStatus{}, [](const auto& s) { return (s.primary_status & 0x0F) == 5; }, 10s, drive);
  ASSERT_TRUE(emergency) << jausd->output();
  EXPECT_EQ(emergency->primary_status & 0x0F, 5) << jausd->output();
  const auto stopped = ocu.ask_until<msg::ReportVelocityState>(
      velocity, msg::QueryVelocityState{{0x0001}},
      [](const auto& v) { return v.velocity_x_mps && *v.velocity_x_mps == 0.0; }, 10s, drive);
  ASSERT_TRUE(stopped && stopped->velocity_x_mps) << jausd->output();
  EXPECT_EQ(*stopped->velocity_x_mps, 0.0);
  EXPECT_TRUE(jausd->output_shows("drive stopped: entered Emergency")) << jausd->output();
  // It never answered a challenge, and nothing it asked for went unanswered for it.
  EXPECT_FALSE(jausd->output_contains("not executed: its reply could not be sent")) << jausd->output();
}

}  // namespace
}  // namespace jaus::test
