// The runner's other OCUs on UDP: sessions on the runner's io_context, and a
// silenced one's port kept bound by a socket that hears and never answers.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/ip/udp.hpp>
#include <array>

#include "jaus/conform/ocu_factory.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::conform {

namespace {

// The silent OCU's port. Shared with its pending receive, which may complete
// after the endpoint is gone (cancelled) when the io_context next runs.
struct DeafPort : std::enable_shared_from_this<DeafPort> {
  using udp = boost::asio::ip::udp;
  DeafPort(boost::asio::io_context& io, OcuFactory::Heard on_heard) : socket(io), heard(std::move(on_heard)) {}

  void receive() {
    socket.async_receive_from(boost::asio::buffer(datagram), from,
                              [self = shared_from_this()](const boost::system::error_code& ec, std::size_t size) {
                                if (ec || !self->heard) return;  // closed: the case is over
                                if (auto unframed = transport::unframe(std::span(self->datagram).first(size)))
                                  self->heard(unframed->packet);
                                self->receive();
                              });
  }
  void close() {
    heard = nullptr;
    boost::system::error_code ignored;
    socket.close(ignored);
  }

  udp::socket socket;
  OcuFactory::Heard heard;
  std::array<std::uint8_t, transport::kMaxDatagramSize> datagram{};
  udp::endpoint from;
};

class DeafUdpEndpoint final : public DeafEndpoint {
 public:
  explicit DeafUdpEndpoint(std::shared_ptr<DeafPort> port) : port_(std::move(port)) {}
  ~DeafUdpEndpoint() override { port_->close(); }

 private:
  std::shared_ptr<DeafPort> port_;
};

class UdpOcuFactory final : public OcuFactory {
 public:
  explicit UdpOcuFactory(ocu::OcuSession& runner) : runner_(runner) {}

  Expected<std::unique_ptr<ocu::OcuSession>> open(ocu::SessionOptions options) override {
    options.bind.port = 0;  // the runner's address, a port of its own
    return ocu::OcuSession::open(std::move(options), runner_.io_context());
  }

  Expected<std::unique_ptr<DeafEndpoint>> silence(ocu::OcuSession& session, Heard heard) override {
    auto* link = session.udp_link();
    if (link == nullptr || runner_.io_context() == nullptr)
      return unexpected(make_error(ErrorCode::invalid_argument, "silencing an OCU: it is not on UDP"));
    const transport::Ipv4Endpoint port = link->local_endpoint();
    link->close();
    auto deaf = std::make_shared<DeafPort>(*runner_.io_context(), std::move(heard));
    boost::system::error_code ec;
    deaf->socket.open(DeafPort::udp::v4(), ec);
    if (!ec) deaf->socket.bind(DeafPort::udp::endpoint(boost::asio::ip::address_v4(port.address), port.port), ec);
    if (ec)
      return unexpected(
          make_error(ErrorCode::io, "the silent OCU's port " + transport::to_string(port) + ": " + ec.message()));
    deaf->receive();
    return std::unique_ptr<DeafEndpoint>(std::make_unique<DeafUdpEndpoint>(std::move(deaf)));
  }

 private:
  ocu::OcuSession& runner_;
};

}  // namespace

std::unique_ptr<OcuFactory> udp_ocu_factory(ocu::OcuSession& runner) { return std::make_unique<UdpOcuFactory>(runner); }

}  // namespace jaus::conform
