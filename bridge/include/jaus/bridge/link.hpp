// The Clearpath link over Boost.Asio: serial port (115200 8N1 by default),
// UDP or TCP (frames verbatim, one per datagram). A thin shell around
// ClientCore: it moves bytes, keeps time and reopens the port with backoff
// when it is missing or fails; it never ends the process.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

#include "jaus/bridge/client_core.hpp"

namespace jaus::bridge {

struct LinkEndpoint {
  enum class Kind { serial, udp, tcp } kind = Kind::serial;
  std::string device = "/dev/ttyUSB0";  // serial
  unsigned baud = 115200;
  std::string host = "127.0.0.1";  // udp / tcp
  std::uint16_t port = 0;
};

// "serial:/dev/ttyS0[@115200]", "udp:HOST:PORT", "tcp:HOST:PORT".
std::optional<LinkEndpoint> parse_endpoint(const std::string& text);

class ClearpathLink {
 public:
  ClearpathLink(boost::asio::io_context& io, LinkEndpoint endpoint, ClientConfig config = {});
  ~ClearpathLink();
  ClearpathLink(const ClearpathLink&) = delete;
  ClearpathLink& operator=(const ClearpathLink&) = delete;

  void start();
  void stop();

  // Thread-safe: each posts onto the link's io_context.
  void send(Message message, ClientCore::CommandCallback done = {});
  void subscribe(Message request, ClientCore::CommandCallback done = {});
  void set_setpoint(Message command);
  void on_data(ClientCore::DataCallback callback);
  // Called (on the io thread) after each frame has been written.
  void on_written(std::function<void(std::size_t bytes)> callback) { on_written_ = std::move(callback); }

  // Read on the io thread (or after stop()).
  const ClientCore& core() const { return core_; }

 private:
  void open();
  void close();
  void start_read();
  void pump();
  void on_tick();
  void fail(const boost::system::error_code& ec);

  boost::asio::io_context& io_;
  LinkEndpoint endpoint_;
  ClientCore core_;
  boost::asio::serial_port serial_;
  boost::asio::ip::udp::socket udp_;
  boost::asio::ip::tcp::socket tcp_;
  boost::asio::steady_timer tick_;
  std::array<std::uint8_t, 2048> rx_{};
  std::vector<std::uint8_t> tx_;
  bool writing_ = false;
  bool open_ = false;
  bool running_ = false;
  std::uint64_t generation_ = 0;  // handlers of a closed connection are ignored
  std::function<void(std::size_t)> on_written_;
  // Aborted handlers may run after destruction: they check this first.
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace jaus::bridge
