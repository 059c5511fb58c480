#include "jss_socket.hpp"

#include <boost/asio/ip/multicast.hpp>
#include <string>

namespace jaus::ocu::detail {

namespace asio = boost::asio;
using asio::ip::udp;

namespace {

udp::endpoint to_asio(const transport::Ipv4Endpoint& e) {
  return udp::endpoint(asio::ip::address_v4(e.address), e.port);
}
transport::Ipv4Endpoint from_asio(const udp::endpoint& e) {
  return transport::Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
}

std::string bind_error(const transport::Ipv4Endpoint& endpoint, const boost::system::error_code& ec) {
  if (ec == asio::error::address_in_use) return to_string(endpoint) + " is already in use";
  if (ec == boost::system::errc::address_not_available)
    return to_string(endpoint) + " is not an address of this machine";
  return "cannot bind " + to_string(endpoint) + ": " + ec.message();
}

}  // namespace

JssSocket::JssSocket(asio::io_context& io, rt::LogFn log, Receiver receiver)
    : io_(io), log_(log ? std::move(log) : rt::silent_log()), receiver_(std::move(receiver)) {}

Expected<std::unique_ptr<JssSocket>> JssSocket::open(asio::io_context& io, transport::Ipv4Endpoint bind,
                                                     std::optional<transport::Ipv4Endpoint> multicast, rt::LogFn log,
                                                     Receiver receiver) {
  std::unique_ptr<JssSocket> s(new JssSocket(io, std::move(log), std::move(receiver)));
  if (auto bound = s->bind(bind, multicast); !bound) return unexpected(bound.error());
  s->receive_next(*s->main_);
  if (s->group_) s->receive_next(*s->group_);
  return s;
}

Expected<void> JssSocket::bind(transport::Ipv4Endpoint bind, std::optional<transport::Ipv4Endpoint> multicast) {
  const auto failed = [](std::string what) { return unexpected(make_error(ErrorCode::io, std::move(what))); };
  boost::system::error_code ec;
  main_ = std::make_unique<Socket>(io_);
  main_->socket.open(udp::v4(), ec);
  if (ec) return failed("cannot open a UDP socket: " + ec.message());
  main_->socket.bind(to_asio(bind), ec);
  if (ec) return failed(bind_error(bind, ec));
  if (!multicast) return {};
  if (!multicast->is_multicast()) return failed(to_string(*multicast) + " is not a multicast address (224.0.0.0/4)");
  const auto degrade = [&](const std::string& what, const boost::system::error_code& error) -> Expected<void> {
    log_(rt::LogLevel::warn, "JSS multicast " + to_string(*multicast) + ": " + what + ": " + error.message() +
                                 "; talking to the listed peers only");
    group_.reset();
    return {};
  };
  multicast_group_ = multicast;  // sending to it needs no membership
  const auto interface = asio::ip::address_v4(bind.address);
  if (!bind.is_any()) main_->socket.set_option(asio::ip::multicast::outbound_interface(interface), ec);
  if (!ec) main_->socket.set_option(asio::ip::multicast::enable_loopback(true), ec);
  if (ec) {
    multicast_group_.reset();
    return degrade("cannot send", ec);
  }
  group_ = std::make_unique<Socket>(io_);
  group_->socket.open(udp::v4(), ec);
  if (!ec) group_->socket.set_option(udp::socket::reuse_address(true), ec);
  if (!ec) group_->socket.bind(to_asio(*multicast), ec);
  if (!ec)
    group_->socket.set_option(asio::ip::multicast::join_group(asio::ip::address_v4(multicast->address), interface), ec);
  if (ec) return degrade("cannot receive", ec);
  return {};
}

JssSocket::~JssSocket() {
  boost::system::error_code ignored;
  if (main_) main_->socket.close(ignored);
  if (group_) group_->socket.close(ignored);
}

void JssSocket::send_to(const transport::Ipv4Endpoint& to, std::span<const std::uint8_t> datagram) {
  boost::system::error_code ec;  // a lost datagram is the network's: the callers resend
  main_->socket.send_to(asio::buffer(datagram.data(), datagram.size()), to_asio(to), 0, ec);
}

transport::Ipv4Endpoint JssSocket::local_endpoint() const {
  boost::system::error_code ec;
  const auto endpoint = main_->socket.local_endpoint(ec);
  return ec ? transport::Ipv4Endpoint{} : from_asio(endpoint);
}

void JssSocket::receive_next(Socket& socket) {
  socket.socket.async_receive_from(
      asio::buffer(socket.buffer), socket.sender,
      [this, &socket, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec, std::size_t size) {
        if (alive.expired() || ec == asio::error::operation_aborted) return;
        if (!ec) receiver_(from_asio(socket.sender), std::span(socket.buffer).first(size));
        receive_next(socket);  // other errors (ICMP unreachable) are transient
      });
}

}  // namespace jaus::ocu::detail
