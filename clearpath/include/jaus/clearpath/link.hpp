// The Clearpath link over Boost.Asio: serial port (115200 8N1 by default),
// UDP or TCP (frames verbatim, one per datagram). A thin shell around
// ClientCore: it moves bytes and reopens the port with backoff when it is
// missing or fails; it never ends the process. Time comes from the runtime's
// Clock and Scheduler (transport::AsioRuntime on the same io_context in a
// node), so the link ticks on the node's one thread like every component.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/clearpath/client.hpp"

namespace jaus::clearpath {

struct PlatformEndpoint {
  enum class Kind { serial, udp, tcp } kind = Kind::serial;
  std::string device = "/dev/ttyUSB0";  // serial
  unsigned baud = 115200;
  std::string host = "127.0.0.1";  // udp / tcp
  std::uint16_t port = 0;
};

// "serial:/dev/ttyS0[@115200]", "udp:HOST:PORT", "tcp:HOST:PORT"; an
// invalid_argument error says what is wrong with the text.
Expected<PlatformEndpoint> parse_platform_endpoint(const std::string& text);

class ClearpathLink final : public Client {
 public:
  ClearpathLink(boost::asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler, PlatformEndpoint endpoint,
                ClientConfig config = {});
  ~ClearpathLink() override;
  ClearpathLink(const ClearpathLink&) = delete;
  ClearpathLink& operator=(const ClearpathLink&) = delete;

  void start();
  void stop();
  // Safety: writes at once, synchronously, every frame the client has to send
  // now (a stop's zero setpoint first), for a process that is about to exit
  // and will not run the io_context again. A frame the link left half written
  // (kernel buffer full) is finished first, so frames never interleave; a
  // full buffer is waited for up to a second in all. Errors are ignored: the
  // platform's watchdog is the last line.
  void flush();

  // Client: on the io_context's thread, like every runtime callback.
  void send(AnyMessage message, ClientCore::CommandCallback done = {}) override;
  void subscribe(AnyMessage request, ClientCore::CommandCallback done = {}) override;
  void set_setpoint(AnyMessage command) override;
  void clear_setpoint(std::uint16_t type) override;
  void stop_setpoint(AnyMessage stop) override;
  void on_data(ClientCore::DataCallback callback) override { core_.on_data(std::move(callback)); }
  void on_state(ClientCore::StateCallback callback) override { core_.on_state(std::move(callback)); }
  void on_problem(ClientCore::ProblemCallback callback) override { core_.on_problem(std::move(callback)); }
  ConnectionState state() const override { return core_.state(); }
  const ClientCounters& counters() const override { return core_.counters(); }
  const std::string& down_reason() const override { return core_.down_reason(); }

  // Called after each frame has been written, with the frame.
  void on_written(std::function<void(std::span<const std::uint8_t> frame)> callback) { on_written_ = std::move(callback); }
  const ClientCore& core() const { return core_; }

 private:
  void open();
  void close();
  void start_read();
  void pump();
  int native_handle();
  void on_tick();
  void fail(const boost::system::error_code& ec);

  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  PlatformEndpoint endpoint_;
  ClientCore core_;
  boost::asio::serial_port serial_;
  boost::asio::ip::udp::socket udp_;
  boost::asio::ip::tcp::socket tcp_;
  rt::TimerId tick_ = rt::kNoTimer;
  std::array<std::uint8_t, 2048> rx_{};
  std::vector<std::uint8_t> tx_;  // the frame being written
  std::size_t tx_sent_ = 0;       // of tx_, written so far
  bool writing_ = false;          // in pump(): a callback's send() joins its loop
  bool open_ = false;
  bool running_ = false;
  std::uint64_t generation_ = 0;  // handlers of a closed connection are ignored
  std::function<void(std::span<const std::uint8_t>)> on_written_;
  // Aborted handlers may run after destruction: they check this first.
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace jaus::clearpath
