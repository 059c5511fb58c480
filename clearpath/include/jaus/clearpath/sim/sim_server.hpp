// Boost.Asio shell of the simulated platform: serves SimPlatform over UDP,
// a serial device or a PTY it opens itself, with optional fault injection.
// Time comes from the runtime's Clock and Scheduler (transport::AsioRuntime
// on the same io_context), like everything else that keeps time.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/clearpath/sim/fault_injector.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"

namespace jaus::clearpath::sim {

struct ServerEndpoint {
  enum class Kind { udp, serial, pty } kind = Kind::udp;
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;  // 0: any free port (see udp_port())
  std::string device;
  unsigned baud = 115200;
};

class SimServer {
 public:
  SimServer(boost::asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler, ServerEndpoint endpoint,
            PlatformConfig platform, FaultConfig faults = {});
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Opens the endpoint; an io error says which and why.
  Expected<void> start();
  void stop();

  const std::string& pty_path() const { return pty_path_; }
  std::uint16_t udp_port() const { return bound_port_; }
  const SimPlatform& platform() const { return platform_; }
  // The platform's physical e-stop button or pause input, now.
  void press(HardwareInput input, bool on) { platform_.press(input, on, clock_.now()); }
  // The platform's events (SimPlatform::on_event), each with the clock's time.
  void on_event(std::function<void(const PlatformEvent&)> callback) { platform_.on_event(std::move(callback)); }
  // A one-way line, now: deaf (on) the platform ignores every frame it
  // receives and keeps sending its data; off it hears again. Either ends
  // FaultConfig::deaf_after's rule (it no longer applies).
  void set_deaf(bool on) { deaf_set_ = on; }
  bool deaf() const;

 private:
  void start_read();
  void handle_input(std::span<std::uint8_t> bytes);
  void emit(const std::vector<std::uint8_t>& frames);
  void send_frame(std::vector<std::uint8_t> frame);
  void write_now(std::vector<std::uint8_t> frame);
  void pump_stream();
  void on_tick();
  bool disconnected(rt::TimePoint now) const;

  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
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
  rt::TimerId tick_ = rt::kNoTimer;
  std::array<std::uint8_t, 2048> rx_{};
  std::deque<std::vector<std::uint8_t>> tx_queue_;
  bool writing_ = false;
  bool running_ = false;
  rt::TimePoint started_;
  std::optional<bool> deaf_set_;  // set_deaf(), which overrides deaf_after
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace jaus::clearpath::sim
