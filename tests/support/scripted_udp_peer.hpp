// A JAUS peer scripted over a plain UDP socket on loopback (an ephemeral
// port), for tests that need a node our code did not make: it hands each
// packet that unframes to on_packet() and sends messages in the OPC framing,
// replies to the endpoint the last packet came from, and sends to its peers
// (set_peers). The same protected interface as ScriptedMemoryPeer
// (scripted_memory_peer.hpp), so a script runs on either.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <array>
#include <functional>
#include <span>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jausctl::test {

class ScriptedUdpPeer {
 public:
  explicit ScriptedUdpPeer(boost::asio::io_context& io) : socket_(io), timer_(io) {
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
  // Where send_to_peers() sends.
  void set_peers(std::vector<jaus::transport::Ipv4Endpoint> peers) { peers_ = std::move(peers); }

 protected:
  using Endpoint = boost::asio::ip::udp::endpoint;

  virtual void on_packet(const jaus::Header& header, std::span<const std::uint8_t> payload) = 0;

  // Nothing in or out from now on, timer included.
  void close() {
    timer_.cancel();
    boost::system::error_code ignored;
    socket_.close(ignored);
  }

  // Runs `action` once `delay` has passed, unless closed by then; one
  // action pending at a time (a later call replaces it).
  void after(std::chrono::steady_clock::duration delay, std::function<void()> action) {
    timer_.expires_after(delay);
    timer_.async_wait([action = std::move(action)](const boost::system::error_code& ec) {
      if (!ec) action();
    });
  }

  template <class M>
  void reply(const jaus::Address& from, const jaus::Address& to, const M& message) {
    send(from, to, message, from_);
  }

  template <class M>
  void send_to_peers(const jaus::Address& from, const jaus::Address& to, const M& message) {
    for (const auto& peer : peers_) send(from, to, message, Endpoint(boost::asio::ip::address_v4(peer.address), peer.port));
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
  boost::asio::steady_timer timer_;
  std::vector<jaus::transport::Ipv4Endpoint> peers_;
  Endpoint from_;
  std::array<std::uint8_t, 9000> buffer_{};
};

}  // namespace jausctl::test
