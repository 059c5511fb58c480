#include "daemon.hpp"

#include "component_factory.hpp"
#include "jaus/runtime/node_manager.hpp"

namespace jausd {

namespace {

using namespace jaus;

rt::Duration seconds(double s) {
  return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(s));
}

}  // namespace

transport::UdpLinkOptions link_options(const JausdConfig& config) {
  transport::UdpLinkOptions o;
  o.subsystem = config.subsystem;
  o.node = config.node;
  o.bind = config.transport.bind;
  o.framing = config.transport.framing;
  o.multicast = config.transport.multicast;
  o.broadcast_to_peers = config.transport.broadcast_to_peers;
  o.peers = config.transport.peers;
  o.allow = config.transport.allow;
  o.routes.max_entries = config.transport.max_peers;
  return o;
}

Expected<std::unique_ptr<Daemon>, std::string> Daemon::start(const JausdConfig& config, boost::asio::io_context& io,
                                                             rt::LogFn log) {
  std::unique_ptr<Daemon> d(new Daemon(io, log));
  auto link = transport::UdpLink::open(io, d->runtime_, d->runtime_, link_options(config), log);
  if (!link) return unexpected(link.error());
  d->link_ = std::move(*link);

  node::NodeConfig nc;
  nc.subsystem = config.subsystem;
  nc.node = config.node;
  nc.dialect = config.dialect == "openjaus" ? wire::Dialect::openjaus : wire::Dialect::ra;
  nc.liveness.component_timeout = seconds(config.liveness.component_timeout_s);
  nc.liveness.node_timeout = seconds(config.liveness.node_timeout_s);
  nc.liveness.subsystem_timeout = seconds(config.liveness.subsystem_timeout_s);
  d->node_ = std::make_unique<node::Node>(nc, d->runtime_, d->runtime_, *d->link_, log);
  d->link_->on_packet([node = d->node_.get()](std::span<const std::uint8_t> packet) { node->receive(packet); });

  for (const auto& spec : config.components) {
    auto component = make_component(spec, config, *d->node_);
    if (!component) return unexpected("component kind '" + spec.kind + "' cannot be hosted by this build");
    const bool is_manager = spec.kind == "node_manager";
    auto& hosted = d->node_->add(std::move(component));
    if (is_manager) d->node_->set_node_manager(static_cast<rt::NodeManager*>(&hosted));
  }
  d->link_->start();
  log(rt::LogLevel::info, "node " + std::to_string(config.subsystem) + "." + std::to_string(config.node) +
                              " listening on " + transport::to_string(d->link_->local_endpoint()) + " (" +
                              std::string(transport::to_string(link_options(config).framing)) + ")");
  return d;
}

Daemon::~Daemon() { stop("daemon destroyed"); }

void Daemon::stop(const std::string& why) {
  if (stopped_ || !node_ || !link_) return;  // stopped, or never fully started
  stopped_ = true;
  // Safety: the node shuts every component down (platform commanded to stop)
  // while the link can still carry their last messages.
  node_->shutdown(why);
  const auto& n = node_->counters();
  const auto& l = link_->counters();
  log_(rt::LogLevel::info, "stopped (" + why + "): " + std::to_string(l.datagrams_received) + " datagrams in, " +
                               std::to_string(l.dropped_total()) + " dropped, " + std::to_string(n.delivered) +
                               " messages delivered, " + std::to_string(l.datagrams_sent) + " datagrams out");
  link_->close();
}

}  // namespace jausd
