// jaus-console's web server on loopback (real sockets: the socket is what is
// tested): the page served, the WebSocket's token, Origin and Host checks,
// its limits, and a round trip of frames.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <mutex>
#include <thread>

#include "jaus/console/panels/panel.hpp"  // kEveryPage
#include "jaus/console/web_assets.hpp"
#include "jaus/console/web_server.hpp"

namespace jaus::console {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;

// A server on its own thread that echoes every frame back to its page.
class EchoServer {
 public:
  explicit EchoServer(WebServerOptions options) {
    options.listen = {0x7F000001, 0};
    auto started = WebServer::start(
        io_, options,
        PageEvents{[this](PageId page) {
                     record("opened " + std::to_string(page));
                     // Several frames at once, as the console's welcome does.
                     server_->send(page, "hello " + std::to_string(page));
                     server_->send(kEveryPage, "tree");
                   },
                   [this](PageId page) { record("closed " + std::to_string(page)); },
                   [this](PageId page, std::string_view text) { server_->send(page, "echo:" + std::string(text)); }});
    if (!started) throw std::runtime_error(started.error().message());
    server_ = std::move(*started);
    thread_ = std::thread([this] { io_.run(); });
  }
  ~EchoServer() {
    io_.stop();
    thread_.join();
    server_.reset();
  }
  std::uint16_t port() const { return server_->port(); }
  std::string host() const { return "127.0.0.1:" + std::to_string(port()); }
  bool saw(const std::string& event) {
    for (auto until = std::chrono::steady_clock::now() + 3s; std::chrono::steady_clock::now() < until;) {
      {
        std::lock_guard lock(mutex_);
        for (const auto& e : events_)
          if (e == event) return true;
      }
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }

 private:
  void record(std::string event) {
    std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
  }
  asio::io_context io_;
  std::unique_ptr<WebServer> server_;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<std::string> events_;
};

struct Reply {
  unsigned status = 0;
  std::string content_type;
  std::string body;
};

Reply http_request(std::uint16_t port, http::verb method, const std::string& target) {
  asio::io_context io;
  tcp::socket socket(io);
  socket.connect(tcp::endpoint(asio::ip::address_v4::loopback(), port));
  http::request<http::string_body> request(method, target, 11);
  request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  http::write(socket, request);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(socket, buffer, response);
  return {response.result_int(), std::string(response[http::field::content_type]), response.body()};
}

// A WebSocket client; `error` says whether the handshake failed.
struct Client {
  Client(std::uint16_t port, const std::string& target, const std::string& origin = "", std::string host = "")
      : ws(io) {
    beast::error_code ec;
    ws.next_layer().connect(tcp::endpoint(asio::ip::address_v4::loopback(), port), ec);
    if (!ec) {
      ws.set_option(websocket::stream_base::decorator([origin](websocket::request_type& r) {
        if (!origin.empty()) r.set(http::field::origin, origin);
      }));
      ws.handshake(response, host.empty() ? "127.0.0.1:" + std::to_string(port) : host, target, ec);
    }
    error = ec;
  }
  std::string read() {
    beast::flat_buffer buffer;
    ws.read(buffer);
    return beast::buffers_to_string(buffer.data());
  }
  // Reads the greeting first (hello, tree), then sends `text` and reads the answer.
  std::string round_trip(const std::string& text) {
    if (!greeted) {
      const std::string first = read();  // its own statement: the operands of + may be read in either order
      greeting = first + "|" + read();
      greeted = true;
    }
    ws.text(true);
    ws.write(asio::buffer(text));
    return read();
  }
  bool greeted = false;
  std::string greeting;
  asio::io_context io;
  websocket::stream<tcp::socket> ws;
  websocket::response_type response;
  beast::error_code error;
};

TEST(WebServer, ServesThePageAndNothingElse) {
  EchoServer server({});
  const auto page = http_request(server.port(), http::verb::get, "/");
  EXPECT_EQ(page.status, 200u);
  EXPECT_EQ(page.content_type, "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("<html"), std::string::npos);
  const auto asset = web_assets();
  ASSERT_FALSE(asset.empty());
  for (const auto& a : asset) EXPECT_EQ(http_request(server.port(), http::verb::get, std::string(a.path)).status, 200u);
  EXPECT_EQ(http_request(server.port(), http::verb::get, "/etc/passwd").status, 404u);
  EXPECT_EQ(http_request(server.port(), http::verb::post, "/").status, 405u);
}

TEST(WebServer, WebSocketRoundTripAndCloseIsReported) {
  EchoServer server({});
  {
    Client client(server.port(), "/ws");
    ASSERT_FALSE(client.error) << client.error.message();
    EXPECT_TRUE(server.saw("opened 1"));
    EXPECT_EQ(client.round_trip(R"({"type":"drive"})"), R"(echo:{"type":"drive"})");
    EXPECT_EQ(client.greeting, "hello 1|tree") << "frames sent together arrive in order";
    client.ws.close(websocket::close_code::normal);
  }
  EXPECT_TRUE(server.saw("closed 1"));
}

TEST(WebServer, TokenIsRefusedWhenWrongOrMissingAndAcceptedWhenRight) {
  WebServerOptions options;
  options.token = "s3cret";
  EchoServer server(options);
  EXPECT_TRUE(Client(server.port(), "/ws").error);
  Client wrong(server.port(), "/ws?token=guess");
  EXPECT_TRUE(wrong.error);
  EXPECT_EQ(wrong.error, websocket::error::upgrade_declined) << "answered, not upgraded";
  Client right(server.port(), "/ws?token=s3cret");
  ASSERT_FALSE(right.error) << right.error.message();
  EXPECT_EQ(right.round_trip("x"), "echo:x");
}

TEST(WebServer, OriginOfAnotherSiteIsRefused) {
  EchoServer server({});
  Client evil(server.port(), "/ws", "http://evil.example");
  EXPECT_TRUE(evil.error);
  EXPECT_EQ(evil.error, websocket::error::upgrade_declined);
  Client own(server.port(), "/ws", "http://" + server.host());
  EXPECT_FALSE(own.error) << own.error.message();
}

TEST(WebServer, AForeignHostNameOnLoopbackIsRefused) {
  EchoServer server({});
  const std::string rebound = "evil.example:" + std::to_string(server.port());
  Client client(server.port(), "/ws", "http://" + rebound, rebound);
  EXPECT_TRUE(client.error);
}

TEST(WebServer, PagesBeyondTheLimitAreRefused) {
  WebServerOptions options;
  options.max_pages = 1;
  EchoServer server(options);
  Client first(server.port(), "/ws");
  ASSERT_FALSE(first.error);
  Client second(server.port(), "/ws");
  EXPECT_TRUE(second.error);
  EXPECT_EQ(second.error, websocket::error::upgrade_declined);
}

TEST(WebServer, AFrameOverTheLimitClosesThePage) {
  WebServerOptions options;
  options.max_frame_bytes = 1024;
  EchoServer server(options);
  Client client(server.port(), "/ws");
  ASSERT_FALSE(client.error);
  client.ws.write(asio::buffer(std::string(4096, 'x')));
  beast::error_code ec;
  for (int i = 0; i < 3 && !ec; ++i) {  // the greeting first, then the close
    beast::flat_buffer buffer;
    client.ws.read(buffer, ec);
  }
  EXPECT_TRUE(ec);
  EXPECT_TRUE(server.saw("closed 1"));
}

TEST(WebServer, BeyondLoopbackNeedsAToken) {
  asio::io_context io;
  WebServerOptions options;
  options.listen = {0, 0};
  auto started = WebServer::start(io, options, {});
  ASSERT_FALSE(started);
  EXPECT_EQ(started.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(generate_token().size(), 32u);
  EXPECT_NE(generate_token(), generate_token());
}

TEST(WebServer, UpgradeChecks) {
  WebServerOptions loopback;
  EXPECT_TRUE(check_upgrade(loopback, 8080, {"/ws", "127.0.0.1:8080", ""}));
  EXPECT_TRUE(check_upgrade(loopback, 8080, {"/ws", "localhost:8080", "http://localhost:8080"}));
  EXPECT_FALSE(check_upgrade(loopback, 8080, {"/other", "127.0.0.1:8080", ""}));
  EXPECT_FALSE(check_upgrade(loopback, 8080, {"/ws", "127.0.0.1:8080", "http://localhost:8080"}));
  WebServerOptions open;
  open.listen = {0, 8080};
  open.token = "t";
  EXPECT_TRUE(check_upgrade(open, 8080, {"/ws?token=t", "robot.lan:8080", "http://robot.lan:8080"}));
  EXPECT_FALSE(check_upgrade(open, 8080, {"/ws?token=u", "robot.lan:8080", "http://robot.lan:8080"}));
  EXPECT_FALSE(check_upgrade(open, 8080, {"/ws?token=t", "robot.lan:8080", "http://evil.example"}));
}

}  // namespace
}  // namespace jaus::console
