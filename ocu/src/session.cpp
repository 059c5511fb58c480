#include "jaus/ocu/session.hpp"

#include <algorithm>
#include <csignal>

#include "jaus/host/node_host.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;
using jaus::unexpected;

// run_until() wakes at least this often to look at its deadline.
constexpr jaus::rt::Duration kRunSlice = 100ms;
constexpr std::uint8_t kNodeManagerComponent = 1;

}  // namespace

jaus::Error no_reply_error(const jaus::Address& from, jaus::rt::Duration timeout) {
  return jaus::make_error(jaus::ErrorCode::timeout, "no reply from " + from.to_string() + " within " + seconds_text(timeout));
}

OcuSession::OcuSession(SessionOptions options, boost::asio::io_context* io)
    : options_(std::move(options)),
      owned_io_(io ? nullptr : std::make_unique<boost::asio::io_context>()),
      io_(io ? *io : *owned_io_) {
  if (!options_.log) options_.log = jaus::rt::silent_log();
}

jaus::Expected<std::unique_ptr<OcuSession>> OcuSession::open(SessionOptions options, boost::asio::io_context* io) {
  const jaus::Address self = options.self;
  if (!self.is_valid() || self.is_broadcast() || self.component == kNodeManagerComponent)
    return unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument,
                                       "the OCU's address " + self.to_string() +
                                           " must be a real component (no 0 or 255; component 1 is its node manager)"));
  std::unique_ptr<OcuSession> s(new OcuSession(std::move(options), io));
  const SessionOptions& o = s->options_;

  jaus::host::HostConfig config;
  config.node.subsystem = self.subsystem;
  config.node.node = self.node;
  config.node.dialect = o.dialect;
  config.link.bind = o.bind;
  config.link.framing = o.framing;
  for (const auto& peer : o.to) config.link.peers.push_back(jaus::transport::StaticPeer{peer, o.framing});
  config.link.relay = false;  // messages end at the OCU
  config.settings.identity.subsystem_name = "jausctl";
  config.settings.identity.subsystem_type = kOcuSubsystemType;
  config.settings.identity.node_name = "jausctl";
  config.components = {jaus::host::ComponentSpec{"node_manager", kNodeManagerComponent, 1, 0, "jausctl node manager", {}, 0, {}}};
  auto host = jaus::host::NodeHost::open(std::move(config), s->io_, o.log);
  if (!host) return unexpected(host.error());
  s->host_ = std::move(*host);
  s->host_->watch([session = s.get()](const jaus::PacketView& packet) { session->observe(packet); });

  jaus::rt::ComponentConfig ocu_config = s->host_->component_config("jausctl", self.component, self.instance);
  ocu_config.authority = o.authority;
  s->component_ = &s->host_->emplace<OcuComponent>(
      ocu_config, [session = s.get()](const jaus::Header& h, std::span<const std::uint8_t> payload) {
        session->deliver(Received{h, {payload.begin(), payload.end()}});
      });
  return s;
}

jaus::node::Node& OcuSession::node() { return host_->node(); }
jaus::transport::UdpLink& OcuSession::link() { return host_->link(); }
jaus::rt::Clock& OcuSession::clock() { return host_->runtime(); }

OcuSession::~OcuSession() {
  if (signals_) {
    boost::system::error_code ignored;
    signals_->cancel(ignored);
  }
  // While the link is open: the OCU component's service connections are
  // terminated on the wire, not left to time out on the provider.
  if (host_) host_->stop("jausctl exits");
}

void OcuSession::send_raw(jaus::Header header, std::span<const std::uint8_t> payload) {
  header.source = options_.self;
  header.data_size = static_cast<std::uint16_t>(std::min(payload.size(), std::size_t{0xFFFF}));
  host_->node().send(header, payload);
}

OcuSession::ListenerId OcuSession::listen(Listener listener) {
  listeners_.emplace(++last_id_, std::move(listener));
  return last_id_;
}

OcuSession::ListenerId OcuSession::watch(Watcher watcher) {
  watchers_.emplace(++last_id_, std::move(watcher));
  return last_id_;
}

void OcuSession::unlisten(ListenerId id) {
  listeners_.erase(id);
  watchers_.erase(id);
}

void OcuSession::observe(const jaus::PacketView& packet) {
  const jaus::Header& h = packet.header;
  if (h.source.subsystem == options_.self.subsystem && h.source.node == options_.self.node) return;
  // Watchers may unlisten themselves (or others) while called: walk the ids.
  std::vector<ListenerId> ids;
  for (const auto& [id, w] : watchers_) ids.push_back(id);
  for (const auto id : ids)
    if (const auto it = watchers_.find(id); it != watchers_.end()) it->second(h);
  // Messages the runtime consumes never reach the component's inbox; the
  // caller still wants to see them (a Confirm Service Connection after `send`).
  if (h.data_flag == jaus::DataFlag::single && h.destination.matches(options_.self) &&
      component_->consumes(h.command_code))
    deliver(Received{h, {packet.payload.begin(), packet.payload.end()}});
}

void OcuSession::deliver(const Received& message) {
  std::vector<ListenerId> ids;
  for (const auto& [id, l] : listeners_) ids.push_back(id);
  for (const auto id : ids)
    if (const auto it = listeners_.find(id); it != listeners_.end()) it->second(message);
}

bool OcuSession::run_until(const std::function<bool()>& done, jaus::rt::Duration limit) {
  const auto deadline = clock().now() + limit;
  for (;;) {
    if (done()) return true;
    if (interrupted_) return false;
    const auto now = clock().now();
    if (now >= deadline) return false;
    if (io_.stopped()) io_.restart();
    io_.run_one_for(std::min(deadline - now, kRunSlice));
  }
}

void OcuSession::stop_on_signals() {
  if (signals_) return;
  signals_.emplace(io_, SIGINT, SIGTERM);
  arm_signals();
}

void OcuSession::arm_signals() {
  // Every signal interrupts; the commands' clean-up only sends (it never
  // waits), so a second Ctrl-C is never needed.
  signals_->async_wait([this](const boost::system::error_code& ec, int) {
    if (ec) return;  // cancelled: the session is gone
    interrupted_ = true;
    arm_signals();
  });
}

jaus::Expected<Received> OcuSession::await_reply(const jaus::Address& from,
                                                              std::vector<std::uint16_t> codes,
                                                              jaus::rt::Duration timeout) {
  std::optional<Received> reply;
  const ListenerId id = listen([&](const Received& r) {
    if (reply || !from.matches(r.header.source)) return;
    if (!codes.empty() && std::find(codes.begin(), codes.end(), r.header.command_code) == codes.end()) return;
    reply = r;
  });
  run_until([&] { return reply.has_value(); }, timeout);
  unlisten(id);
  if (reply) return std::move(*reply);
  if (interrupted_) return unexpected(jaus::make_error(jaus::ErrorCode::interrupted, "interrupted"));
  return unexpected(no_reply_error(from, timeout));
}

}  // namespace jaus::ocu
