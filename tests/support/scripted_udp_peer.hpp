// A JAUS peer scripted over a plain UDP socket on loopback (an ephemeral
// port), for tests that need a node our code did not make: it hands each
// packet that unframes to on_packet() and sends messages in the OPC framing,
// replies to the endpoint the last packet came from.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <array>
#include <span>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jausctl::test {

class ScriptedUdpPeer {
 public:
  explicit ScriptedUdpPeer(boost::asio::io_context& io) : socket_(io) {
    namespace ip = boost::asio::ip;
    socket_.open(ip::udp::v4());
    socket_.bind(ip::udp::endpoint(ip::make_address_v4("127.0.0.1"), 0));
    receive();  // its handlers run once the io_context runs, after the derived peer is made
  }
  virtual ~ScriptedUdpPeer() = default;
  ScriptedUdpPeer(const ScriptedUdpPeer&) = delete;
  ScriptedUdpPeer& operator=(const ScriptedUdpPeer&) = delete;

  jaus::transport::Ipv4Endpoint endpoint() const {
    const auto e = socket_.local_endpoint();
    return jaus::transport::Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
  }

 protected:
  using Endpoint = boost::asio::ip::udp::endpoint;

  virtual void on_packet(const jaus::Header& header, std::span<const std::uint8_t> payload) = 0;

  // Nothing in or out from now on.
  void close() {
    boost::system::error_code ignored;
    socket_.close(ignored);
  }

  template <class M>
  void reply(const jaus::Address& from, const jaus::Address& to, const M& message) {
    send(from, to, message, from_);
  }

  template <class M>
  void send(const jaus::Address& from, const jaus::Address& to, const M& message, const Endpoint& endpoint) {
    std::vector<std::uint8_t> packet(jaus::kHeaderSize + jaus::kMaxPayloadSize);
    const auto size = jaus::wire::encode_payload(message, std::span(packet).subspan(jaus::kHeaderSize));
    if (!size) return;
    jaus::Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    jaus::encode_header_unchecked(h, std::span(packet).template first<jaus::kHeaderSize>());
    packet.resize(jaus::kHeaderSize + *size);
    const auto prefix = jaus::transport::frame_prefix(jaus::transport::Framing::opc, packet.size());
    std::vector<std::uint8_t> datagram(prefix.view().begin(), prefix.view().end());
    datagram.insert(datagram.end(), packet.begin(), packet.end());
    boost::system::error_code ignored;
    socket_.send_to(boost::asio::buffer(datagram), endpoint, 0, ignored);
  }

 private:
  void receive() {
    socket_.async_receive_from(boost::asio::buffer(buffer_), from_,
                               [this](const boost::system::error_code& ec, std::size_t size) {
                                 if (ec == boost::asio::error::operation_aborted || !socket_.is_open()) return;
                                 if (!ec)
                                   if (const auto unframed = jaus::transport::unframe(std::span(buffer_).first(size)))
                                     on_packet(unframed->packet.header, unframed->packet.payload);
                                 receive();
                               });
  }

  boost::asio::ip::udp::socket socket_;
  Endpoint from_;
  std::array<std::uint8_t, 9000> buffer_{};
};

}  // namespace jausctl::test
