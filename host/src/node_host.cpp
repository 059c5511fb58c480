#include "jaus/host/node_host.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <algorithm>
#include <csignal>

#include "jaus/clearpath/link.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace jaus::host {

NodeHost::NodeHost(HostConfig config, rt::LogFn log)
    : config_(std::move(config)), log_(log ? std::move(log) : rt::silent_log()) {
  config_.link.subsystem = config_.node.subsystem;
  config_.link.node = config_.node.node;
}

Expected<std::unique_ptr<NodeHost>> NodeHost::open(HostConfig config, boost::asio::io_context& io, rt::LogFn log) {
  std::unique_ptr<NodeHost> h(new NodeHost(std::move(config), std::move(log)));
  h->io_ = &io;
  h->asio_runtime_ = std::make_unique<transport::AsioRuntime>(io);
  h->clock_ = h->asio_runtime_.get();
  h->scheduler_ = h->asio_runtime_.get();
  auto link = transport::UdpLink::open(io, *h->asio_runtime_, *h->asio_runtime_, h->config_.link, h->log_);
  if (!link) return unexpected(link.error());
  h->udp_link_ = std::move(*link);
  h->make_node(*h->udp_link_);
  h->udp_link_->on_packet([host = h.get()](const PacketView& packet, transport::Framing, rt::SenderStanding standing) {
    if (host->watcher_) host->watcher_(packet);
    host->node_->receive(packet, standing);
  });
  // No hijack (issue 28): an ID that holds control, an emergency or a
  // service connection here keeps its route to its host while it does. The
  // link asks only on a claim from another address, never per datagram.
  h->udp_link_->pin_routes_while([node = h->node_.get()](std::uint8_t subsystem, std::uint8_t node_id) {
    return node->holds_state_for(subsystem, node_id);
  });
  if (auto added = h->add_components(); !added) return unexpected(added.error());
  h->udp_link_->start();
  return h;
}

Expected<std::unique_ptr<NodeHost>> NodeHost::attach(HostConfig config, node::Link& link, rt::Clock& clock,
                                                     rt::Scheduler& scheduler, rt::LogFn log) {
  if (config.platform.kind == PlatformSettings::Kind::clearpath)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "a Clearpath platform at an endpoint needs an opened host (NodeHost::open, on an "
                            "io_context); an attached host takes model or clearpath_sim"));
  std::unique_ptr<NodeHost> h(new NodeHost(std::move(config), std::move(log)));
  h->clock_ = &clock;
  h->scheduler_ = &scheduler;
  h->make_node(link);
  if (auto added = h->add_components(); !added) return unexpected(added.error());
  return h;
}

void NodeHost::make_node(node::Link& link) {
  node_ = std::make_unique<node::Node>(config_.node, *clock_, *scheduler_, link, log_);
}

Expected<void> NodeHost::add_components() {
  // The hardware the configured components need (each kind says which
  // interfaces), each made once on the configured platform.
  for (const auto& spec : config_.components)
    if (const ComponentKind* kind = find_component_kind(spec.kind))
      for (const std::string_view interface : kind->needs)
        if (auto provided = provide(interface); !provided) return unexpected(provided.error());
  restore_emergency_holds();
  for (const auto& spec : config_.components) {
    auto component = make_component(spec, config_.settings, *node_, backends_);
    if (!component) return unexpected(component.error());
    const ComponentKind& kind = *find_component_kind(spec.kind);  // made, so known
    if (!kind.needs.empty()) {
      const auto needs = [&](std::string_view interface) {
        return std::find(kind.needs.begin(), kind.needs.end(), interface) != kind.needs.end();
      };
      // Before it starts: a hold restored from the file puts it in Emergency at once.
      rt::EmergencyLatch& latch = latch_for(spec);
      (*component)->share_emergency(latch);
      // The platform's emergency flag mirrors the latch of what drives the vehicle.
      if (needs(components::Drive::kInterface)) driver_latch_ = &latch;
      // Every component on the Clearpath platform is held by its e-stop.
      const bool on_platform = std::any_of(platform_interfaces_.begin(), platform_interfaces_.end(), needs);
      if (on_platform &&
          std::find(platform_latches_.begin(), platform_latches_.end(), &latch) == platform_latches_.end())
        platform_latches_.push_back(&latch);
    }
    node_->add(std::move(*component));
  }
  persist_emergency_holds();
  if (clearpath_vehicle_)
    platform_emergency_ =
        std::make_unique<bridge::PlatformEmergencyMirror>(*clearpath_vehicle_, platform_latches_, driver_latch_);
  return {};
}

// ---- emergency holds (emergency_holds.hpp) -------------------------------------

void NodeHost::restore_emergency_holds() {
  holds_file_ = emergency_holds_file(config_.emergency);
  if (!holds_file_) {
    log_(rt::LogLevel::warn, "emergency holds are not persisted (no state_directory): a restart forgets them");
    return;
  }
  auto holds = read_emergency_holds(*holds_file_);
  if (!holds) {
    // Fail safe: who held what is unknown, so everything is held until the local clear.
    holds_unreadable_ = true;
    log_(rt::LogLevel::error, "emergency holds unreadable (" + holds.error().message() +
                                  "): every component with hardware is held in Emergency until SIGUSR1 clears it");
    return;
  }
  restored_holds_ = std::move(*holds);
  for (const auto& [latch, hold] : restored_holds_) {
    std::string who;
    for (const auto& a : hold.holders) who += (who.empty() ? "" : ", ") + a.to_string();
    if (hold.overflowed) who += std::string(who.empty() ? "" : ", ") + "senders beyond the recorded ones";
    log_(rt::LogLevel::warn, "emergency held since before the restart (" + latch + "): " + who);
  }
}

rt::EmergencyLatch& NodeHost::latch_for(const ComponentSpec& spec) {
  const std::string name =
      config_.emergency.scope == EmergencyScope::vehicle && moves_hardware(spec.kind)
          ? std::string("vehicle")
          : Address{config_.node.subsystem, config_.node.node, spec.id, spec.instance}.to_string();
  auto& latch = latches_[name];
  if (latch) return *latch;
  latch = std::make_unique<rt::EmergencyLatch>();
  if (holds_unreadable_) latch->restore({}, /*overflowed=*/true);
  // A hold of a latch this configuration no longer has (the scope changed)
  // holds every latch: nobody is forgotten.
  for (const auto& [held, hold] : restored_holds_)
    if (held == name || !latch_configured(held)) latch->restore(hold.holders, hold.overflowed);
  // Written right after the change has taken effect: the stop first, then the disk.
  latch->observe([this](const rt::EmergencyLatch&) { schedule_persisting(); });
  return *latch;
}

bool NodeHost::latch_configured(const std::string& name) const {
  if (name == "vehicle") return config_.emergency.scope == EmergencyScope::vehicle;
  for (const auto& c : config_.components)
    if (has_hardware(c.kind) &&
        Address{config_.node.subsystem, config_.node.node, c.id, c.instance}.to_string() == name)
      return true;
  return false;
}

// A file write (and its fsync) never delays a stop: the members of a latch
// follow its change in the same call, the write comes once that handler is
// done, and a flood of new holders in one batch is one write. Should jausd die
// in between, the platform's emergency flag it left is held as the platform's
// own stop by the next run (fail safe).
void NodeHost::schedule_persisting() {
  if (!holds_file_ || persist_posted_) return;
  persist_posted_ = true;
  scheduler_->post([this, alive = std::weak_ptr<char>(alive_)] {
    if (alive.expired()) return;
    persist_posted_ = false;
    persist_emergency_holds();
  });
}

void NodeHost::persist_emergency_holds() {
  if (!holds_file_) return;
  PersistedHolds holds;
  for (const auto& [name, latch] : latches_)
    if (latch->held_by_jaus()) holds[name] = PersistedHold{latch->holders(), latch->overflowed()};
  if (holds == written_holds_) return;  // a local hold changed, or nothing did
  if (auto written = write_emergency_holds(*holds_file_, holds); !written) {
    // Once per failing streak: a peer toggling Set/Clear Emergency on a broken disk writes one line, not one a toggle.
    if (!persisting_fails_)
      log_(rt::LogLevel::error, "emergency holds not persisted: " + written.error().message() + " (retried at every change)");
    persisting_fails_ = true;
    return;
  }
  if (persisting_fails_) log_(rt::LogLevel::info, "emergency holds persisted again");
  persisting_fails_ = false;
  written_holds_ = std::move(holds);
}

std::size_t NodeHost::clear_emergency_holds_locally(const std::string& why) {
  std::size_t cleared = 0;
  for (const auto& [name, latch] : latches_) {
    if (!latch->held_by_jaus()) continue;
    const std::string held = latch->describe_holders();
    const std::size_t n = latch->clear_jaus_holders();
    cleared += n;
    log_(rt::LogLevel::warn, "emergency holds cleared locally (" + why + "), " + name + ": " + held);
  }
  // What an earlier run left on the platform is ours to clear too; a hardware stop stays.
  if (clearpath_vehicle_) clearpath_vehicle_->reclaim_safety_bits();
  if (cleared == 0) log_(rt::LogLevel::info, "local clear of emergency holds (" + why + "): none held");
  return cleared;
}

const rt::EmergencyLatch* NodeHost::emergency_latch(const std::string& name) const {
  const auto it = latches_.find(name);
  return it == latches_.end() ? nullptr : it->second.get();
}

// The platform's backend of each hardware interface: `model` makes the
// components' own simulations (vehicle, cameras, arm), `clearpath` and
// `clearpath_sim` the bridge's backends on one PlatformConnection (the
// images stay the simulated cameras'; a camera mount or an arm joint not
// mapped to the platform stays simulated).
Expected<void> NodeHost::provide(std::string_view interface) {
  const bool model = config_.platform.kind == PlatformSettings::Kind::model;
  if (interface == components::Drive::kInterface || interface == components::PoseSource::kInterface) {
    if (vehicle_ || clearpath_vehicle_) return {};
    components::Drive* drive = nullptr;
    components::PoseSource* pose = nullptr;
    if (model) {
      vehicle_ = std::make_unique<components::SimulatedVehicle>(config_.vehicle, *clock_);
      drive = vehicle_.get();
      pose = vehicle_.get();
    } else {
      open_platform();
      clearpath_vehicle_ = std::make_unique<bridge::ClearpathVehicle>(*platform_, config_.platform.vehicle);
      drive = clearpath_vehicle_.get();
      pose = clearpath_vehicle_.get();
      platform_interfaces_.push_back(components::Drive::kInterface);
      platform_interfaces_.push_back(components::PoseSource::kInterface);
    }
    backends_.offer<components::Drive>(drive);
    backends_.offer<components::PoseSource>(pose);
  } else if (interface == components::Cameras::kInterface) {
    if (cameras_) return {};
    // The images are always the simulated cameras'; their mounts may be the platform's.
    cameras_ = std::make_unique<components::SimulatedCameras>(config_.cameras, *clock_);
    backends_.offer<components::Cameras>(cameras_.get());
    backends_.offer<components::Cameras>("camera_images", cameras_.get());
    if (io_ != nullptr) {
      // Frames are encoded on a thread of their own; boost::asio::post (not
      // AsioRuntime::post, which is the loop's alone) brings each back.
      auto thread = std::make_unique<components::ThreadFrameWorker>(
          [io = io_](std::function<void()> fn) { boost::asio::post(*io, std::move(fn)); });
      frame_thread_ = thread.get();
      frame_worker_ = std::move(thread);
    } else {
      frame_worker_ = std::make_unique<components::ScheduledFrameWorker>(*scheduler_, *clock_);
    }
    backends_.offer<components::FrameWorker>(frame_worker_.get());
    const auto& mounts = config_.platform.cameras;
    if (!model && !mounts.mounts.empty()) {
      if (auto ok = bridge::check_clearpath_cameras_config(config_.cameras.cameras, mounts); !ok) return unexpected(ok.error());
      open_platform();
      clearpath_cameras_ = std::make_unique<bridge::ClearpathCameras>(*platform_, *scheduler_, *cameras_, mounts);
      backends_.offer<components::Cameras>(clearpath_cameras_.get());
      platform_interfaces_.push_back(components::Cameras::kInterface);
    }
  } else if (interface == components::ManipulatorArm::kInterface) {
    if (arm_ || clearpath_arm_) return {};
    const auto& joints = config_.platform.arm;
    if (!model && !joints.joints.empty()) {
      if (auto ok = bridge::check_clearpath_arm_config(config_.arm, joints); !ok) return unexpected(ok.error());
      open_platform();
      clearpath_arm_ = std::make_unique<bridge::ClearpathArm>(*platform_, *scheduler_, config_.arm, joints);
      backends_.offer<components::ManipulatorArm>(clearpath_arm_.get());
      platform_interfaces_.push_back(components::ManipulatorArm::kInterface);
    } else {
      arm_ = std::make_unique<components::SimulatedArm>(config_.arm, *clock_);
      backends_.offer<components::ManipulatorArm>(arm_.get());
    }
  }
  // Anything else this platform does not have: the kind that needs it says so.
  return {};
}

// The Clearpath platform's client: a link that reopens with backoff and never
// fails the node (a missing port is a link down, which the components report
// as Failure), or the simulated platform in this process.
void NodeHost::open_platform() {
  if (platform_) return;
  const auto& p = config_.platform;
  if (p.kind == PlatformSettings::Kind::clearpath_sim) {
    clearpath::sim::LoopbackConfig loopback;
    loopback.platform = p.sim;
    loopback.client = p.client;
    loopback.period = std::chrono::milliseconds(5);
    platform_client_ = std::make_unique<clearpath::sim::LoopbackClient>(*clock_, *scheduler_, loopback);
    log_(rt::LogLevel::info, "Clearpath platform: simulated in process");
  } else {
    // attach() refuses a real platform: an opened host has the io_context.
    auto link = std::make_unique<clearpath::ClearpathLink>(*io_, *clock_, *scheduler_, p.endpoint, p.client);
    link->start();
    platform_link_ = link.get();
    platform_client_ = std::move(link);
  }
  platform_ = std::make_unique<bridge::PlatformConnection>(*platform_client_, *clock_, log_);
}

NodeHost::~NodeHost() {
  stop("host destroyed");
  if (frame_thread_ != nullptr) frame_thread_->stop();  // a host that never fully opened: before its cameras go
}

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
  // The local clear of emergency holds: only someone on the vehicle can send it.
  boost::asio::signal_set local_clear(io, SIGUSR1);
  std::function<void()> wait_for_local_clear = [&] {
    local_clear.async_wait([&](const boost::system::error_code& ec, int) {
      if (ec || stopped_) return;
      clear_emergency_holds_locally("SIGUSR1");
      wait_for_local_clear();
    });
  };
  wait_for_local_clear();
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
  if (stopped_ || !node_) return;  // stopped, or never fully opened
  stopped_ = true;
  // Safety: the node shuts every component down (platform commanded to stop)
  // while the link can still carry their last messages.
  node_->shutdown(why);
  // No frame is wanted after Shutdown: the worker's thread ends here, before
  // anything it was given could go.
  if (frame_thread_ != nullptr) frame_thread_->stop();
  persist_emergency_holds();  // a change still waiting for the loop
  // ...and the stop's zero setpoint goes out now, before a process exits
  // without running its io_context again.
  if (platform_link_ != nullptr) platform_link_->flush();
  const auto& n = node_->counters();
  if (!udp_link_) {
    log_(rt::LogLevel::info, "stopped (" + why + "): " + std::to_string(n.delivered) + " messages delivered");
    return;
  }
  const auto& l = udp_link_->counters();
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
  udp_link_->close();
}

}  // namespace jaus::host
