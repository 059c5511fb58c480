#include "session.hpp"

#include <algorithm>
#include <csignal>

#include "cli_values.hpp"
#include "jaus/components/node_manager.hpp"

namespace jausctl::ocu {

namespace {

using namespace std::chrono_literals;
using jaus::unexpected;

// run_until() wakes at least this often to look at its deadline.
constexpr jaus::rt::Duration kRunSlice = 100ms;
constexpr std::uint8_t kNodeManagerComponent = 1;

}  // namespace

std::string no_reply_text(const jaus::Address& from, jaus::rt::Duration timeout) {
  return "no reply from " + from.to_string() + " within " + seconds_text(timeout);
}

OcuSession::OcuSession(SessionOptions options, boost::asio::io_context* io)
    : options_(std::move(options)),
      owned_io_(io ? nullptr : std::make_unique<boost::asio::io_context>()),
      io_(io ? *io : *owned_io_),
      runtime_(io_) {
  if (!options_.log) options_.log = [](jaus::rt::LogLevel, const std::string&) {};
}

jaus::Expected<std::unique_ptr<OcuSession>, std::string> OcuSession::open(SessionOptions options,
                                                                          boost::asio::io_context* io) {
  const jaus::Address self = options.self;
  if (!self.is_valid() || self.is_broadcast() || self.component == kNodeManagerComponent)
    return unexpected("the OCU's address " + self.to_string() +
                      " must be a real component (no 0 or 255; component 1 is its node manager)");
  std::unique_ptr<OcuSession> s(new OcuSession(std::move(options), io));
  const SessionOptions& o = s->options_;

  jaus::transport::UdpLinkOptions link_options;
  link_options.subsystem = self.subsystem;
  link_options.node = self.node;
  link_options.bind = o.bind;
  link_options.framing = o.framing;
  for (const auto& peer : o.to) link_options.peers.push_back(jaus::transport::StaticPeer{peer, o.framing});
  auto link = jaus::transport::UdpLink::open(s->io_, s->runtime_, s->runtime_, link_options, o.log);
  if (!link) return unexpected(link.error());
  s->link_ = std::move(*link);

  jaus::node::NodeConfig node_config;
  node_config.subsystem = self.subsystem;
  node_config.node = self.node;
  node_config.dialect = o.dialect;
  s->node_ = std::make_unique<jaus::node::Node>(node_config, s->runtime_, s->runtime_, *s->link_, o.log);
  s->link_->on_packet([session = s.get()](std::span<const std::uint8_t> packet) {
    session->observe(packet);
    session->node_->receive(packet);
  });

  jaus::rt::ComponentConfig manager_config;
  manager_config.name = "jausctl node manager";
  manager_config.address = jaus::Address{self.subsystem, self.node, kNodeManagerComponent, 1};
  jaus::rt::NodeManagerConfig identity;
  identity.subsystem_name = "jausctl";
  identity.subsystem_type = kOcuSubsystemType;
  identity.node_name = "jausctl";
  auto& manager = s->node_->add(std::make_unique<jaus::rt::NodeManager>(manager_config, s->node_->environment(),
                                                                         *s->node_, identity));
  s->node_->set_node_manager(static_cast<jaus::rt::NodeManager*>(&manager));

  jaus::rt::ComponentConfig ocu_config;
  ocu_config.name = "jausctl";
  ocu_config.address = self;
  ocu_config.authority = o.authority;
  s->component_ = static_cast<OcuComponent*>(&s->node_->add(std::make_unique<OcuComponent>(
      ocu_config, s->node_->environment(),
      [session = s.get()](const jaus::Header& h, std::span<const std::uint8_t> payload) {
        session->deliver(Received{h, {payload.begin(), payload.end()}});
      })));
  s->link_->start();
  return s;
}

OcuSession::~OcuSession() {
  if (signals_) {
    boost::system::error_code ignored;
    signals_->cancel(ignored);
  }
  // While the link is open: the OCU component's service connections are
  // terminated on the wire, not left to time out on the provider.
  if (node_) node_->shutdown("jausctl exits");
  node_.reset();
  if (link_) link_->close();
}

void OcuSession::send_raw(jaus::Header header, std::span<const std::uint8_t> payload) {
  header.source = options_.self;
  header.data_size = static_cast<std::uint16_t>(std::min(payload.size(), std::size_t{0xFFFF}));
  node_->send(header, payload);
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

void OcuSession::observe(std::span<const std::uint8_t> packet) {
  auto decoded = jaus::decode_packet(packet);
  if (!decoded) return;  // the node counts and logs it
  const jaus::Header& h = decoded->header;
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
    deliver(Received{h, {decoded->payload.begin(), decoded->payload.end()}});
}

void OcuSession::deliver(const Received& message) {
  std::vector<ListenerId> ids;
  for (const auto& [id, l] : listeners_) ids.push_back(id);
  for (const auto id : ids)
    if (const auto it = listeners_.find(id); it != listeners_.end()) it->second(message);
}

bool OcuSession::run_until(const std::function<bool()>& done, jaus::rt::Duration limit) {
  const auto deadline = runtime_.now() + limit;
  for (;;) {
    if (done()) return true;
    if (interrupted_) return false;
    const auto now = runtime_.now();
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

jaus::Expected<Received, std::string> OcuSession::await_reply(const jaus::Address& from,
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
  if (interrupted_) return unexpected(std::string("interrupted"));
  return unexpected(no_reply_text(from, timeout));
}

}  // namespace jausctl::ocu
