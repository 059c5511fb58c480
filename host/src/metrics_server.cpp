#include "jaus/host/metrics_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>

#include "jaus/base/error.hpp"
#include "jaus/host/http_token.hpp"

namespace jaus::host {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;

constexpr std::size_t kMaxMetricsRequestHeader = 8 * 1024;  // a scrape's GET: headers only
constexpr auto kMetricsConnectionTime = 5s;
constexpr auto kAcceptRetry = 100ms;
constexpr const char* kExpositionType = "text/plain; version=0.0.4; charset=utf-8";

}  // namespace

struct MetricsServer::Impl {
  Impl(asio::io_context& io, MetricsServerOptions o, std::function<std::string()> r)
      : acceptor(io), retry(io), options(std::move(o)), render(std::move(r)) {}

  void accept(std::shared_ptr<Impl> self);

  tcp::acceptor acceptor;
  asio::steady_timer retry;  // after a failed accept (no file descriptors left): no busy loop
  MetricsServerOptions options;
  std::function<std::string()> render;  // emptied when the server goes: what it reads may be gone
  MetricsServerCounters counters;
  std::size_t open_connections = 0;
  std::uint16_t port = 0;
};

namespace {

class MetricsConnection : public std::enable_shared_from_this<MetricsConnection> {
 public:
  MetricsConnection(tcp::socket socket, std::shared_ptr<MetricsServer::Impl> server)
      : stream_(std::move(socket)), server_(std::move(server)) {
    ++server_->open_connections;
    parser_.header_limit(kMaxMetricsRequestHeader);
    parser_.body_limit(0);
  }
  ~MetricsConnection() { --server_->open_connections; }

  void start() {
    stream_.expires_after(kMetricsConnectionTime);
    http::async_read(stream_, buffer_, parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
  void on_read(beast::error_code ec) {
    if (ec) {
      ++server_->counters.failed;
      return;  // the socket closes with this object
    }
    const auto& request = parser_.get();
    response_.version(request.version());
    response_.keep_alive(false);
    const std::string_view target(request.target().data(), request.target().size());
    const std::string_view path = target.substr(0, target.find('?'));
    const auto& token = server_->options.token;
    const std::string_view authorization(request[http::field::authorization].data(),
                                         request[http::field::authorization].size());
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      ++server_->counters.not_found;
      reply(http::status::method_not_allowed, "only GET /metrics here\n");
      response_.set(http::field::allow, "GET, HEAD");
    } else if (path != "/metrics") {
      ++server_->counters.not_found;
      reply(http::status::not_found, "the metrics are at /metrics\n");
    } else if (!token.empty() && !same_secret(bearer_token(authorization), token) &&
               !same_secret(query_value(target, "token"), token)) {
      ++server_->counters.unauthorized;
      reply(http::status::unauthorized, "a token is needed: Authorization: Bearer TOKEN, or ?token=TOKEN\n");
      response_.set(http::field::www_authenticate, "Bearer");
    } else if (!server_->render) {
      reply(http::status::service_unavailable, "the node is stopping\n");
    } else {
      ++server_->counters.served;
      reply(http::status::ok, server_->render(), kExpositionType);
      if (request.method() == http::verb::head) response_.body().clear();
    }
    response_.prepare_payload();
    http::async_write(stream_, response_, [self = shared_from_this()](beast::error_code, std::size_t) {
      beast::error_code ignored;
      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    });
  }
  void reply(http::status status, std::string body, const char* type = "text/plain; charset=utf-8") {
    response_.result(status);
    response_.set(http::field::content_type, type);
    response_.set(http::field::cache_control, "no-store");
    response_.body() = std::move(body);
  }

  beast::tcp_stream stream_;
  std::shared_ptr<MetricsServer::Impl> server_;
  beast::flat_buffer buffer_;
  http::request_parser<http::empty_body> parser_;
  http::response<http::string_body> response_;
};

}  // namespace

void MetricsServer::Impl::accept(std::shared_ptr<Impl> self) {
  acceptor.async_accept([self](beast::error_code ec, tcp::socket socket) {
    if (ec == asio::error::operation_aborted || !self->acceptor.is_open()) return;  // the server is gone
    if (ec) {
      ++self->counters.failed;
      self->retry.expires_after(kAcceptRetry);
      self->retry.async_wait([self](beast::error_code waited) {
        if (!waited && self->acceptor.is_open()) self->accept(self);
      });
      return;
    }
    if (self->open_connections >= self->options.max_connections) {
      ++self->counters.turned_away;  // `socket` closes here
    } else {
      std::make_shared<MetricsConnection>(std::move(socket), self)->start();
    }
    self->accept(self);
  });
}

Expected<std::unique_ptr<MetricsServer>> MetricsServer::start(asio::io_context& io, MetricsServerOptions options,
                                                              std::function<std::string()> render) {
  const std::string where = transport::to_string(options.listen);
  if (!is_loopback_address(options.listen.address) && options.token.empty())
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "metrics on " + where + " need a token (only loopback may go without one)"));
  auto impl = std::make_shared<Impl>(io, std::move(options), std::move(render));
  const tcp::endpoint endpoint(asio::ip::address_v4(impl->options.listen.address), impl->options.listen.port);
  beast::error_code ec;
  impl->acceptor.open(endpoint.protocol(), ec);
  if (!ec) impl->acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) impl->acceptor.bind(endpoint, ec);
  if (!ec) impl->acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec)
    return unexpected(make_error(ErrorCode::io, "metrics on " + where + ": " +
                                                    (ec == asio::error::address_in_use ? std::string("already in use")
                                                                                       : ec.message())));
  impl->port = impl->acceptor.local_endpoint().port();
  impl->accept(impl);
  return std::unique_ptr<MetricsServer>(new MetricsServer(std::move(impl)));
}

MetricsServer::~MetricsServer() {
  impl_->render = nullptr;
  beast::error_code ignored;
  impl_->acceptor.close(ignored);
  impl_->retry.cancel();
}

std::uint16_t MetricsServer::port() const { return impl_->port; }
const MetricsServerCounters& MetricsServer::counters() const { return impl_->counters; }

}  // namespace jaus::host
