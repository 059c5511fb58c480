// The node's counters for Prometheus (jaus/host/metrics.hpp,
// metrics_server.hpp): the text is valid exposition format (every sample in
// its declared family, names and labels well formed, each family once), it
// says per peer what was exchanged and the round trip measured, per
// component its state; the server answers GET /metrics, refuses other paths
// and methods, asks a token when it has one, and will not listen beyond
// loopback without one.
#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <thread>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/metrics.hpp"
#include "jaus/host/metrics_server.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/testing/memory_link.hpp"
#include "../support/prometheus_text.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

class MetricsTest : public ::testing::Test {
 protected:
  static constexpr Address kOcu{2, 1, 40, 1};
  static constexpr Address kDriver{1, 1, 33, 1};

  MetricsTest() {
    host::HostConfig config;
    config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "node manager", {}, 0, {}},
                         host::ComponentSpec{"primitive_driver", 33, 1, 0, "primitive driver", {}, 0, {}}};
    auto attached = host::NodeHost::attach(config, vehicle_link, time, time, {});
    EXPECT_TRUE(attached) << attached.error().message();
    vehicle = std::move(*attached);
    vehicle_link.deliver_to(vehicle->node());
    node::NodeConfig ocu_config;
    ocu_config.subsystem = kOcu.subsystem;
    ocu_config.node = kOcu.node;
    ocu = std::make_unique<node::Node>(ocu_config, time, time, ocu_link);
    ocu_link.deliver_to(*ocu);
  }
  ~MetricsTest() override { vehicle->stop("test over"); }

  void send_acknowledged(const Address& to, std::uint16_t code) {
    Header h;
    h.command_code = code;
    h.source = kOcu;
    h.destination = to;
    ocu->send_acknowledged(h, {}, node::AckPolicy{50ms, 4}, {});
  }

  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time, 5ms};
  testing::MemoryLink& vehicle_link = network.attach(1, 1);
  testing::MemoryLink& ocu_link = network.attach(2, 1);
  std::unique_ptr<host::NodeHost> vehicle;
  std::unique_ptr<node::Node> ocu;
};

TEST_F(MetricsTest, EachPeerSaysWhatWasExchangedAndTheRoundTripMeasured) {
  send_acknowledged(kDriver, msg::Resume::code);                   // ACKed
  send_acknowledged(Address{1, 1, 99, 1}, msg::Resume::code);      // no such component: NAKed
  time.advance(100ms);
  vehicle_link.set_connected(false);
  send_acknowledged(kDriver, msg::Standby::code);                  // lost, 4 times
  time.advance(1s);
  vehicle_link.set_connected(true);

  const auto samples = parse_exposition(host::metrics_text(host::MetricsSources{ocu.get(), nullptr, nullptr}));
  EXPECT_EQ(samples.at(R"(jaus_peer_ack_requests_total{peer="1.1",outcome="acknowledged"})"), 1);
  EXPECT_EQ(samples.at(R"(jaus_peer_ack_requests_total{peer="1.1",outcome="refused"})"), 1);
  EXPECT_EQ(samples.at(R"(jaus_peer_ack_requests_total{peer="1.1",outcome="unacknowledged"})"), 1);
  EXPECT_EQ(samples.at(R"(jaus_peer_retransmissions_total{peer="1.1"})"), 3);
  EXPECT_EQ(samples.at(R"(jaus_peer_packets_sent_total{peer="1.1"})"), 6);
  EXPECT_EQ(samples.at(R"(jaus_node_ack_requests_total{outcome="acknowledged"})"), 1);
  // 5 ms each way, measured from the first ACK (the NAK's message went once too).
  EXPECT_NEAR(samples.at(R"(jaus_peer_round_trip_seconds{peer="1.1"})"), 0.010, 0.001);
  EXPECT_GT(samples.at(R"(jaus_peer_retransmission_timeout_seconds{peer="1.1"})"), 0);
}

TEST_F(MetricsTest, TheVehicleSaysItsComponentsStatesAndWhatItFiltered) {
  // A Resume whose ACKs are all lost: sent 4 times, acted on once.
  ocu_link.set_loss(0, 1, 1);
  send_acknowledged(kDriver, msg::Resume::code);
  time.advance(1s);
  const auto samples = parse_exposition(host::metrics_text(*vehicle));
  EXPECT_EQ(samples.at(R"(jaus_peer_packets_received_total{peer="2.1"})"), 4);
  EXPECT_EQ(samples.at(R"(jaus_peer_duplicates_total{peer="2.1"})"), 3);
  EXPECT_EQ(samples.at(R"(jaus_node_duplicates_filtered_total)"), 3);
  EXPECT_EQ(samples.at(R"(jaus_node_acks_sent_total{answer="ack"})"), 4);
  EXPECT_EQ(samples.at(R"(jaus_component_primary_status{component="1.1.33.1",name="primitive driver"})"),
            static_cast<double>(msg::PrimaryStatus::ready));
  // The copy delivered (the only one) refused: the OCU does not control the driver.
  EXPECT_EQ(samples.at(R"(jaus_component_refused_total{component="1.1.33.1",name="primitive driver",)"
                       R"(reason="not_controller"})"),
            1);
  EXPECT_GE(samples.at(R"(jaus_component_messages_received_total{component="1.1.33.1",name="primitive driver"})"), 1);
  EXPECT_FALSE(samples.contains("jaus_send_budget_bits_per_second")) << "no budget, no budget metrics";
  EXPECT_FALSE(samples.contains("jaus_transport_datagrams_received_total")) << "no UDP link";
}

TEST(MetricsText, LabelValuesAreEscaped) {
  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time};
  auto& link = network.attach(1, 1);
  host::HostConfig config;
  config.components = {host::ComponentSpec{"primitive_driver", 33, 1, 0, "the \"front\" \\ driver", {}, 0, {}}};
  auto attached = host::NodeHost::attach(config, link, time, time, {});
  ASSERT_TRUE(attached) << attached.error().message();
  const auto samples = parse_exposition(host::metrics_text(**attached));
  EXPECT_TRUE(samples.contains(
      R"(jaus_component_primary_status{component="1.1.33.1",name="the \"front\" \\ driver"})"));
  (*attached)->stop("test over");
}

// An HTTP exchange with the server, on its own connection.
struct Reply {
  unsigned status = 0;
  std::string body;
  std::string content_type;
};
Reply http_request(std::uint16_t port, boost::beast::http::verb method, const std::string& target,
                   const std::string& authorization = "") {
  namespace http = boost::beast::http;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address_v4("127.0.0.1"), port});
  http::request<http::empty_body> request(method, target, 11);
  request.set(http::field::host, "127.0.0.1");
  if (!authorization.empty()) request.set(http::field::authorization, authorization);
  http::write(socket, request);
  boost::beast::flat_buffer buffer;
  http::response<http::string_body> response;
  boost::beast::error_code ec;
  http::read(socket, buffer, response, ec);
  return {response.result_int(), response.body(), std::string(response[http::field::content_type])};
}

class MetricsServerTest : public ::testing::Test {
 protected:
  void start(std::string token) {
    host::MetricsServerOptions options;
    options.listen = {0x7F000001, 0};
    options.token = std::move(token);
    auto started = host::MetricsServer::start(io, options, [] { return std::string("jaus_test_total 7\n"); });
    ASSERT_TRUE(started) << started.error().message();
    server = std::move(*started);
    runner = std::thread([this] { io.run(); });
  }
  ~MetricsServerTest() override {
    io.stop();
    if (runner.joinable()) runner.join();
  }

  boost::asio::io_context io;
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work{io.get_executor()};
  std::unique_ptr<host::MetricsServer> server;
  std::thread runner;
};

TEST_F(MetricsServerTest, GetMetricsIsTheTextAndNothingElseIsServed) {
  start("");
  namespace http = boost::beast::http;
  const auto ok = http_request(server->port(), http::verb::get, "/metrics");
  EXPECT_EQ(ok.status, 200u);
  EXPECT_EQ(ok.body, "jaus_test_total 7\n");
  EXPECT_EQ(ok.content_type, "text/plain; version=0.0.4; charset=utf-8");
  const auto head = http_request(server->port(), http::verb::head, "/metrics");
  EXPECT_EQ(head.status, 200u);
  EXPECT_EQ(http_request(server->port(), http::verb::get, "/").status, 404u);
  EXPECT_EQ(http_request(server->port(), http::verb::post, "/metrics").status, 405u);
}

TEST_F(MetricsServerTest, WithATokenOnlyAScrapeThatGivesItIsServed) {
  start("s3cret");
  namespace http = boost::beast::http;
  EXPECT_EQ(http_request(server->port(), http::verb::get, "/metrics").status, 401u);
  EXPECT_EQ(http_request(server->port(), http::verb::get, "/metrics", "Bearer wrong").status, 401u);
  EXPECT_EQ(http_request(server->port(), http::verb::get, "/metrics", "Bearer s3cret").body, "jaus_test_total 7\n");
  EXPECT_EQ(http_request(server->port(), http::verb::get, "/metrics?token=s3cret").status, 200u);
}

TEST(MetricsServerStart, BeyondLoopbackATokenIsNeeded) {
  boost::asio::io_context io;
  host::MetricsServerOptions options;
  options.listen = {0, 0};  // every address
  const auto started = host::MetricsServer::start(io, options, [] { return std::string(); });
  ASSERT_FALSE(started);
  EXPECT_EQ(started.error().message(), "metrics on 0.0.0.0:0 need a token (only loopback may go without one)");
}

}  // namespace
}  // namespace jaus::test
