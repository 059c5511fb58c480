#include "jaus/console/web_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <random>

#include "jaus/console/web_assets.hpp"
#include "jaus/host/http_token.hpp"

namespace jaus::console {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;

constexpr std::size_t kMaxRequestBytes = 16 * 1024;  // a page's GET: headers only
constexpr auto kHttpTimeout = 30s;

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

jaus::Unexpected<jaus::Error> refused(std::string why) {
  return jaus::unexpected(jaus::make_error(jaus::ErrorCode::refused, std::move(why)));
}

}  // namespace

std::string generate_token() {
  std::random_device random;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 8; ++i) {
    const auto v = random();
    token += kHex[(v >> 12) & 15];
    token += kHex[(v >> 8) & 15];
    token += kHex[(v >> 4) & 15];
    token += kHex[v & 15];
  }
  return token;
}

bool is_loopback(std::uint32_t address) { return jaus::host::is_loopback_address(address); }

jaus::Expected<void> check_upgrade(const WebServerOptions& options, std::uint16_t bound_port,
                                   const UpgradeRequest& request) {
  std::string_view path = request.target.substr(0, request.target.find('?'));
  if (path != "/ws") return refused("no WebSocket at " + std::string(path));
  if (!options.token.empty() && !jaus::host::same_secret(jaus::host::query_value(request.target, "token"), options.token))
    return refused("a wrong or missing ?token=");
  const std::string host = lower(request.host);
  if (is_loopback(options.listen.address)) {
    // On loopback only a loopback name: a site that resolves its own name to
    // 127.0.0.1 (DNS rebinding) is refused.
    const std::string port = ":" + std::to_string(bound_port);
    if (host != "127.0.0.1" + port && host != "localhost" + port && host != "[::1]" + port &&
        host != jaus::transport::ipv4_to_string(options.listen.address) + port)
      return refused("Host '" + std::string(request.host) + "' is not this console's loopback address");
  }
  if (request.origin.empty()) return {};  // not a browser (a test, a script with the token)
  const std::string origin = lower(request.origin);
  if (origin != "http://" + host && origin != "https://" + host)
    return refused("Origin '" + std::string(request.origin) + "' is not this console's page");
  return {};
}

// ---- the server's insides

class PageSession;

struct WebServer::Impl {
  Impl(asio::io_context& io_context, WebServerOptions o, PageEvents e)
      : io(io_context), acceptor(io_context), options(std::move(o)), events(std::move(e)) {}

  void accept();
  void log(jaus::rt::LogLevel level, const std::string& text) const {
    if (options.log) options.log(level, text);
  }

  asio::io_context& io;
  tcp::acceptor acceptor;
  WebServerOptions options;
  PageEvents events;
  std::uint16_t port = 0;
  PageId last_page = 0;
  std::map<PageId, std::weak_ptr<PageSession>> pages;
  bool stopped = false;
  // Sessions still running check this before touching the server.
  std::shared_ptr<Impl*> self = std::make_shared<Impl*>(this);
};

class PageSession : public std::enable_shared_from_this<PageSession> {
 public:
  PageSession(tcp::socket socket, std::weak_ptr<WebServer::Impl*> server, PageId id, std::size_t max_frame,
              std::size_t max_queued)
      : ws_(std::move(socket)), server_(std::move(server)), id_(id), max_queued_(max_queued) {
    ws_.read_message_max(max_frame);
    ws_.auto_fragment(false);  // one frame per message: an image is not cut into 4 KiB pieces
  }

  void accept(http::request<http::string_body> request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
  }

  void send(std::shared_ptr<const std::string> frame) {
    if (closing_) return;
    queued_bytes_ += frame->size();
    if (queued_bytes_ > max_queued_) {
      // A page that cannot keep up is closed rather than let memory grow.
      close();
      return;
    }
    queue_.push_back(std::move(frame));
    if (open_ && !writing_) write_next();
  }

  bool is_open() const { return open_; }

  void close() {
    if (closing_) return;
    closing_ = true;
    queue_.clear();
    beast::error_code ignored;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ignored);
    beast::get_lowest_layer(ws_).socket().close(ignored);
  }

 private:
  WebServer::Impl* server() const {
    const auto s = server_.lock();
    return s ? *s : nullptr;
  }

  void on_accept(beast::error_code ec) {
    auto* s = server();
    if (ec || !s || s->stopped) {
      finished();
      return;
    }
    open_ = true;
    if (s->events.opened) s->events.opened(id_);  // may send: the first write starts there
    if (!writing_ && !queue_.empty()) write_next();
    read();
  }

  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec) {
      finished();
      return;
    }
    const auto data = buffer_.data();
    const std::string_view text(static_cast<const char*>(data.data()), data.size());
    if (auto* s = server(); s && s->events.frame) s->events.frame(id_, text);
    buffer_.consume(buffer_.size());
    if (!closing_) read();
  }

  // One write at a time (Beast allows no more): the next starts when it ends.
  void write_next() {
    writing_ = true;
    ws_.text(true);
    ws_.async_write(asio::buffer(*queue_.front()),
                    [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_write(ec); });
  }

  void on_write(beast::error_code ec) {
    if (ec) {
      close();
      return;
    }
    if (!queue_.empty()) {
      queued_bytes_ -= queue_.front()->size();
      queue_.pop_front();
    }
    if (!queue_.empty())
      write_next();
    else
      writing_ = false;
  }

  // The page is gone: the console hears it once (its drive stops).
  void finished() {
    if (finished_) return;
    finished_ = true;
    close();
    auto* s = server();
    if (!s) return;
    if (s->pages.erase(id_) && open_ && s->events.closed) s->events.closed(id_);
  }

  websocket::stream<beast::tcp_stream> ws_;
  std::weak_ptr<WebServer::Impl*> server_;
  PageId id_;
  std::size_t max_queued_;
  beast::flat_buffer buffer_;
  std::deque<std::shared_ptr<const std::string>> queue_;
  std::size_t queued_bytes_ = 0;
  bool open_ = false;
  bool writing_ = false;
  bool closing_ = false;
  bool finished_ = false;
};

// One HTTP connection: the page's files, or the upgrade to a PageSession.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, std::weak_ptr<WebServer::Impl*> server)
      : stream_(std::move(socket)), server_(std::move(server)) {}

  void read() {
    parser_.emplace();
    parser_->header_limit(kMaxRequestBytes);
    parser_->body_limit(kMaxRequestBytes);
    stream_.expires_after(kHttpTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
  WebServer::Impl* server() const {
    const auto s = server_.lock();
    return s ? *s : nullptr;
  }

  void on_read(beast::error_code ec) {
    auto* s = server();
    if (ec || !s || s->stopped) {
      beast::error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
      return;
    }
    auto request = parser_->release();
    if (websocket::is_upgrade(request)) {
      upgrade(*s, std::move(request));
      return;
    }
    serve(request);
  }

  void upgrade(WebServer::Impl& s, http::request<http::string_body> request) {
    const auto allowed = check_upgrade(
        s.options, s.port,
        UpgradeRequest{std::string_view(request.target().data(), request.target().size()),
                       std::string_view(request[http::field::host].data(), request[http::field::host].size()),
                       std::string_view(request[http::field::origin].data(), request[http::field::origin].size())});
    if (!allowed) {
      s.log(jaus::rt::LogLevel::warn, "WebSocket refused: " + allowed.error().message());
      respond(request, http::status::forbidden, "text/plain; charset=utf-8", allowed.error().message() + "\n", false);
      return;
    }
    if (s.pages.size() >= s.options.max_pages) {
      s.log(jaus::rt::LogLevel::warn, "WebSocket refused: already " + std::to_string(s.pages.size()) + " pages");
      respond(request, http::status::service_unavailable, "text/plain; charset=utf-8",
              "too many pages (" + std::to_string(s.options.max_pages) + ")\n", false);
      return;
    }
    stream_.expires_never();
    const PageId id = ++s.last_page;
    auto page = std::make_shared<PageSession>(stream_.release_socket(), server_, id, s.options.max_frame_bytes,
                                              s.options.max_queued_bytes);
    s.pages[id] = page;
    page->accept(std::move(request));
  }

  void serve(const http::request<http::string_body>& request) {
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      respond(request, http::status::method_not_allowed, "text/plain; charset=utf-8", "GET only\n", true);
      return;
    }
    const std::string_view target(request.target().data(), request.target().size());
    const WebAsset* asset = find_web_asset(target);
    if (!asset) {
      respond(request, http::status::not_found, "text/plain; charset=utf-8", "not found\n", true);
      return;
    }
    respond(request, http::status::ok, asset->content_type,
            std::string(reinterpret_cast<const char*>(asset->bytes.data()), asset->bytes.size()), true);
  }

  void respond(const http::request<http::string_body>& request, http::status status, std::string_view type,
               std::string body, bool keep_alive) {
    auto response = std::make_shared<http::response<http::string_body>>(status, request.version());
    response->set(http::field::server, "jaus-console");
    response->set(http::field::content_type, std::string(type));
    response->set(http::field::cache_control, "no-store");
    response->set("X-Content-Type-Options", "nosniff");
    response->set("X-Frame-Options", "DENY");
    response->keep_alive(keep_alive && request.keep_alive());
    const bool head = request.method() == http::verb::head;
    response->body() = std::move(body);
    response->prepare_payload();
    if (head) response->body().clear();
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
                        if (ec || !response->keep_alive()) {
                          beast::error_code ignored;
                          self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                          return;
                        }
                        self->read();
                      });
  }

  beast::tcp_stream stream_;
  std::weak_ptr<WebServer::Impl*> server_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

void WebServer::Impl::accept() {
  acceptor.async_accept([this, alive = std::weak_ptr<Impl*>(self)](beast::error_code ec, tcp::socket socket) {
    if (alive.expired() || stopped) return;
    if (!ec) std::make_shared<HttpSession>(std::move(socket), self)->read();
    accept();
  });
}

jaus::Expected<std::unique_ptr<WebServer>> WebServer::start(asio::io_context& io, WebServerOptions options,
                                                             PageEvents events) {
  if (!is_loopback(options.listen.address) && options.token.empty())
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::invalid_argument,
        "listening on " + jaus::transport::to_string(options.listen) + ", beyond loopback, needs a token"));
  auto impl = std::make_unique<Impl>(io, std::move(options), std::move(events));
  const tcp::endpoint endpoint(asio::ip::address_v4(impl->options.listen.address), impl->options.listen.port);
  beast::error_code ec;
  const auto fail = [&](const char* what) {
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::io, jaus::transport::to_string(impl->options.listen) + ": " + what + ": " + ec.message()));
  };
  impl->acceptor.open(endpoint.protocol(), ec);
  if (ec) return fail("cannot open a socket");
  impl->acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  impl->acceptor.bind(endpoint, ec);
  if (ec) return fail("cannot listen");
  impl->acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return fail("cannot listen");
  impl->port = impl->acceptor.local_endpoint(ec).port();
  impl->accept();
  return std::unique_ptr<WebServer>(new WebServer(std::move(impl)));
}

WebServer::WebServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebServer::~WebServer() { stop(); }

std::uint16_t WebServer::port() const { return impl_->port; }
std::size_t WebServer::page_count() const { return impl_->pages.size(); }

void WebServer::send(PageId to, const std::string& frame) {
  auto shared = std::make_shared<const std::string>(frame);
  if (to != 0) {
    if (auto it = impl_->pages.find(to); it != impl_->pages.end())
      if (auto page = it->second.lock()) page->send(std::move(shared));
    return;
  }
  // Copied first: a page closed while sending leaves the map.
  std::vector<std::shared_ptr<PageSession>> pages;
  for (auto& [id, weak] : impl_->pages)
    if (auto page = weak.lock()) pages.push_back(std::move(page));
  for (auto& page : pages) page->send(shared);
}

void WebServer::stop() {
  if (impl_->stopped) return;
  impl_->stopped = true;
  beast::error_code ignored;
  impl_->acceptor.close(ignored);
  auto pages = std::move(impl_->pages);
  impl_->pages.clear();
  for (auto& [id, weak] : pages)
    if (auto page = weak.lock()) {
      if (page->is_open() && impl_->events.closed) impl_->events.closed(id);
      page->close();
    }
}

}  // namespace jaus::console
