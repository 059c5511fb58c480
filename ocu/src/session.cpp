#include "jaus/ocu/session.hpp"

#include <algorithm>
#include <random>

#include "jaus/components/node_manager.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;
using jaus::unexpected;

constexpr std::uint8_t kNodeManagerComponent = 1;
constexpr const char* kExits = "jausctl exits";

// Who the OCU's node manager says the node is.
jaus::components::NodeManagerConfig ocu_identity() {
  jaus::components::NodeManagerConfig identity;
  identity.subsystem_name = "jausctl";
  identity.subsystem_type = kOcuSubsystemType;
  identity.node_name = "jausctl";
  return identity;
}

}  // namespace

OcuSession::OcuSession(SessionOptions options) : options_(std::move(options)) {
  if (!options_.log) options_.log = jaus::rt::silent_log();
}

jaus::Expected<void> OcuSession::check_address(const jaus::Address& self) {
  if (!self.is_valid() || self.is_broadcast() || self.component == kNodeManagerComponent)
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::invalid_argument,
        "the OCU's address " + self.to_string() + " must be a real component (no 0 or 255; component 1 is its node manager)"));
  return {};
}

jaus::Expected<std::unique_ptr<OcuSession>> OcuSession::open(SessionOptions options, boost::asio::io_context* io) {
  if (auto checked = check_address(options.self); !checked) return unexpected(checked.error());
  const jaus::Address self = options.self;
  std::unique_ptr<OcuSession> s(new OcuSession(std::move(options)));
  if (!io) {
    s->owned_io_ = std::make_unique<boost::asio::io_context>();
    io = s->owned_io_.get();
  }
  const SessionOptions& o = s->options_;

  jaus::host::HostConfig config;
  config.node.subsystem = self.subsystem;
  config.node.node = self.node;
  config.node.dialect = o.dialect;
  // Each run numbers its messages from a random start: runs that follow one
  // another under one kept operator ID would otherwise send a repeated
  // command with the number the last run gave it, and a vehicle would take it
  // for that run's retransmitted copy (ACKed, not acted on).
  config.node.sequences.first = static_cast<std::uint16_t>(std::random_device{}());
  config.node.acks.round_trip = o.must_arrive.round_trip;
  config.link.bind = o.bind;
  config.link.framing = o.framing;
  config.link.multicast = o.multicast;
  for (const auto& peer : o.to) config.link.peers.push_back(jaus::transport::StaticPeer{peer, o.framing});
  config.link.relay = false;  // messages end at the OCU
  config.operator_unit = true;  // no vehicle posture warnings, no holds file (HostConfig)
  config.link.broadcast_to_unheard_peers = true;  // a stop to S.255.255.255 reaches a vehicle not heard yet
  config.settings.identity = ocu_identity();
  config.components = {jaus::host::ComponentSpec{"node_manager", kNodeManagerComponent, 1, 0, "jausctl node manager", {}, 0, {}}};
  auto host = jaus::host::NodeHost::open(std::move(config), *io, o.log);
  if (!host) return unexpected(host.error());
  s->host_ = std::move(*host);
  s->host_->watch([session = s.get()](const jaus::PacketView& packet) { session->observe(packet); });
  s->node_ = &s->host_->node();
  s->run_on(s->host_->clock(), s->host_->scheduler(), io, {});
  s->add_ocu_component();
  return s;
}

jaus::Expected<std::unique_ptr<OcuSession>> OcuSession::attach(SessionOptions options, SessionEnvironment environment) {
  if (auto checked = check_address(options.self); !checked) return unexpected(checked.error());
  if (!environment.clock || !environment.scheduler || !environment.link || !environment.connect || !environment.wait)
    return unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument,
                                       "an attached OCU session needs a clock, a scheduler, a link, connect and wait"));
  std::unique_ptr<OcuSession> s(new OcuSession(std::move(options)));
  s->environment_ = std::move(environment);
  const SessionOptions& o = s->options_;
  jaus::node::NodeConfig node_config;
  node_config.subsystem = o.self.subsystem;
  node_config.node = o.self.node;
  node_config.dialect = o.dialect;
  node_config.acks.round_trip = o.must_arrive.round_trip;
  SessionEnvironment& env = s->environment_;
  s->own_node_ = std::make_unique<jaus::node::Node>(node_config, *env.clock, *env.scheduler, *env.link, o.log);
  s->node_ = s->own_node_.get();
  s->run_on(*env.clock, *env.scheduler, nullptr, env.wait);
  jaus::rt::ComponentConfig manager;
  manager.name = "jausctl node manager";
  manager.address = jaus::Address{o.self.subsystem, o.self.node, kNodeManagerComponent, 1};
  s->node_->add(std::make_unique<jaus::components::NodeManager>(manager, s->node_->environment(), *s->node_,
                                                                ocu_identity()));
  s->add_ocu_component();
  env.connect([session = s.get()](std::span<const std::uint8_t> bytes) { session->receive_packet(bytes); });
  return s;
}

void OcuSession::add_ocu_component() {
  jaus::rt::ComponentConfig config =
      host_ ? host_->component_config("jausctl", options_.self.component, options_.self.instance) : jaus::rt::ComponentConfig{};
  config.name = "jausctl";
  config.address = options_.self;
  config.authority = options_.authority;
  component_ = &node_->add_as(std::make_unique<OcuComponent>(
      config, node_->environment(), [this](const jaus::Header& h, std::span<const std::uint8_t> payload) {
        deliver(Received{h, {payload.begin(), payload.end()}});
      }));
}

void OcuSession::receive_packet(std::span<const std::uint8_t> bytes) {
  // What a UDP link checks before the node: a packet that does not decode is
  // the node's to count (receive_bytes).
  const auto packet = jaus::decode_packet(bytes);
  if (!packet) return node_->receive_bytes(bytes);
  observe(*packet);
  node_->receive(*packet);
}

jaus::transport::UdpLink* OcuSession::udp_link() { return host_ ? host_->udp_link() : nullptr; }

OcuSession::~OcuSession() {
  // While the link is open: the OCU component's service connections are
  // terminated on the wire, not left to time out on the provider.
  if (host_) host_->stop(kExits);
  if (own_node_) {
    own_node_->shutdown(kExits);
    environment_.connect({});  // nothing more for this session
  }
}

void OcuSession::send_raw(jaus::Header header, std::span<const std::uint8_t> payload) {
  header.source = options_.self;
  header.data_size = static_cast<std::uint16_t>(std::min(payload.size(), std::size_t{0xFFFF}));
  node_->send(header, payload);
}

OcuSession::ListenerId OcuSession::watch(Watcher watcher) {
  const ListenerId id = next_listener_id();
  watchers_.emplace(id, std::move(watcher));
  return id;
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
  // (An ACK or NAK carries the code of what it answers, and no message: the
  // node settles it, must_arrive.hpp.)
  const bool ack_or_nak = h.ack_nak == jaus::AckNak::ack || h.ack_nak == jaus::AckNak::nak;
  if (h.data_flag == jaus::DataFlag::single && !ack_or_nak && h.destination.matches(options_.self) &&
      component_->consumes(h.command_code))
    deliver(Received{h, {packet.payload.begin(), packet.payload.end()}});
}

}  // namespace jaus::ocu
