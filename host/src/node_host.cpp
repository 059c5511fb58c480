#include "jaus/host/node_host.hpp"

namespace jaus::host {

NodeHost::NodeHost(HostConfig config, boost::asio::io_context& io, rt::LogFn log)
    : config_(std::move(config)), runtime_(io), log_(log ? std::move(log) : rt::silent_log()) {
  config_.link.subsystem = config_.node.subsystem;
  config_.link.node = config_.node.node;
}

Expected<std::unique_ptr<NodeHost>> NodeHost::open(HostConfig config, boost::asio::io_context& io, rt::LogFn log) {
  std::unique_ptr<NodeHost> h(new NodeHost(std::move(config), io, std::move(log)));
  auto link = transport::UdpLink::open(io, h->runtime_, h->runtime_, h->config_.link, h->log_);
  if (!link) return unexpected(link.error());
  h->link_ = std::move(*link);
  h->node_ = std::make_unique<node::Node>(h->config_.node, h->runtime_, h->runtime_, *h->link_, h->log_);
  h->link_->on_packet([host = h.get()](const PacketView& packet, transport::Framing) {
    if (host->watcher_) host->watcher_(packet);
    host->node_->receive(packet);
  });
  // The simulated hardware the configured components need, each made once.
  VehicleBackends backends;
  for (const auto& spec : h->config_.components) {
    const Hardware hardware = hardware_of(spec.kind);
    if (hardware == Hardware::vehicle && !h->vehicle_) {
      h->vehicle_ = std::make_unique<components::SimulatedVehicle>(h->config_.vehicle, h->runtime_);
      backends.drive = h->vehicle_.get();
      backends.pose = h->vehicle_.get();
    } else if (hardware == Hardware::cameras && !h->cameras_) {
      h->cameras_ = std::make_unique<components::SimulatedCameras>(h->config_.cameras, h->runtime_);
      backends.cameras = h->cameras_.get();
    } else if (hardware == Hardware::arm && !h->arm_) {
      h->arm_ = std::make_unique<components::SimulatedArm>(h->config_.arm, h->runtime_);
      backends.arm = h->arm_.get();
    }
  }
  for (const auto& spec : h->config_.components) {
    auto component = make_component(spec, h->config_.settings, *h->node_, backends);
    if (!component) return unexpected(component.error());
    h->node_->add(std::move(*component));
  }
  h->link_->start();
  return h;
}

NodeHost::~NodeHost() { stop("host destroyed"); }

rt::ComponentConfig NodeHost::component_config(std::string name, std::uint8_t component, std::uint8_t instance) const {
  rt::ComponentConfig c = config_.settings.defaults;
  c.name = std::move(name);
  c.address = Address{config_.node.subsystem, config_.node.node, component, instance};
  return c;
}

void NodeHost::stop(const std::string& why) {
  if (stopped_ || !node_ || !link_) return;  // stopped, or never fully opened
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

}  // namespace jaus::host
