// jaus-console's HTTP and WebSocket server (Boost.Beast) on the session's
// io_context: GET / and the page's files (embedded, web_assets.hpp), and
// GET /ws, the page's WebSocket (docs/console.md, "Protocol"). One text
// frame in is one page frame; what the console says goes out as text frames.
//
// Security (docs/console.md, "Security"): it listens on loopback unless told
// otherwise, and beyond loopback only with a token. With a token, the
// WebSocket needs `?token=` equal to it. The WebSocket's Origin, when the
// browser sends one, must be the page's own (http://HOST:PORT, HOST the
// request's Host), and on loopback HOST must be a loopback name: another
// site's page in the operator's browser cannot drive the vehicle. Frames
// over max_frame_bytes and pages over max_pages are refused; a page that
// reads too slowly (max_queued_bytes waiting) is closed.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "jaus/base/expected.hpp"
#include "jaus/base/log.hpp"
#include "jaus/console/console_protocol.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::console {

inline constexpr std::uint16_t kDefaultConsolePort = 8080;

struct WebServerOptions {
  jaus::transport::Ipv4Endpoint listen{0x7F000001, kDefaultConsolePort};  // port 0: any free port
  std::string token;  // empty: none asked (loopback only)
  std::size_t max_pages = 8;
  std::size_t max_frame_bytes = 64 * 1024;
  std::size_t max_queued_bytes = 16 * 1024 * 1024;
  jaus::rt::LogFn log;
};

// What the server tells the console.
struct PageEvents {
  std::function<void(PageId)> opened;
  std::function<void(PageId)> closed;
  std::function<void(PageId, std::string_view)> frame;
};

// A token for --token: 128 random bits as hex.
std::string generate_token();
// Whether `address` (IPv4, host order) is 127.0.0.0/8.
bool is_loopback(std::uint32_t address);

// Whether a WebSocket upgrade may be accepted: the token (when one is set)
// and the Origin. The error says why not, for the 403 and the log.
struct UpgradeRequest {
  std::string_view target;  // "/ws?token=..."
  std::string_view host;    // the Host header
  std::string_view origin;  // the Origin header, empty when absent
};
jaus::Expected<void> check_upgrade(const WebServerOptions& options, std::uint16_t bound_port,
                                   const UpgradeRequest& request);

class WebServer {
 public:
  // Binds and listens. Errors: io (the address in use, ...), invalid_argument
  // (beyond loopback without a token).
  static jaus::Expected<std::unique_ptr<WebServer>> start(boost::asio::io_context& io, WebServerOptions options,
                                                          PageEvents events);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // The port bound (the options' or, for 0, the one chosen).
  std::uint16_t port() const;
  std::size_t page_count() const;
  // A text frame to one page, or to every page (kEveryPage = 0).
  void send(PageId to, const std::string& frame);
  // Stops accepting and closes every page (each reported closed).
  void stop();

  struct Impl;

 private:
  explicit WebServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace jaus::console
