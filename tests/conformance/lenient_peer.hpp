// A component scripted over a plain UDP socket (6.1.40.1 on loopback) that
// never checks a payload, the flaw the robustness cases look for: it
// answers Query Identification with or without its query type, acts on a
// Set Emergency of any size, and answers any message it does not know with
// Report Component Status. Otherwise it answers what learn_component() and
// the cases ask (identification, services, status) and keeps its emergency
// until a Clear Emergency.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <array>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::conform::test {

class LenientPeer {
 public:
  static constexpr Address kAddress{6, 1, 40, 1};

  explicit LenientPeer(boost::asio::io_context& io) : socket_(io) {
    namespace ip = boost::asio::ip;
    socket_.open(ip::udp::v4());
    socket_.bind(ip::udp::endpoint(ip::make_address_v4("127.0.0.1"), 0));
    receive();
  }

  transport::Ipv4Endpoint endpoint() const {
    const auto e = socket_.local_endpoint();
    return transport::Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
  }

 private:
  using Endpoint = boost::asio::ip::udp::endpoint;

  void receive() {
    socket_.async_receive_from(boost::asio::buffer(buffer_), from_,
                               [this](const boost::system::error_code& ec, std::size_t size) {
                                 if (ec == boost::asio::error::operation_aborted || !socket_.is_open()) return;
                                 if (!ec) on_datagram(std::span(buffer_).first(size));
                                 receive();
                               });
  }

  void on_datagram(std::span<const std::uint8_t> datagram) {
    const auto unframed = transport::unframe(datagram);
    if (!unframed) return;
    const Header& h = unframed->packet.header;
    if (!h.destination.matches(kAddress)) return;
    using namespace msg;
    switch (h.command_code) {
      case QueryIdentification::code:  // the flaw: its query type is never read
        return reply(h.source, ReportIdentification{{identification::kComponent, 0, 0, "lenient"}});
      case QueryServices::code: {
        ReportServices services;
        ServiceEntry core;
        for (const std::uint16_t code : {QueryIdentification::code, QueryComponentStatus::code, SetEmergency::code,
                                         ClearEmergency::code})
          core.inputs.push_back({code, 0});
        services.services.push_back(core);
        return reply(h.source, services);
      }
      case QueryComponentStatus::code: {
        const auto state = emergency_ ? PrimaryStatus::emergency : PrimaryStatus::ready;
        return reply(h.source, ReportComponentStatus{{static_cast<std::uint8_t>(state), 0}});
      }
      case SetEmergency::code:  // the flaw: acted on whatever its size
        emergency_ = true;
        return;
      case ClearEmergency::code:
        emergency_ = false;
        return;
      case ReportHeartbeatPulse::code:
        return;
      default:  // the flaw: anything else is answered as if understood
        return reply(h.source, ReportComponentStatus{{static_cast<std::uint8_t>(PrimaryStatus::ready), 0}});
    }
  }

  template <class M>
  void reply(const Address& to, const M& message) {
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(message, std::span(packet).subspan(kHeaderSize));
    if (!size) return;
    Header h;
    h.command_code = M::code;
    h.source = kAddress;
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    encode_header_unchecked(h, std::span(packet).first<kHeaderSize>());
    packet.resize(kHeaderSize + *size);
    const auto prefix = transport::frame_prefix(transport::Framing::opc, packet.size());
    std::vector<std::uint8_t> datagram(prefix.view().begin(), prefix.view().end());
    datagram.insert(datagram.end(), packet.begin(), packet.end());
    boost::system::error_code ignored;
    socket_.send_to(boost::asio::buffer(datagram), from_, 0, ignored);
  }

  boost::asio::ip::udp::socket socket_;
  Endpoint from_;
  std::array<std::uint8_t, 9000> buffer_{};
  bool emergency_ = false;
};

}  // namespace jaus::conform::test
