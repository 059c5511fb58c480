// The JSS session's UDP sockets: one bound to the session's address (what
// it sends from, where replies come), and, with a multicast group, one bound
// to the group to hear broadcasts. Best effort for the group, as UdpLink.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>

#include "jaus/base/expected.hpp"
#include "jaus/base/log.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::ocu::detail {

class JssSocket {
 public:
  using Receiver = std::function<void(const transport::Ipv4Endpoint& from, std::span<const std::uint8_t> datagram)>;

  // Errors (io): "0.0.0.0:3794 is already in use", "cannot open a UDP socket: ...".
  static Expected<std::unique_ptr<JssSocket>> open(boost::asio::io_context& io, transport::Ipv4Endpoint bind,
                                                   std::optional<transport::Ipv4Endpoint> multicast, rt::LogFn log,
                                                   Receiver receiver);
  ~JssSocket();
  JssSocket(const JssSocket&) = delete;
  JssSocket& operator=(const JssSocket&) = delete;

  void send_to(const transport::Ipv4Endpoint& to, std::span<const std::uint8_t> datagram);
  bool has_multicast() const { return multicast_group_.has_value(); }
  transport::Ipv4Endpoint local_endpoint() const;

 private:
  struct Socket {
    explicit Socket(boost::asio::io_context& io) : socket(io) {}
    boost::asio::ip::udp::socket socket;
    boost::asio::ip::udp::endpoint sender;
    std::array<std::uint8_t, 65536> buffer{};
  };
  JssSocket(boost::asio::io_context& io, rt::LogFn log, Receiver receiver);
  Expected<void> bind(transport::Ipv4Endpoint bind, std::optional<transport::Ipv4Endpoint> multicast);
  void receive_next(Socket& socket);

  boost::asio::io_context& io_;
  rt::LogFn log_;
  Receiver receiver_;
  std::unique_ptr<Socket> main_;
  std::unique_ptr<Socket> group_;
  std::optional<transport::Ipv4Endpoint> multicast_group_;
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace jaus::ocu::detail
