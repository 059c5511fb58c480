// Two jausd processes on one host (127.0.0.21 and 127.0.0.22, port 3794, as
// peers that answer IP:3794 require), and an OCU node in the test on
// 127.0.0.23: they find each other, the OCU controls a component of one and
// subscribes to another, when one node dies the other notices, and one
// serves its counters for Prometheus (metrics). Real
// processes and sockets: only outcomes are asserted, with generous deadlines.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <csignal>
#include <cstring>  // sigabbrev_np
#include <array>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <fstream>

#include "../support/prometheus_text.hpp"
#include "child_process.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/host/node_host.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

const Address kOcu{9, 1, 40, 1};
const Address kManagerA{1, 1, 1, 1}, kManagerB{2, 1, 1, 1};
const Address kCommunicatorA{1, 1, 35, 1}, kCommunicatorB{2, 1, 35, 1};

// The OCU's component: keeps every message no handler took (the reports).
class Ocu : public rt::Component {
 public:
  using Component::Component;
  template <class M>
  void send_to(const Address& to, const M& m) {
    send(to, m);
  }
  template <class M>
  std::vector<M> received_from(const Address& from) const {
    std::vector<M> out;
    for (const auto& [h, payload] : inbox)
      if (h.command_code == M::code && h.source == from)
        if (auto m = wire::decode_payload<M>(payload)) out.push_back(*m);
    return out;
  }
  std::vector<std::pair<Header, std::vector<std::uint8_t>>> inbox;

 protected:
  bool unhandled(const Header& h, std::span<const std::uint8_t> payload) override {
    inbox.emplace_back(h, std::vector<std::uint8_t>(payload.begin(), payload.end()));
    return true;
  }
};

// The controller is checked every 0.5 s: only a stall of about a second drops
// one that answers (which the component level must not do sooner either).
std::string node_config(int subsystem, const std::string& bind, const std::string& peer) {
  return "identification: {subsystem: " + std::to_string(subsystem) + ", node: 1}\n"
         "heartbeat_hz: 5\n"
         "control: {controller_timeout_s: 1.5}\n"
         "liveness: {component_timeout_s: 3, node_timeout_s: 1.5, subsystem_timeout_s: 1.5}\n"
         "transport:\n"
         "  bind: " + bind + "\n"
         "  multicast: null\n"  // static peers only: tests side by side on one loopback must not meet
         "  peers: [" + peer + "]\n";
}

class TwoNodes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("jaus-two-nodes-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    // Node a also serves its counters (docs/running.md, "Metrics").
    a = start("a", node_config(1, "127.0.0.21:3794", "127.0.0.22:3794") + "metrics: {listen: 127.0.0.21}\n");
    b = start("b", node_config(2, "127.0.0.22:3794", "127.0.0.21:3794"));

    host::HostConfig config;
    config.node.subsystem = kOcu.subsystem;
    config.node.node = kOcu.node;
    config.link.bind = *transport::parse_endpoint("127.0.0.23:3794");
    config.link.peers = {{*transport::parse_endpoint("127.0.0.21:3794"), transport::Framing::opc},
                         {*transport::parse_endpoint("127.0.0.22:3794"), transport::Framing::judp}};
    config.settings.identity.subsystem_type = 20001;
    config.settings.identity.heartbeat_period = 200ms;
    config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "ocu node manager", {}, 0, {}}};
    auto opened = host::NodeHost::open(config, io);
    ASSERT_TRUE(opened) << opened.error().message();
    node_host = std::move(*opened);
    ocu = &node_host->emplace<Ocu>(node_host->component_config("ocu", kOcu.component, kOcu.instance));
    // The daemons take a moment to start (longer under sanitizers): a
    // datagram sent before they listen is lost, so wait until both answer.
    for (const Address& daemon : {kManagerA, kManagerB})
      ASSERT_TRUE(answers(daemon)) << (daemon == kManagerA ? a : b)->output();
    ocu->inbox.clear();
  }

  // Asks `manager` for its identification until it answers.
  bool answers(const Address& manager) {
    return run_until([&] {
      ocu->send_to(manager, msg::QueryIdentification{{msg::identification::kComponent}});
      return run_until([&] { return !ocu->received_from<msg::ReportIdentification>(manager).empty(); }, 200ms);
    }, 20s);
  }
  void TearDown() override {
    node_host.reset();
    a.reset();
    b.reset();
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }

  std::unique_ptr<ChildProcess> start(const std::string& name, const std::string& yaml) {
    const fs::path config = dir / (name + ".yaml");
    std::ofstream(config) << yaml;
    auto child = std::make_unique<ChildProcess>(
        std::vector<std::string>{JAUSD_PATH, "--config", config.string(), "--log-level", "debug"},
        (dir / (name + ".log")).string());
    EXPECT_TRUE(child->started());
    return child;
  }

  // Runs the OCU's node until `done` or the deadline.
  bool run_until(const std::function<bool()>& done, std::chrono::milliseconds deadline = 10s) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!done()) {
      if (std::chrono::steady_clock::now() > until) return false;
      io.run_for(10ms);
    }
    return true;
  }
  void run_for(std::chrono::milliseconds duration) {
    run_until([] { return false; }, duration);
  }
  // Asks `manager` for its subsystem list until `subsystem` is (or is not) in it.
  bool subsystem_list_shows(const Address& manager, std::uint8_t subsystem, bool present) {
    return run_until([&] {
      ocu->inbox.clear();
      ocu->send_to(manager, msg::QuerySubsystemList{});
      run_until([&] { return !ocu->received_from<msg::ReportSubsystemList>(manager).empty(); }, 300ms);
      const auto lists = ocu->received_from<msg::ReportSubsystemList>(manager);
      if (lists.empty()) return false;
      bool found = false;
      for (const auto& s : lists.back().subsystems) found |= s.subsystem == subsystem;
      return found == present;
    });
  }

  fs::path dir;
  std::unique_ptr<ChildProcess> a, b;
  boost::asio::io_context io;
  std::unique_ptr<host::NodeHost> node_host;
  Ocu* ocu = nullptr;
};

// GET http://127.0.0.21:9794/metrics, as Prometheus scrapes it.
std::string scrape_node_a() {
  namespace http = boost::beast::http;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  boost::beast::error_code ec;
  socket.connect({boost::asio::ip::make_address_v4("127.0.0.21"), 9794}, ec);
  if (ec) return "connect: " + ec.message();
  http::request<http::empty_body> request(http::verb::get, "/metrics", 11);
  request.set(http::field::host, "127.0.0.21:9794");
  http::write(socket, request, ec);
  boost::beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(socket, buffer, response, ec);
  return response.result() == http::status::ok ? response.body() : "status " + std::to_string(response.result_int());
}

TEST_F(TwoNodes, ANodeServesItsCountersForPrometheus) {
  // SetUp's queries reached it from the OCU; the other node's heartbeats come every 200 ms.
  run_for(1s);
  const std::string text = scrape_node_a();
  const auto samples = parse_exposition(text);
  ASSERT_FALSE(samples.empty()) << text;
  EXPECT_GE(samples.at(R"(jaus_peer_packets_received_total{peer="9.1"})"), 1) << text;
  EXPECT_GE(samples.at(R"(jaus_peer_packets_received_total{peer="2.1"})"), 2) << text;
  EXPECT_GE(samples.at(R"(jaus_transport_datagrams_received_total)"), 3);
  EXPECT_EQ(first_sample(samples, R"(jaus_component_primary_status{component="1.1.35.1",)"),
            static_cast<double>(msg::PrimaryStatus::ready))
      << text;
}

TEST_F(TwoNodes, FindEachOther) {
  EXPECT_TRUE(subsystem_list_shows(kManagerA, 2, true)) << a->output();
  EXPECT_TRUE(subsystem_list_shows(kManagerB, 1, true)) << b->output();
  // We speak JUDP to B (our static peer entry) and OPC to A: each answers in kind.
  EXPECT_EQ(node_host->udp_link()->routes().route(2, 1)->framing, transport::Framing::judp);
  EXPECT_EQ(node_host->udp_link()->routes().route(1, 1)->framing, transport::Framing::opc);
}

TEST_F(TwoNodes, TheOcuControlsAComponentOfTheOtherNodeAndHoldsIt) {
  ASSERT_TRUE(subsystem_list_shows(kManagerA, 2, true)) << a->output();
  ocu->send_to(kCommunicatorB, msg::RequestComponentControl{{50}});
  ASSERT_TRUE(run_until([&] { return !ocu->received_from<msg::ConfirmComponentControl>(kCommunicatorB).empty(); }));
  EXPECT_EQ(ocu->received_from<msg::ConfirmComponentControl>(kCommunicatorB).front().response_code, 0);
  // Past the check that would drop a silent controller (at 2 s: silence over
  // the 1.5 s timeout), control is still ours: the OCU answers B's liveness checks.
  run_for(2500ms);
  ocu->inbox.clear();
  ocu->send_to(kCommunicatorB, msg::QueryComponentControl{});
  ASSERT_TRUE(run_until([&] { return !ocu->received_from<msg::ReportComponentControl>(kCommunicatorB).empty(); }));
  EXPECT_EQ(ocu->received_from<msg::ReportComponentControl>(kCommunicatorB).front().controller, kOcu) << b->output();
  EXPECT_TRUE(ocu->received_from<msg::RejectComponentControl>(kCommunicatorB).empty());
  // A command only the controller may give is executed.
  ocu->send_to(kCommunicatorB, msg::Standby{});
  ocu->send_to(kCommunicatorB, msg::QueryComponentStatus{});
  EXPECT_TRUE(run_until([&] {
    const auto s = ocu->received_from<msg::ReportComponentStatus>(kCommunicatorB);
    return !s.empty() && s.back().primary_status == static_cast<std::uint8_t>(msg::PrimaryStatus::standby);
  }));
}

// Across processes on the real clock, only what no load can change: reports
// keep coming, flagged as SC reports, numbered one after another. Their rate
// is exact under virtual time (tests/runtime/service_connection_test.cpp);
// jitter on the real clock is bench_sc_jitter's figure.
TEST_F(TwoNodes, AServiceConnectionDeliversNumberedReports) {
  std::vector<Header> reports;
  ocu->subscribe<msg::ReportComponentStatus>(
      kCommunicatorA, 10, 0, [&](const Header& h, const msg::ReportComponentStatus&) { reports.push_back(h); });
  ASSERT_TRUE(run_until([&] { return reports.size() >= 5; }, 20s)) << a->output();
  for (std::size_t i = 1; i < reports.size(); ++i) {
    EXPECT_TRUE(reports[i].service_connection);
    EXPECT_EQ(reports[i].sequence, static_cast<std::uint16_t>(reports[i - 1].sequence + 1));
  }
}

TEST_F(TwoNodes, OneNoticesTheOthersLoss) {
  ASSERT_TRUE(subsystem_list_shows(kManagerA, 2, true)) << a->output();
  b->signal(SIGKILL);  // no goodbye: a crash or a cut cable
  EXPECT_TRUE(subsystem_list_shows(kManagerA, 2, false)) << a->output();
  EXPECT_TRUE(a->output_shows("node 2.1.0.0 silent: lost")) << a->output();
}

// Each signal that asks a process to end (systemctl stop, Ctrl-C, Ctrl-\, a
// closed terminal) runs every component's stop path before the exit.
class TwoNodesStopSignal : public TwoNodes, public ::testing::WithParamInterface<int> {};

TEST_P(TwoNodesStopSignal, IsAnOrderlyShutdown) {
  const int signal = GetParam();
  ocu->send_to(kCommunicatorA, msg::RequestComponentControl{{50}});
  ASSERT_TRUE(run_until([&] { return !ocu->received_from<msg::ConfirmComponentControl>(kCommunicatorA).empty(); }));
  a->signal(signal);
  // The controller hears that control is gone (the platform was stopped).
  EXPECT_TRUE(run_until([&] { return !ocu->received_from<msg::RejectComponentControl>(kCommunicatorA).empty(); }));
  EXPECT_EQ(a->wait(20s), 0);
  EXPECT_TRUE(a->output_shows("Ready -> Shutdown")) << a->output();
  EXPECT_TRUE(a->output_shows("stopped (SIG" + std::string(sigabbrev_np(signal)) + ")")) << a->output();
}

INSTANTIATE_TEST_SUITE_P(EverySignal, TwoNodesStopSignal, ::testing::Values(SIGTERM, SIGINT, SIGHUP, SIGQUIT),
                         [](const ::testing::TestParamInfo<int>& signal) { return std::string(sigabbrev_np(signal.param)); });

// Fills a pipe that has a reader (which never reads) to the brim, as a log
// output nobody reads ends up.
bool fill(const fs::path& fifo) {
  const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (writer < 0) return false;
  const std::array<char, 4096> filler{};
  std::size_t filled = 0;
  for (ssize_t n; (n = ::write(writer, filler.data(), filler.size())) > 0;) filled += static_cast<std::size_t>(n);
  ::close(writer);
  return filled >= filler.size();
}

// A log output nobody reads (a full pipe, a stopped terminal) must not stall
// the event loop: the node keeps answering while its log cannot be written,
// and once the pipe drains its last lines say how it stopped.
TEST_F(TwoNodes, AStalledLogOutputNeverStallsTheNode) {
  const fs::path fifo = dir / "c.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // open, never read until the end
  ASSERT_GE(reader, 0);
  ASSERT_TRUE(fill(fifo));
  const fs::path config = dir / "c.yaml";
  std::ofstream(config) << node_config(3, "127.0.0.20:3794", "127.0.0.23:3794");
  ChildProcess c({JAUSD_PATH, "--config", config.string(), "--log-level", "debug"}, fifo.string());
  ASSERT_TRUE(c.started());
  const Address manager_c{3, 1, 1, 1};
  ASSERT_TRUE(answers(manager_c));
  // Queries and their debug lines, while the log cannot be written.
  for (int i = 0; i < 5000; ++i) {
    ocu->send_to(manager_c, msg::QueryIdentification{{msg::identification::kComponent}});
    if (i % 100 == 0) run_for(5ms);
  }
  run_for(500ms);
  for (int round = 0; round < 5; ++round) {
    ocu->inbox.clear();
    EXPECT_TRUE(answers(manager_c)) << "round " << round;
  }
  c.signal(SIGTERM);
  // The stop runs at once; the exit waits for the queued lines to be written.
  std::string tail;
  std::array<char, 65536> buffer;
  const auto read_what_is_there = [&] {
    for (ssize_t n; (n = ::read(reader, buffer.data(), buffer.size())) > 0;) {
      tail.append(buffer.data(), static_cast<std::size_t>(n));
      if (tail.size() > 1'000'000) tail.erase(0, tail.size() - 100'000);
    }
  };
  std::optional<int> exit_code;
  const auto until = std::chrono::steady_clock::now() + 20s;
  while (!exit_code && std::chrono::steady_clock::now() < until) {
    read_what_is_there();
    exit_code = c.wait(20ms);
  }
  read_what_is_there();  // the last lines, written just before the exit
  ::close(reader);
  EXPECT_EQ(exit_code, std::optional<int>(0));
  EXPECT_NE(tail.find("stopped (SIGTERM)"), std::string::npos) << tail.substr(tail.size() > 2000 ? tail.size() - 2000 : 0);
}

// An output nobody ever reads: the stop still runs in full (the controller
// hears control is gone) and the process exits with its code once its queued
// lines have had jausd::kLogDrainLimit (5 s) to be written, instead of waiting
// for a reader forever.
TEST_F(TwoNodes, AnOutputNobodyReadsNeverKeepsAStoppedNodeFromExiting) {
  const fs::path fifo = dir / "c.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // open, never read
  ASSERT_GE(reader, 0);
  ASSERT_TRUE(fill(fifo));  // jausd's first line blocks its logging thread
  const fs::path config = dir / "c.yaml";
  std::ofstream(config) << node_config(3, "127.0.0.20:3794", "127.0.0.23:3794");
  ChildProcess c({JAUSD_PATH, "--config", config.string(), "--log-level", "debug"}, fifo.string());
  ASSERT_TRUE(c.started());
  const Address manager_c{3, 1, 1, 1};
  const Address communicator_c{3, 1, 35, 1};
  ASSERT_TRUE(answers(manager_c));
  ocu->send_to(communicator_c, msg::RequestComponentControl{{50}});
  ASSERT_TRUE(run_until([&] { return !ocu->received_from<msg::ConfirmComponentControl>(communicator_c).empty(); }));
  c.signal(SIGTERM);
  EXPECT_TRUE(run_until([&] { return !ocu->received_from<msg::RejectComponentControl>(communicator_c).empty(); }));
  EXPECT_EQ(c.wait(30s), std::optional<int>(0));
  ::close(reader);
}

TEST_F(TwoNodes, ABusyAddressAndABadFileExitWith2AndOneLine) {
  ASSERT_TRUE(subsystem_list_shows(kManagerA, 2, true));
  auto second = start("second", node_config(3, "127.0.0.21:3794", "127.0.0.22:3794"));
  EXPECT_EQ(second->wait(20s), 2);
  EXPECT_TRUE(second->output_shows("127.0.0.21:3794 is already in use")) << second->output();
  auto bad = start("bad", "heartbeat_hz: 1\nhearbeat_hz: 2\n");
  EXPECT_EQ(bad->wait(20s), 2);
  EXPECT_TRUE(bad->output_shows("bad.yaml:2: unknown key 'hearbeat_hz'")) << bad->output();
}

}  // namespace
}  // namespace jaus::test
