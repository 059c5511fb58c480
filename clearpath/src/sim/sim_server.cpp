#include "jaus/clearpath/sim/sim_server.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cstdlib>

namespace jaus::clearpath::sim {

namespace asio = boost::asio;
using boost::system::error_code;

namespace {
constexpr auto kTickPeriod = std::chrono::milliseconds(5);
}

SimServer::SimServer(asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler, ServerEndpoint endpoint,
                     PlatformConfig platform, FaultConfig faults)
    : clock_(clock), scheduler_(scheduler), endpoint_(std::move(endpoint)), platform_(std::move(platform), clock.now()),
      faults_(faults), udp_(io), serial_(io), pty_master_(io), started_(clock.now()) {}

SimServer::~SimServer() {
  *alive_ = false;
  stop();
}

Expected<void> SimServer::start() {
  const auto fail = [](std::string why) { return unexpected(make_error(ErrorCode::io, std::move(why))); };
  error_code ec;
  switch (endpoint_.kind) {
    case ServerEndpoint::Kind::udp: {
      const auto address = asio::ip::make_address(endpoint_.host, ec);
      if (ec) return fail("bad address " + endpoint_.host + ": " + ec.message());
      udp_.open(address.is_v4() ? asio::ip::udp::v4() : asio::ip::udp::v6(), ec);
      if (!ec) udp_.set_option(asio::socket_base::reuse_address(true), ec);
      if (!ec) udp_.bind({address, endpoint_.port}, ec);
      if (ec) return fail("cannot bind " + endpoint_.host + ":" + std::to_string(endpoint_.port) + ": " + ec.message());
      bound_port_ = udp_.local_endpoint().port();
      break;
    }
    case ServerEndpoint::Kind::serial:
      serial_.open(endpoint_.device, ec);
      if (!ec) serial_.set_option(asio::serial_port_base::baud_rate(endpoint_.baud), ec);
      if (ec) return fail("cannot open " + endpoint_.device + ": " + ec.message());
      break;
    case ServerEndpoint::Kind::pty: {
      const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
      if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return fail("cannot open a PTY");
      const char* name = ::ptsname(master);
      if (name == nullptr) return fail("cannot name the PTY");
      pty_path_ = name;
      pty_slave_fd_ = ::open(name, O_RDWR | O_NOCTTY);
      if (pty_slave_fd_ < 0) return fail("cannot open " + pty_path_);
      termios raw{};
      ::tcgetattr(pty_slave_fd_, &raw);
      ::cfmakeraw(&raw);
      ::cfsetspeed(&raw, B115200);
      ::tcsetattr(pty_slave_fd_, TCSANOW, &raw);
      pty_master_.assign(master);
      break;
    }
  }
  running_ = true;
  start_read();
  on_tick();
  return {};
}

void SimServer::stop() {
  running_ = false;
  error_code ignored;
  scheduler_.cancel(tick_);
  tick_ = rt::kNoTimer;
  if (udp_.is_open()) udp_.close(ignored);
  if (serial_.is_open()) serial_.close(ignored);
  if (pty_master_.is_open()) pty_master_.close(ignored);
  if (pty_slave_fd_ >= 0) {
    ::close(pty_slave_fd_);
    pty_slave_fd_ = -1;
  }
  tx_queue_.clear();
}

bool SimServer::disconnected(rt::TimePoint now) const {
  const auto& f = faults_.config();
  if (f.disconnect_every.count() <= 0) return false;
  const auto cycle = f.disconnect_every + f.disconnect_for;
  const auto phase = (now - started_) % cycle;
  return phase >= f.disconnect_every;  // the last disconnect_for of every cycle
}

bool SimServer::deaf() const {
  if (deaf_set_) return *deaf_set_;
  const auto after = faults_.config().deaf_after;
  return after.count() > 0 && clock_.now() - started_ >= after;
}

void SimServer::start_read() {
  if (!running_) return;
  auto alive = alive_;
  auto handler = [this, alive](const error_code& ec, std::size_t n) {
    if (!*alive || !running_) return;
    if (!ec) {
      handle_input(std::span(rx_.data(), n));
    } else if (ec == asio::error::operation_aborted) {
      return;
    }
    // Other errors (ICMP refusals on UDP, EIO on a PTY) are transient: keep reading.
    start_read();
  };
  switch (endpoint_.kind) {
    case ServerEndpoint::Kind::udp: udp_.async_receive_from(asio::buffer(rx_), sender_, handler); break;
    case ServerEndpoint::Kind::serial: serial_.async_read_some(asio::buffer(rx_), handler); break;
    case ServerEndpoint::Kind::pty: pty_master_.async_read_some(asio::buffer(rx_), handler); break;
  }
}

void SimServer::handle_input(std::span<std::uint8_t> bytes) {
  const auto now = clock_.now();
  if (disconnected(now)) return;  // a pulled cable: input is lost
  // The peer is where the data goes, as on a serial line that still carries it.
  if (endpoint_.kind == ServerEndpoint::Kind::udp) peer_ = sender_;
  if (deaf()) return;  // a one-way line: heard nothing, so no ACK and no action; data still goes (on_tick)
  faults_.maybe_corrupt(bytes);
  emit(platform_.receive(bytes, now));
}

void SimServer::emit(const std::vector<std::uint8_t>& frames) {
  // One datagram per frame on UDP, and faults apply per frame.
  for (const auto frame : split_frames(frames)) send_frame({frame.begin(), frame.end()});
}

void SimServer::send_frame(std::vector<std::uint8_t> frame) {
  if (faults_.drop()) return;
  faults_.maybe_corrupt(frame);
  const auto latency = faults_.config().latency;
  if (latency.count() <= 0) return write_now(std::move(frame));
  // Not cancelled by stop(): the callback checks alive_ and running_ instead.
  scheduler_.call_at(clock_.now() + latency, [this, alive = alive_, f = std::move(frame)]() mutable {
    if (*alive && running_) write_now(std::move(f));
  });
}

void SimServer::write_now(std::vector<std::uint8_t> frame) {
  if (!running_ || disconnected(clock_.now())) return;
  if (endpoint_.kind == ServerEndpoint::Kind::udp) {
    if (!peer_) return;
    auto data = std::make_shared<std::vector<std::uint8_t>>(std::move(frame));
    udp_.async_send_to(asio::buffer(*data), *peer_, [data](const error_code&, std::size_t) {});
    return;
  }
  tx_queue_.push_back(std::move(frame));
  pump_stream();
}

void SimServer::pump_stream() {
  if (writing_ || tx_queue_.empty() || !running_) return;
  writing_ = true;
  auto alive = alive_;
  auto handler = [this, alive](const error_code&, std::size_t) {
    if (!*alive) return;
    writing_ = false;
    if (!tx_queue_.empty()) tx_queue_.pop_front();
    pump_stream();
  };
  if (endpoint_.kind == ServerEndpoint::Kind::serial) asio::async_write(serial_, asio::buffer(tx_queue_.front()), handler);
  else asio::async_write(pty_master_, asio::buffer(tx_queue_.front()), handler);
}

void SimServer::on_tick() {
  if (!running_) return;
  const auto now = clock_.now();
  auto out = platform_.tick(now);
  if (!disconnected(now)) emit(std::move(out));
  tick_ = scheduler_.call_at(now + kTickPeriod, [this, alive = alive_] {
    if (*alive) on_tick();
  });
}

}  // namespace jaus::clearpath::sim
