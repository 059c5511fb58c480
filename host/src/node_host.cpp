#include "jaus/host/node_host.hpp"

#include <boost/asio/signal_set.hpp>
#include <csignal>

#include "jaus/clearpath/link.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

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
  // The hardware the configured components need, each made once.
  VehicleBackends backends;
  for (const auto& spec : h->config_.components) {
    const Hardware hardware = hardware_of(spec.kind);
    if (hardware == Hardware::vehicle && !h->vehicle_ && !h->clearpath_vehicle_) {
      if (h->config_.platform.kind == PlatformSettings::Kind::model) {
        h->vehicle_ = std::make_unique<components::SimulatedVehicle>(h->config_.vehicle, h->runtime_);
        backends.drive = h->vehicle_.get();
        backends.pose = h->vehicle_.get();
      } else {
        h->open_platform(io);
        h->clearpath_vehicle_ = std::make_unique<bridge::ClearpathVehicle>(*h->platform_, h->config_.platform.vehicle);
        backends.drive = h->clearpath_vehicle_.get();
        backends.pose = h->clearpath_vehicle_.get();
      }
    } else if (hardware == Hardware::cameras && !h->cameras_) {
      // The images are always the simulated cameras'; their mounts may be the platform's.
      h->cameras_ = std::make_unique<components::SimulatedCameras>(h->config_.cameras, h->runtime_);
      backends.cameras = h->cameras_.get();
      const auto& mounts = h->config_.platform.cameras;
      if (h->config_.platform.kind != PlatformSettings::Kind::model && !mounts.mounts.empty()) {
        if (auto ok = bridge::check_clearpath_cameras_config(h->config_.cameras.cameras, mounts); !ok)
          return unexpected(ok.error());
        h->open_platform(io);
        h->clearpath_cameras_ = std::make_unique<bridge::ClearpathCameras>(*h->platform_, h->runtime_, *h->cameras_, mounts);
        backends.cameras = h->clearpath_cameras_.get();
      }
    } else if (hardware == Hardware::arm && !h->arm_ && !h->clearpath_arm_) {
      const auto& joints = h->config_.platform.arm;
      if (h->config_.platform.kind != PlatformSettings::Kind::model && !joints.joints.empty()) {
        if (auto ok = bridge::check_clearpath_arm_config(h->config_.arm, joints); !ok) return unexpected(ok.error());
        h->open_platform(io);
        h->clearpath_arm_ = std::make_unique<bridge::ClearpathArm>(*h->platform_, h->runtime_, h->config_.arm, joints);
        backends.arm = h->clearpath_arm_.get();
      } else {
        h->arm_ = std::make_unique<components::SimulatedArm>(h->config_.arm, h->runtime_);
        backends.arm = h->arm_.get();
      }
    }
  }
  std::vector<std::pair<const ComponentSpec*, rt::Component*>> on_vehicle;
  for (const auto& spec : h->config_.components) {
    auto component = make_component(spec, h->config_.settings, *h->node_, backends);
    if (!component) return unexpected(component.error());
    rt::Component& added = h->node_->add(std::move(*component));
    const Hardware hardware = hardware_of(spec.kind);
    // Every component on the Clearpath platform shares its e-stop.
    if (hardware == Hardware::vehicle || (hardware == Hardware::cameras && h->clearpath_cameras_) ||
        (hardware == Hardware::arm && h->clearpath_arm_))
      on_vehicle.emplace_back(&spec, &added);
  }
  if (h->clearpath_vehicle_) h->mirror_emergencies(on_vehicle);
  h->link_->start();
  return h;
}

// The Clearpath platform's client: a link that reopens with backoff and never
// fails the node (a missing port is a link down, which the components report
// as Failure), or the simulated platform in this process.
void NodeHost::open_platform(boost::asio::io_context& io) {
  if (platform_) return;
  const auto& p = config_.platform;
  if (p.kind == PlatformSettings::Kind::clearpath_sim) {
    clearpath::sim::LoopbackConfig loopback;
    loopback.platform = p.sim;
    loopback.client = p.client;
    loopback.period = std::chrono::milliseconds(5);
    platform_client_ = std::make_unique<clearpath::sim::LoopbackClient>(runtime_, runtime_, loopback);
    log_(rt::LogLevel::info, "Clearpath platform: simulated in process");
  } else {
    auto link = std::make_unique<clearpath::ClearpathLink>(io, runtime_, runtime_, p.endpoint, p.client);
    link->start();
    platform_link_ = link.get();
    platform_client_ = std::move(link);
  }
  platform_ = std::make_unique<bridge::PlatformConnection>(*platform_client_, runtime_, log_);
}

// Safety, both ways between JAUS and the platform's own e-stop: the
// platform's e-stop or pause puts every component on the vehicle in Emergency
// until it clears; the primitive driver's Emergency sets the platform's
// emergency flag when `emergency_flags` is configured.
void NodeHost::mirror_emergencies(const std::vector<std::pair<const ComponentSpec*, rt::Component*>>& on_vehicle) {
  std::vector<rt::Component*> components;
  for (const auto& [spec, component] : on_vehicle) components.push_back(component);
  clearpath_vehicle_->on_platform_emergency([components](const std::optional<std::string>& why) {
    for (auto* c : components) {
      if (why) c->hold_hardware_emergency(*why);
      else c->release_hardware_emergency("the platform's e-stop cleared");
    }
  });
  for (const auto& [spec, component] : on_vehicle) {
    if (spec->kind != "primitive_driver") continue;
    component->on_state_change([vehicle = clearpath_vehicle_.get()](rt::PrimaryStatus before, rt::PrimaryStatus after) {
      if (after == rt::PrimaryStatus::emergency) vehicle->command_emergency(true);
      else if (before == rt::PrimaryStatus::emergency) vehicle->command_emergency(false);
    });
  }
}

NodeHost::~NodeHost() { stop("host destroyed"); }

namespace {
std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    default: return "signal " + std::to_string(signal);
  }
}
}  // namespace

std::optional<std::string> NodeHost::run(boost::asio::io_context& io) {
  // Every signal that asks a process to end (systemctl stop, Ctrl-C, Ctrl-\,
  // a closed terminal) ends it the same orderly way.
  boost::asio::signal_set signals(io, SIGINT, SIGTERM, SIGHUP);
  signals.add(SIGQUIT);
  signals.async_wait([&](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    stop(signal_name(signal));
    io.stop();
  });
  std::optional<std::string> failure;
  try {
    io.run();
  } catch (const std::exception& e) {
    // Nothing in the libraries throws, but should anything escape the loop
    // (memory exhausted, a bug), the platform still stops before the exit.
    failure = e.what();
    log_(rt::LogLevel::error, "event loop failed: " + *failure + "; stopping");
  } catch (...) {
    failure = "unknown exception";
    log_(rt::LogLevel::error, "event loop failed: unknown exception; stopping");
  }
  stop(failure ? "exception: " + *failure : std::string("event loop ended"));
  return failure;
}

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
  // The components are gone: the platform's e-stop has nobody left to hold.
  if (clearpath_vehicle_) clearpath_vehicle_->on_platform_emergency({});
  // ...and the stop's zero setpoint goes out now, before a process exits
  // without running its io_context again.
  if (platform_link_ != nullptr) platform_link_->flush();
  const auto& n = node_->counters();
  const auto& l = link_->counters();
  std::string reasons;
  for (std::size_t r = 0; r < l.dropped.size(); ++r)
    if (l.dropped[r] > 0)
      reasons += std::string(reasons.empty() ? " (" : ", ") + std::to_string(l.dropped[r]) + " " +
                 std::string(transport::to_string(static_cast<transport::DropReason>(r)));
  if (!reasons.empty()) reasons += ")";
  log_(rt::LogLevel::info, "stopped (" + why + "): " + std::to_string(l.datagrams_received) + " datagrams in, " +
                               std::to_string(l.dropped_total()) + " dropped" + reasons + ", " +
                               std::to_string(n.delivered) + " messages delivered, " +
                               std::to_string(l.datagrams_sent) + " datagrams out");
  link_->close();
}

}  // namespace jaus::host
