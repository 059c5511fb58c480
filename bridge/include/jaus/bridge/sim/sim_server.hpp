// Boost.Asio shell of the simulated platform: serves SimPlatform over UDP,
// a serial device or a PTY it opens itself, with optional fault injection.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

#include "jaus/bridge/sim/fault_injector.hpp"
#include "jaus/bridge/sim/sim_platform.hpp"

namespace jaus::bridge::sim {

struct ServerEndpoint {
  enum class Kind { udp, serial, pty } kind = Kind::udp;
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;  // 0: any free port (see udp_port())
  std::string device;
  unsigned baud = 115200;
};

class SimServer {
 public:
  SimServer(boost::asio::io_context& io, ServerEndpoint endpoint, PlatformConfig platform, FaultConfig faults = {});
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Opens the endpoint; returns an error text on failure.
  std::optional<std::string> start();
  void stop();

  const std::string& pty_path() const { return pty_path_; }
  std::uint16_t udp_port() const { return bound_port_; }
  const SimPlatform& platform() const { return platform_; }

 private:
  void start_read();
  void handle_input(std::span<std::uint8_t> bytes);
  void emit(std::vector<std::uint8_t> bytes);
  void send_frame(std::vector<std::uint8_t> frame);
  void write_now(std::vector<std::uint8_t> frame);
  void pump_stream();
  void on_tick();
  bool disconnected(Clock::time_point now) const;

  boost::asio::io_context& io_;
  ServerEndpoint endpoint_;
  SimPlatform platform_;
  FaultInjector faults_;
  boost::asio::ip::udp::socket udp_;
  boost::asio::serial_port serial_;
  boost::asio::posix::stream_descriptor pty_master_;
  int pty_slave_fd_ = -1;  // kept open so the master never sees a hang-up
  std::string pty_path_;
  std::uint16_t bound_port_ = 0;
  std::optional<boost::asio::ip::udp::endpoint> peer_;
  boost::asio::ip::udp::endpoint sender_;
  boost::asio::steady_timer tick_;
  std::array<std::uint8_t, 2048> rx_{};
  std::deque<std::vector<std::uint8_t>> tx_queue_;
  bool writing_ = false;
  bool running_ = false;
  Clock::time_point started_;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace jaus::bridge::sim
