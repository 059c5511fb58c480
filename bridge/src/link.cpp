#include "jaus/bridge/link.hpp"

#include <charconv>

namespace jaus::bridge {

namespace asio = boost::asio;
using boost::system::error_code;

namespace {
constexpr auto kTickPeriod = std::chrono::milliseconds(5);

std::optional<std::uint16_t> parse_port(const std::string& s) {
  unsigned v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || v == 0 || v > 65535) return std::nullopt;
  return static_cast<std::uint16_t>(v);
}
}  // namespace

std::optional<LinkEndpoint> parse_endpoint(const std::string& text) {
  LinkEndpoint e;
  const auto colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const std::string scheme = text.substr(0, colon), rest = text.substr(colon + 1);
  if (scheme == "serial") {
    e.kind = LinkEndpoint::Kind::serial;
    const auto at = rest.find('@');
    e.device = rest.substr(0, at);
    if (at != std::string::npos) {
      const auto baud = rest.substr(at + 1);
      const auto [end, ec] = std::from_chars(baud.data(), baud.data() + baud.size(), e.baud);
      if (ec != std::errc{} || end != baud.data() + baud.size()) return std::nullopt;
    }
    return e.device.empty() ? std::nullopt : std::optional(e);
  }
  if (scheme != "udp" && scheme != "tcp") return std::nullopt;
  e.kind = scheme == "udp" ? LinkEndpoint::Kind::udp : LinkEndpoint::Kind::tcp;
  const auto last = rest.rfind(':');
  if (last == std::string::npos) return std::nullopt;
  e.host = rest.substr(0, last);
  const auto port = parse_port(rest.substr(last + 1));
  if (!port || e.host.empty()) return std::nullopt;
  e.port = *port;
  return e;
}

ClearpathLink::ClearpathLink(asio::io_context& io, LinkEndpoint endpoint, ClientConfig config)
    : io_(io), endpoint_(std::move(endpoint)), core_(config), serial_(io), udp_(io), tcp_(io), tick_(io) {}

ClearpathLink::~ClearpathLink() {
  *alive_ = false;
  running_ = false;
  tick_.cancel();
  close();
}

void ClearpathLink::start() {
  running_ = true;
  on_tick();
}

void ClearpathLink::stop() {
  running_ = false;
  tick_.cancel();
  close();
}

void ClearpathLink::send(Message message, ClientCore::CommandCallback done) {
  asio::post(io_, [this, alive = alive_, m = std::move(message), d = std::move(done)]() mutable {
    if (!*alive) return;
    core_.send(std::move(m), std::move(d));
    pump();
  });
}

void ClearpathLink::subscribe(Message request, ClientCore::CommandCallback done) {
  asio::post(io_, [this, alive = alive_, m = std::move(request), d = std::move(done)]() mutable {
    if (!*alive) return;
    core_.subscribe(std::move(m), std::move(d));
    pump();
  });
}

void ClearpathLink::set_setpoint(Message command) {
  asio::post(io_, [this, alive = alive_, m = std::move(command)]() mutable {
    if (!*alive) return;
    core_.set_setpoint(std::move(m));
    pump();
  });
}

void ClearpathLink::on_data(ClientCore::DataCallback callback) {
  asio::post(io_, [this, alive = alive_, c = std::move(callback)]() mutable {
    if (*alive) core_.on_data(std::move(c));
  });
}

void ClearpathLink::close() {
  ++generation_;
  open_ = false;
  writing_ = false;
  error_code ignored;
  if (serial_.is_open()) serial_.close(ignored);
  if (udp_.is_open()) udp_.close(ignored);
  if (tcp_.is_open()) tcp_.close(ignored);
}

void ClearpathLink::fail(const error_code& ec) {
  if (ec == asio::error::operation_aborted) return;
  close();
  core_.on_disconnected(Clock::now());
}

void ClearpathLink::open() {
  close();
  const auto now = Clock::now();
  core_.reconnect_started(now);
  error_code ec;
  switch (endpoint_.kind) {
    case LinkEndpoint::Kind::serial:
      serial_.open(endpoint_.device, ec);
      if (!ec) serial_.set_option(asio::serial_port_base::baud_rate(endpoint_.baud), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::character_size(8), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one), ec);
      if (!ec) serial_.set_option(asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
      break;
    case LinkEndpoint::Kind::udp: {
      const auto address = asio::ip::make_address(endpoint_.host, ec);
      if (ec) break;
      udp_.open(address.is_v4() ? asio::ip::udp::v4() : asio::ip::udp::v6(), ec);
      if (!ec) udp_.connect({address, endpoint_.port}, ec);
      break;
    }
    case LinkEndpoint::Kind::tcp: {
      const auto address = asio::ip::make_address(endpoint_.host, ec);
      if (ec) break;
      // Asynchronous so a slow peer never blocks the io thread.
      const auto generation = generation_;
      tcp_.async_connect({address, endpoint_.port}, [this, alive = alive_, generation](const error_code& cec) {
        if (!*alive || generation != generation_) return;
        if (cec) {
          close();
          core_.open_failed(Clock::now());
          return;
        }
        open_ = true;
        core_.on_connected(Clock::now());
        start_read();
        pump();
      });
      return;
    }
  }
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
    core_.on_bytes(std::span(rx_.data(), n), Clock::now());
    pump();
    start_read();
  };
  switch (endpoint_.kind) {
    case LinkEndpoint::Kind::serial: serial_.async_read_some(asio::buffer(rx_), handler); break;
    case LinkEndpoint::Kind::udp: udp_.async_receive(asio::buffer(rx_), handler); break;
    case LinkEndpoint::Kind::tcp: tcp_.async_read_some(asio::buffer(rx_), handler); break;
  }
}

void ClearpathLink::pump() {
  if (!open_ || writing_) return;
  tx_ = core_.take_frame(Clock::now());
  if (tx_.empty()) return;
  writing_ = true;
  const auto generation = generation_;
  auto handler = [this, alive = alive_, generation](const error_code& ec, std::size_t n) {
    if (!*alive || generation != generation_) return;
    writing_ = false;
    if (ec) return fail(ec);
    if (on_written_) on_written_(n);
    pump();
  };
  switch (endpoint_.kind) {
    case LinkEndpoint::Kind::serial: asio::async_write(serial_, asio::buffer(tx_), handler); break;
    case LinkEndpoint::Kind::udp: udp_.async_send(asio::buffer(tx_), handler); break;
    case LinkEndpoint::Kind::tcp: asio::async_write(tcp_, asio::buffer(tx_), handler); break;
  }
}

void ClearpathLink::on_tick() {
  if (!running_) return;
  const auto now = Clock::now();
  core_.tick(now);
  if (core_.state() == LinkState::down && open_) close();
  if (core_.wants_reconnect() && now >= core_.reconnect_at()) open();
  pump();
  tick_.expires_after(kTickPeriod);
  tick_.async_wait([this, alive = alive_](const error_code& ec) {
    if (!ec && *alive) on_tick();
  });
}

}  // namespace jaus::bridge
