// One JAUS node built from a configuration: the node and its components,
// either opened on the network (a UDP link on the caller's io_context, with
// the io_context's clock and timers, AsioRuntime) or attached to a link,
// clock and scheduler the caller injects (a memory link under virtual time in
// tests). jausd is an opened NodeHost with signal handling; the OCU is a
// NodeHost with one more component; tests host nodes the same way.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/bridge/platform_emergency.hpp"
#include "jaus/clearpath/client.hpp"
#include "jaus/clearpath/link.hpp"
#include "jaus/components/frame_worker.hpp"
#include "jaus/components/simulated_arm.hpp"
#include "jaus/components/simulated_cameras.hpp"
#include "jaus/components/simulated_vehicle.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/emergency_holds.hpp"
#include "jaus/host/platform.hpp"
#include "jaus/node/node.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::host {

struct HostConfig {
  node::NodeConfig node;            // subsystem and node IDs, dialect, liveness, queues
  transport::UdpLinkOptions link;   // bind, framing, peers, ...; its IDs are the node's
  ComponentSettings settings;       // what every component shares, the node manager's identity
  std::vector<ComponentSpec> components;
  // The vehicle the mobility components drive and read, made when one of
  // them is configured, on the host's clock.
  components::SimulatedVehicleConfig vehicle;
  // The visual sensor's cameras and the manipulator's arm, simulated on the
  // host's clock when those components are configured.
  components::VisualSensorConfig cameras;
  components::ArmConfig arm;
  // What carries the vehicle: the simulated vehicle above (model), or a
  // Clearpath platform through the bridge.
  PlatformSettings platform;
  // How far Set Emergency reaches, and where its holds persist (emergency_holds.hpp).
  EmergencySettings emergency;
};

class NodeHost {
 public:
  // Sees every JAUS message the UDP link hands the node, before the node does
  // (tools watch heartbeats addressed to broadcast IDs this way). Opened hosts only.
  using Watcher = std::function<void(const PacketView& packet)>;

  // Opens the link, builds the node and every configured component, and starts
  // receiving. The error is one line, e.g. "127.0.0.1:3794 is already in use".
  static Expected<std::unique_ptr<NodeHost>> open(HostConfig config, boost::asio::io_context& io,
                                                  rt::LogFn log = {});
  // The same node and components on `link`, `clock` and `scheduler`, which
  // outlive the host; no io_context, no socket. The caller delivers what the
  // link receives to node() (e.g. MemoryLink::deliver_to(host->node())), so
  // watch() sees nothing. Frames are encoded on the scheduler (no thread), a
  // clearpath_sim platform runs on the clock and scheduler, and a real
  // Clearpath platform (it needs an io_context) is refused.
  static Expected<std::unique_ptr<NodeHost>> attach(HostConfig config, node::Link& link, rt::Clock& clock,
                                                    rt::Scheduler& scheduler, rt::LogFn log = {});
  // stop("host destroyed").
  ~NodeHost();
  NodeHost(const NodeHost&) = delete;
  NodeHost& operator=(const NodeHost&) = delete;

  // A component that no configuration names (an OCU's own, a test's).
  template <class C, class... Args>
  C& emplace(rt::ComponentConfig config, Args&&... args) {
    return node_->add_as(std::make_unique<C>(std::move(config), node_->environment(), std::forward<Args>(args)...));
  }
  // The settings every hosted component shares, with this name and address.
  rt::ComponentConfig component_config(std::string name, std::uint8_t component, std::uint8_t instance = 1) const;

  void watch(Watcher watcher) { watcher_ = std::move(watcher); }

  // Orderly stop. Safety: every component goes to Shutdown first, which
  // commands its platform to stop (Component::enforce_stop), drops control
  // and ends its service connections, with those messages sent while the
  // link is still open; then the link closes. Idempotent.
  void stop(const std::string& why);
  bool stopped() const { return stopped_; }

  // The local clear of emergency holds (SIGUSR1 in run()): every Set
  // Emergency holder of every latch is cleared, logged with what each held,
  // and the platform's emergency flag left by an earlier run is reclaimed.
  // The platform's own stops stay until it reports them clear. Returns how
  // many holds were cleared.
  std::size_t clear_emergency_holds_locally(const std::string& why);
  // The latch a component with hardware follows (nullptr for the others).
  const rt::EmergencyLatch* emergency_latch(const std::string& name) const;

  // Runs `io` (the one the host was opened on) until a stop signal (SIGINT,
  // SIGTERM, SIGHUP, SIGQUIT), io.stop() or an exception escaping a handler;
  // SIGUSR1 is the local clear of emergency holds.
  // Safety: whatever ends the loop, stop() runs before this returns, so every
  // component's stop path (platform commanded to stop) has run. Returns the
  // exception's message when one ended the loop.
  std::optional<std::string> run(boost::asio::io_context& io);

  const HostConfig& config() const { return config_; }
  node::Node& node() { return *node_; }
  const node::Node& node() const { return *node_; }
  // The UDP link of an opened host; nullptr for an attached one.
  transport::UdpLink* udp_link() { return udp_link_.get(); }
  const transport::UdpLink* udp_link() const { return udp_link_.get(); }
  rt::Clock& clock() { return *clock_; }
  rt::Scheduler& scheduler() { return *scheduler_; }
  // The simulated hardware, when a configured component needs it.
  components::SimulatedVehicle* vehicle() { return vehicle_.get(); }
  components::SimulatedCameras* cameras() { return cameras_.get(); }
  components::FrameWorker* frame_worker() { return frame_worker_.get(); }
  components::SimulatedArm* arm() { return arm_.get(); }
  // The Clearpath platform, when the configuration names one: its client
  // (ClearpathLink or, for clearpath_sim, sim::LoopbackClient) and the
  // bridge's backend of the mobility components.
  clearpath::Client* platform_client() { return platform_client_.get(); }
  clearpath::ClearpathLink* platform_link() { return platform_link_; }  // a real link (not clearpath_sim)
  bridge::PlatformConnection* platform() { return platform_.get(); }
  bridge::ClearpathVehicle* clearpath_vehicle() { return clearpath_vehicle_.get(); }
  bridge::ClearpathCameras* clearpath_cameras() { return clearpath_cameras_.get(); }
  bridge::ClearpathArm* clearpath_arm() { return clearpath_arm_.get(); }

 private:
  NodeHost(HostConfig config, rt::LogFn log);
  // What open() and attach() share: the node on `link`, then the hardware
  // and the components.
  void make_node(node::Link& link);
  Expected<void> add_components();
  // Makes the backend of a hardware interface (rt::Backends names) once, on
  // the configured platform, and offers it in backends_; an interface the
  // platform lacks is left out (the kind that needs it says so).
  Expected<void> provide(std::string_view interface);
  void open_platform();
  void restore_emergency_holds();
  rt::EmergencyLatch& latch_for(const ComponentSpec& spec);
  bool latch_configured(const std::string& name) const;  // a latch this configuration makes
  void schedule_persisting();
  void persist_emergency_holds();

  HostConfig config_;
  rt::LogFn log_;
  // An opened host's loop and runtime; an attached host has neither.
  boost::asio::io_context* io_ = nullptr;
  std::unique_ptr<transport::AsioRuntime> asio_runtime_;
  rt::Clock* clock_ = nullptr;
  rt::Scheduler* scheduler_ = nullptr;
  // Lifetimes: the emergency latches of the components with hardware are the
  // host's, made before and destroyed after every component and backend, so
  // nothing that outlives a component (the platform's e-stop, the holds
  // file) keeps a pointer to one. By name: "vehicle" or an address.
  std::map<std::string, std::unique_ptr<rt::EmergencyLatch>> latches_;
  std::vector<rt::EmergencyLatch*> platform_latches_;  // of components on the Clearpath platform
  rt::EmergencyLatch* driver_latch_ = nullptr;         // the platform's emergency flag mirrors it
  std::optional<std::filesystem::path> holds_file_;
  PersistedHolds restored_holds_;
  bool holds_unreadable_ = false;
  PersistedHolds written_holds_;
  bool persist_posted_ = false;
  bool persisting_fails_ = false;  // the last write failed (said once per streak)
  std::shared_ptr<char> alive_ = std::make_shared<char>(0);  // posted work runs only while the host lives
  std::unique_ptr<transport::UdpLink> udp_link_;  // an opened host's
  // The visual sensor's frames are captured and encoded off the loop: on a
  // thread of their own in an opened host (stop(), and so the destructor,
  // joins it before the components and cameras go, dropping what is
  // queued), on the scheduler in an attached one.
  std::unique_ptr<components::FrameWorker> frame_worker_;
  components::ThreadFrameWorker* frame_thread_ = nullptr;  // frame_worker_, when it is a thread
  // Declared before the node: components refer to them, so they outlive them.
  std::unique_ptr<components::SimulatedVehicle> vehicle_;
  std::unique_ptr<components::SimulatedCameras> cameras_;
  std::unique_ptr<components::SimulatedArm> arm_;
  std::unique_ptr<clearpath::Client> platform_client_;
  clearpath::ClearpathLink* platform_link_ = nullptr;  // platform_client_, when it is a real link
  std::unique_ptr<bridge::PlatformConnection> platform_;
  std::unique_ptr<bridge::ClearpathVehicle> clearpath_vehicle_;
  std::unique_ptr<bridge::ClearpathCameras> clearpath_cameras_;
  std::unique_ptr<bridge::ClearpathArm> clearpath_arm_;
  std::unique_ptr<bridge::PlatformEmergencyMirror> platform_emergency_;  // the platform's stops <-> the latches
  rt::Backends backends_;  // what the components are made with: the above, by interface
  std::vector<std::string_view> platform_interfaces_;  // those of backends_ the Clearpath platform carries
  std::unique_ptr<node::Node> node_;
  Watcher watcher_;
  bool stopped_ = false;
};

}  // namespace jaus::host
