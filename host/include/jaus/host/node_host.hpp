// One JAUS node built from a configuration: the node and its components,
// either opened on the network (a UDP link on the caller's io_context, with
// the io_context's clock and timers, AsioRuntime) or attached to a link,
// clock and scheduler the caller injects (a memory link under virtual time in
// tests). jausd is an opened NodeHost and the signals that stop it; the OCU
// is a NodeHost with one more component; tests host nodes the same way.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/components/arm_config.hpp"
#include "jaus/components/camera_config.hpp"
#include "jaus/components/simulated_vehicle.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/drop_summary.hpp"
#include "jaus/host/emergency_holds.hpp"
#include "jaus/host/platform.hpp"
#include "jaus/host/platform_kinds.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/node/budgeted_link.hpp"
#include "jaus/node/node.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::host {

struct HostConfig {
  node::NodeConfig node;            // subsystem and node IDs, dialect, liveness, queues
  transport::UdpLinkOptions link;   // bind, framing, peers, ...; its IDs are the node's
  // The rate the node may send at, stops first (a field radio's); off by
  // default (node/budgeted_link.hpp).
  node::SendBudgetOptions send_budget;
  ComponentSettings settings;       // what every component shares, the node manager's identity
  std::vector<ComponentSpec> components;
  // The vehicle the mobility components drive and read, made when one of
  // them is configured, on the host's clock.
  components::SimulatedVehicleConfig vehicle;
  // The visual sensor's cameras and the manipulator's arm, simulated on the
  // host's clock when those components are configured.
  components::VisualSensorConfig cameras;
  components::ArmConfig arm;
  // What carries the vehicle: a platform kind by name (platform_kinds.hpp),
  // the simulated vehicle above by default (`model`), or e.g. a Clearpath
  // platform through the bridge (clearpath_platform.hpp).
  PlatformSettings platform;
  // How far Set Emergency reaches, and where its holds persist (emergency_holds.hpp).
  EmergencySettings emergency;
  // An operator's own node (jausctl, jaus-console): it takes no commands and
  // holds no stop, so it persists no emergency holds (it must never write a
  // vehicle's holds file) and says nothing of a vehicle's posture (an open
  // bind, holds not persisted): those warnings are jausd's (issue 49).
  bool operator_unit = false;
  // The JSS face (SAE JAUS on the same port, docs/jss.md): off unless
  // enabled. Its identification and controller timeout are the node's
  // (`settings`), copied when the host is made.
  // (Not `{.enabled = false}`: gcc's -Wmissing-field-initializers refuses a partial designated list.)
  jss_face::FaceConfig jss = [] {
    jss_face::FaceConfig off;
    off.enabled = false;
    return off;
  }();
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

  // The JSS face when `jss.enabled`, else nullptr. An opened host's face
  // sends through the UDP link (UdpLink::transmit_jss) and receives what it
  // hands on; an attached host's face sends through set_jss_sender's function
  // (nothing until one is set) and receives what the caller gives
  // jss_face()->receive().
  jss_face::JssFace* jss_face() { return jss_face_.get(); }
  const jss_face::JssFace* jss_face() const { return jss_face_.get(); }
  void set_jss_sender(jss_face::JssFace::DatagramSender sender) { jss_sender_ = std::move(sender); }

  // Orderly stop. Safety: every component goes to Shutdown first, which
  // commands its platform to stop (Component::enforce_stop), drops control
  // and ends its service connections, with those messages sent while the
  // link is still open; then the link closes. Idempotent.
  void stop(const std::string& why);
  bool stopped() const { return stopped_; }

  // The local clear of emergency holds (jausd's SIGUSR1): every Set
  // Emergency holder of every component is cleared (the shared vehicle
  // latch, each component's own: sensors, communicator, node manager,
  // drivers), logged with who held what, and the platform's emergency flag
  // left by an earlier run is reclaimed.
  // The platform's own stops stay until it reports them clear. Returns how
  // many holds were cleared.
  std::size_t clear_emergency_holds_locally(const std::string& why);
  // The latch a component with hardware follows (nullptr for the others).
  const rt::EmergencyLatch* emergency_latch(const std::string& name) const;

  // Runs `io` (the one the host was opened on) until io.stop() or an
  // exception escaping a handler. Signals are the app's (jausd installs
  // them: a stop signal is stop() then io.stop(), SIGUSR1 the local clear).
  // Safety: whatever ends the loop, stop() runs before this returns, so every
  // component's stop path (platform commanded to stop) has run. The error:
  // the exception that ended the loop.
  Expected<void> run(boost::asio::io_context& io);

  const HostConfig& config() const { return config_; }
  node::Node& node() { return *node_; }
  const node::Node& node() const { return *node_; }
  // The send budget in front of the link; nullptr when none is set.
  const node::BudgetedLink* send_budget() const { return budgeted_link_.get(); }
  // The UDP link of an opened host; nullptr for an attached one.
  transport::UdpLink* udp_link() { return udp_link_.get(); }
  const transport::UdpLink* udp_link() const { return udp_link_.get(); }
  rt::Clock& clock() { return *clock_; }
  rt::Scheduler& scheduler() { return *scheduler_; }
  // The platform the components' hardware is on, as its kind made it (a
  // ModelPlatform, a ClearpathPlatform, ...), whose typed accessors reach
  // each backend; backends() is what the components were made with, by interface.
  Platform& platform() { return *platform_; }
  // The platform as its class (nullptr when it is another), e.g.
  // platform_as<ModelPlatform>()->vehicle().
  template <class P>
  P* platform_as() {
    return dynamic_cast<P*>(platform_.get());
  }
  const rt::Backends& backends() const { return backends_; }

 private:
  NodeHost(HostConfig config, rt::LogFn log);
  // What open() and attach() share: the node on `link`, then the hardware
  // and the components.
  void make_node(node::Link& link);
  // The face, once the node and its components exist (the face reads them).
  void make_jss_face(jss_face::JssFace::DatagramSender send);
  // Our node manager's JSS ID (the face's numbering of RA component 1).
  jss::JssId jss_node_manager_id() const;
  Expected<void> add_components(boost::asio::io_context* io);  // io: an opened host's
  // Reads the holds (refusing a state directory that cannot be written) and
  // binds each restored holder to its host (bind_restored_holders).
  Expected<void> restore_emergency_holds();
  void bind_restored_holders(PersistedHolds holds);
  // The JSS holders' alias slots and JSS routes, once the face exists.
  void rebind_jss_holders();
  rt::EmergencyLatch& latch_for(const ComponentSpec& spec);
  // The latch of a component without hardware: the host's, so that the local clear reaches it.
  rt::EmergencyLatch& unpersisted_latch_for(const ComponentSpec& spec);
  bool latch_configured(const std::string& name) const;  // a latch this configuration makes
  void schedule_persisting();
  void persist_emergency_holds();
  // Once a minute, one line of what was dropped since the last (nothing
  // dropped: no line). jausd's, not an operator unit's.
  void arm_drop_summary();
  // Who holds a latch, as persisted: dialect, ID and host of each holder.
  PersistedHold describe_for_persisting(const rt::EmergencyLatch& latch) const;
  void persisting_failed(const Error& error);
  void persisting_recovered();

  HostConfig config_;
  rt::LogFn log_;
  // An opened host's runtime on its io_context; an attached host has none.
  std::unique_ptr<transport::AsioRuntime> asio_runtime_;
  rt::Clock* clock_ = nullptr;
  rt::Scheduler* scheduler_ = nullptr;
  // Lifetimes: the emergency latches of the components with hardware are the
  // host's, made before and destroyed after every component and backend, so
  // nothing that outlives a component (the platform's e-stop, the holds
  // file) keeps a pointer to one. By name: "vehicle" or an address.
  std::map<std::string, std::unique_ptr<rt::EmergencyLatch>> latches_;
  // Those of the components without hardware (their holds are not persisted),
  // by "address (name)", for the local clear; same lifetime rule.
  std::map<std::string, std::unique_ptr<rt::EmergencyLatch>> unpersisted_latches_;
  std::optional<std::filesystem::path> holds_file_;
  // Restored holds by latch, each holder bound (its address restored) or
  // not (held as the latch's overflow: only the local clear releases it).
  struct RestoredHold {
    std::vector<Address> bound;
    bool overflowed = false;
  };
  std::map<std::string, RestoredHold> restored_holds_;
  struct JssBinding {
    std::uint8_t slot = 0;
    jss::JssId client_node;
    std::uint32_t host = 0;
  };
  std::vector<JssBinding> jss_bindings_;  // applied once the face exists
  bool holds_unreadable_ = false;
  PersistedHolds written_holds_;
  std::uint64_t holds_generation_ = 0;  // of the last write begun
  bool persist_posted_ = false;
  bool persisting_fails_ = false;  // the last write failed (said once per streak; clears refused meanwhile)
  rt::TimerId persist_retry_ = rt::kNoTimer;
  rt::TimerId drop_summary_ = rt::kNoTimer;
  DropCounts drops_seen_;  // at the last summary
  std::shared_ptr<char> alive_ = std::make_shared<char>(0);  // posted work runs only while the host lives
  std::unique_ptr<transport::UdpLink> udp_link_;  // an opened host's
  // The node's link when the face is on (around the UDP or the attached
  // link): declared after that link and before the node, which uses it.
  std::unique_ptr<jss_face::FaceLink> face_link_;
  // Around both when a send budget is set: what goes to JSS clients is held
  // to the rate too. After them, before the node.
  std::unique_ptr<node::BudgetedLink> budgeted_link_;
  // Declared before the node: components refer to its backends, so they outlive them.
  std::unique_ptr<Platform> platform_;
  rt::Backends backends_;  // what the components are made with: the platform's, by interface
  std::unique_ptr<node::Node> node_;
  // After the node: it refers to the node, and the node's shutdown (Reject
  // Component Control to aliases, ...) still goes through it. Destroyed
  // (detached first) right after stop(), before the node and the links.
  std::unique_ptr<jss_face::JssFace> jss_face_;
  jss_face::JssFace::DatagramSender jss_sender_;  // an attached host's
  Watcher watcher_;
  bool stopped_ = false;
};

}  // namespace jaus::host
