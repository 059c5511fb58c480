#include "jaus/clearpath/link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>

namespace jaus::clearpath {

namespace asio = boost::asio;
using boost::system::error_code;

namespace {
constexpr auto kTickPeriod = std::chrono::milliseconds(5);
// flush() waits this long at most for a full kernel buffer to drain: an exit
// must not hang on a peer that stopped reading.
constexpr auto kFlushLimit = std::chrono::seconds(1);

// One non-blocking write of `bytes` to `fd`: how many went (0: the kernel's
// buffer is full), or an error. A socket is written with MSG_NOSIGNAL, so a
// TCP peer that went away is an EPIPE error here, never a SIGPIPE.
std::size_t write_now(int fd, bool socket, std::span<const std::uint8_t> bytes, error_code& ec) {
  ec.clear();
  for (;;) {
    const auto n = socket ? ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) : ::write(fd, bytes.data(), bytes.size());
    if (n >= 0) return static_cast<std::size_t>(n);
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return 0;
    ec = error_code(errno, boost::system::system_category());
    return 0;
  }
}

void set_non_blocking(int fd, error_code& ec) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) ec = error_code(errno, boost::system::system_category());
}

Error bad_endpoint(const std::string& text, std::string_view why) {
  return make_error(ErrorCode::invalid_argument, "'" + text + "' is not a Clearpath endpoint (" + std::string(why) +
                                                     "; expected serial:DEVICE[@BAUD], udp:HOST:PORT or tcp:HOST:PORT)");
}

std::optional<std::uint16_t> parse_port(const std::string& s) {
  unsigned v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || v == 0 || v > 65535) return std::nullopt;
  return static_cast<std::uint16_t>(v);
}
}  // namespace

Expected<PlatformEndpoint> parse_platform_endpoint(const std::string& text) {
  PlatformEndpoint e;
  const auto colon = text.find(':');
  if (colon == std::string::npos) return unexpected(bad_endpoint(text, "no scheme"));
  const std::string scheme = text.substr(0, colon), rest = text.substr(colon + 1);
  if (scheme == "serial") {
    e.kind = PlatformEndpoint::Kind::serial;
    const auto at = rest.find('@');
    e.device = rest.substr(0, at);
    if (at != std::string::npos) {
      const auto baud = rest.substr(at + 1);
      const auto [end, ec] = std::from_chars(baud.data(), baud.data() + baud.size(), e.baud);
      if (ec != std::errc{} || end != baud.data() + baud.size() || e.baud == 0)
        return unexpected(bad_endpoint(text, "bad baud rate"));
    }
    if (e.device.empty()) return unexpected(bad_endpoint(text, "no device"));
    return e;
  }
  if (scheme != "udp" && scheme != "tcp") return unexpected(bad_endpoint(text, "unknown scheme"));
  e.kind = scheme == "udp" ? PlatformEndpoint::Kind::udp : PlatformEndpoint::Kind::tcp;
  const auto last = rest.rfind(':');
  if (last == std::string::npos) return unexpected(bad_endpoint(text, "no port"));
  e.host = rest.substr(0, last);
  const auto port = parse_port(rest.substr(last + 1));
  if (!port) return unexpected(bad_endpoint(text, "bad port"));
  if (e.host.empty()) return unexpected(bad_endpoint(text, "no host"));
  e.port = *port;
  return e;
}

ClearpathLink::ClearpathLink(asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler,
                             PlatformEndpoint endpoint, ClientConfig config)
    : clock_(clock), scheduler_(scheduler), endpoint_(std::move(endpoint)), core_(config), serial_(io), udp_(io),
      tcp_(io) {}

ClearpathLink::~ClearpathLink() {
  *alive_ = false;
  stop();
}

void ClearpathLink::start() {
  running_ = true;
  on_tick();
}

void ClearpathLink::stop() {
  running_ = false;
  scheduler_.cancel(tick_);
  tick_ = rt::kNoTimer;
  close();
}

void ClearpathLink::send(AnyMessage message, ClientCore::CommandCallback done) {
  core_.send(std::move(message), std::move(done));
  pump();
}

void ClearpathLink::subscribe(AnyMessage request, ClientCore::CommandCallback done) {
  core_.subscribe(std::move(request), std::move(done));
  pump();
}

void ClearpathLink::set_setpoint(AnyMessage command) {
  core_.set_setpoint(std::move(command), clock_.now());
  pump();
}

void ClearpathLink::stop_setpoint(AnyMessage stop) {
  core_.stop_setpoint(std::move(stop), clock_.now());
  pump();
}

void ClearpathLink::clear_setpoint(std::uint16_t type) { core_.clear_setpoint(type); }

void ClearpathLink::close() {
  ++generation_;
  open_ = false;
  // A frame half written stays half written on the old connection (a
  // platform's parser resynchronises); the next one starts afresh.
  tx_.clear();
  tx_sent_ = 0;
  error_code ignored;
  if (serial_.is_open()) serial_.close(ignored);
  if (udp_.is_open()) udp_.close(ignored);
  if (tcp_.is_open()) tcp_.close(ignored);
}

void ClearpathLink::fail(const error_code& ec) {
  if (ec == asio::error::operation_aborted) return;
  close();
  core_.on_disconnected(clock_.now());
}

void ClearpathLink::open() {
  close();
  const auto now = clock_.now();
  core_.reconnect_started(now);
  error_code ec;
  switch (endpoint_.kind) {
    case PlatformEndpoint::Kind::serial:
      serial_.open(endpoint_.device, ec);
      if (!ec) serial_.set_option(asio::serial_port_base::baud_rate(endpoint_.baud), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::character_size(8), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
      break;
    case PlatformEndpoint::Kind::udp: {
      const auto address = asio::ip::make_address(endpoint_.host, ec);
      if (ec) break;
      udp_.open(address.is_v4() ? asio::ip::udp::v4() : asio::ip::udp::v6(), ec);
      if (!ec) udp_.connect({address, endpoint_.port}, ec);
      break;
    }
    case PlatformEndpoint::Kind::tcp: {
      const auto address = asio::ip::make_address(endpoint_.host, ec);
      if (ec) break;
      // Asynchronous so a slow peer never blocks the io thread.
      const auto generation = generation_;
      tcp_.async_connect({address, endpoint_.port}, [this, alive = alive_, generation](const error_code& cec) {
        if (!*alive || generation != generation_) return;
        error_code nec = cec;
        if (!nec) set_non_blocking(native_handle(), nec);
        if (nec) {
          close();
          core_.open_failed(clock_.now());
          return;
        }
        open_ = true;
        core_.on_connected(clock_.now());
        start_read();
        pump();
      });
      return;
    }
  }
  if (!ec) set_non_blocking(native_handle(), ec);
  if (ec) {
    close();
    core_.open_failed(now);
    return;
  }
  open_ = true;
  core_.on_connected(now);
  start_read();
  pump();
}

void ClearpathLink::start_read() {
  const auto generation = generation_;
  auto handler = [this, alive = alive_, generation](const error_code& ec, std::size_t n) {
    if (!*alive || generation != generation_) return;
    if (ec) return fail(ec);
    core_.on_bytes(std::span(rx_.data(), n), clock_.now());
    pump();
    start_read();
  };
  switch (endpoint_.kind) {
    case PlatformEndpoint::Kind::serial: serial_.async_read_some(asio::buffer(rx_), handler); break;
    case PlatformEndpoint::Kind::udp: udp_.async_receive(asio::buffer(rx_), handler); break;
    case PlatformEndpoint::Kind::tcp: tcp_.async_read_some(asio::buffer(rx_), handler); break;
  }
}

int ClearpathLink::native_handle() {
  switch (endpoint_.kind) {
    case PlatformEndpoint::Kind::serial: return serial_.native_handle();
    case PlatformEndpoint::Kind::udp: return udp_.native_handle();
    case PlatformEndpoint::Kind::tcp: return tcp_.native_handle();
  }
  return -1;
}

// Writes are ours, non-blocking and synchronous, not Asio's async_write:
// what has gone out of the current frame (tx_sent_) is then always known on
// this thread, so flush() can finish exactly that frame before writing its
// own. With an async_write in flight, the bytes it has already written are
// known only to its handler, which runs only if the io_context runs again
// (an exit does not), and a synchronous write beside it would put another
// frame into the middle of a half-written one. A full kernel buffer (rare:
// 4 KiB of tty buffer is a third of a second at 115200 baud) leaves the rest
// for the next tick.
void ClearpathLink::pump() {
  if (!open_ || writing_) return;
  writing_ = true;  // on_written may send: that frame goes out in this loop
  while (open_) {
    if (tx_sent_ == tx_.size()) {
      tx_ = core_.take_frame(clock_.now());
      tx_sent_ = 0;
      if (tx_.empty()) break;
    }
    error_code ec;
    tx_sent_ += write_now(native_handle(), endpoint_.kind != PlatformEndpoint::Kind::serial,
                          std::span<const std::uint8_t>(tx_).subspan(tx_sent_), ec);
    if (ec) {
      writing_ = false;
      return fail(ec);
    }
    if (tx_sent_ < tx_.size()) break;  // the kernel's buffer is full
    if (on_written_) on_written_(tx_);
  }
  writing_ = false;
}

void ClearpathLink::flush() {
  if (!open_ || writing_) return;
  const int fd = native_handle();
  const bool socket = endpoint_.kind != PlatformEndpoint::Kind::serial;
  const auto limit = std::chrono::steady_clock::now() + kFlushLimit;
  // Waits (poll) while the kernel's buffer is full, up to kFlushLimit in all.
  const auto write_all = [&](std::span<const std::uint8_t> bytes) {
    while (!bytes.empty()) {
      error_code ec;
      const auto n = write_now(fd, socket, bytes, ec);
      if (ec) return false;
      bytes = bytes.subspan(n);
      if (n > 0) continue;
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(limit - std::chrono::steady_clock::now());
      pollfd p{fd, POLLOUT, 0};
      if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    }
    return true;
  };
  // The rest of a frame the last pump left half written first, or the
  // platform would get the start of one frame and then another.
  if (!write_all(std::span<const std::uint8_t>(tx_).subspan(tx_sent_))) return;
  tx_sent_ = tx_.size();
  for (auto frame = core_.take_frame(clock_.now()); !frame.empty(); frame = core_.take_frame(clock_.now()))
    if (!write_all(frame)) return;
}

void ClearpathLink::on_tick() {
  if (!running_) return;
  const auto now = clock_.now();
  core_.tick(now);
  if (core_.state() == ConnectionState::down && open_) close();
  if (core_.wants_reconnect() && now >= core_.reconnect_at()) open();
  pump();
  tick_ = scheduler_.call_at(now + kTickPeriod, [this, alive = alive_] {
    if (*alive) on_tick();
  });
}

}  // namespace jaus::clearpath
