// Configuration of the node daemon jausd: a YAML file -> JausdConfig. Plain
// data only (no sockets, no runtime objects); main.cpp maps it onto the node,
// its components and the transport. Every key has a default, so an empty file
// is a valid configuration. A bad file gives one error, "file:line: what is
// wrong"; nothing is silently ignored. docs/configuration.md is the reference.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "platform_config.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/components/arm_config.hpp"
#include "jaus/components/camera_config.hpp"
#include "jaus/components/simulated_vehicle.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/component_plugins.hpp"
#include "jaus/host/emergency_holds.hpp"
#include "jaus/transport/ipv4.hpp"
#include "jaus/transport/peer.hpp"

namespace jausd {

// Addresses, networks, framings and peers are the transport's own values
// (jaus/transport/ipv4.hpp, peer.hpp), read with jaus::transport::parse_endpoint
// and parse_cidr, so UdpLinkOptions takes them as they are.
struct TransportConfig {
  jaus::transport::Ipv4Endpoint bind{0, jaus::transport::kJausPort};  // 0.0.0.0:3794
  jaus::transport::Framing framing = jaus::transport::Framing::opc;   // for peers not heard from yet
  // Where broadcasts go and whose datagrams are heard: the group RA 3.x
  // implementations share on the LAN (OpenJAUS's 224.1.0.1:3794), so the
  // node finds them and is found with no configuration; absent = none.
  std::optional<jaus::transport::Ipv4Endpoint> multicast =
      jaus::transport::Ipv4Endpoint{0xE0010001, jaus::transport::kJausPort};  // 224.1.0.1:3794
  // The group's framing: JUDP, what the RA implementations on 224.1.0.1 read.
  jaus::transport::Framing multicast_framing = jaus::transport::Framing::judp;
  bool broadcast_to_peers = true;                  // broadcasts also go to every known peer
  bool relay = false;  // messages for other subsystems sent on to where their node was heard
  std::vector<jaus::transport::StaticPeer> peers;  // known from the start (no discovery needed)
  std::vector<jaus::transport::Cidr> allow;        // sources that may talk to the node; empty = everyone
  // Hosts that may take control and change the node's state (others may
  // query, subscribe and stop it): these networks, and with control_from_local
  // the machine's own networks (its interfaces' subnets and 127.0.0.0/8, read
  // when jausd starts). Both empty: every allowed host (an open posture).
  std::vector<jaus::transport::Cidr> control_from;
  bool control_from_local = true;  // the `local` entry; the default is [local]
  // Replies larger than what a peer sent go only to endpoints that answered a
  // challenge (no amplification toward a forged source address).
  bool verify_endpoints = true;
  // What an endpoint that has not answered a challenge may be sent beyond
  // what it sent (issue 43; jaus/transport/amplification_guard.hpp): per
  // endpoint a token bucket, all such endpoints together a second one.
  std::size_t unverified_burst_bytes = 4096;
  std::size_t unverified_bytes_per_second = 1024;
  std::size_t unverified_total_burst_bytes = 32768;
  std::size_t unverified_total_bytes_per_second = 16384;
  std::size_t max_peers = 256;  // peers learnt from traffic remembered at once (static ones come on top)
  // A field radio's rate: the node sends no faster, stops first and images
  // last (jaus/node/budgeted_link.hpp). 0: no budget, everything at once.
  std::uint64_t send_rate_kbit = 0;
  std::size_t send_queue_bytes = 256 * 1024;  // what may wait, per class
  std::size_t receive_buffer_bytes = 1 << 20;  // SO_RCVBUF asked (the kernel caps it); 0: the system's default
};

using ComponentSpec = jaus::host::ComponentSpec;  // kinds and options: jaus/host/component_kinds.hpp

struct ServiceConnectionSettings {  // per component, see jaus::rt::ServiceConnectionLimits
  double max_rate_hz = 1092;        // confirmed rates are capped at this
  std::size_t max_connections = 64;
  double max_total_rate_hz = 4000;  // reports a second of all of a component's inform SCs
  double deadman_periods = 3;       // a command SC is lost after this many silent periods...
  double deadman_minimum_s = 0.2;   // ...never sooner than this...
  double deadman_maximum_s = 1.0;   // ...and never later than this
};

struct LivenessSettings {  // peers unheard this long are forgotten
  double component_timeout_s = 3;
  double node_timeout_s = 5;
  double subsystem_timeout_s = 5;
  // Peers (subsystems, nodes, components) remembered at once; newcomers
  // beyond it are not recorded (and may not take control) until room frees.
  std::size_t max_entries = 1024;
};

// The JSS face (docs/jss.md, docs/configuration.md "jss"): SAE JAUS spoken
// on the same port by the same components. Identification and the
// controller timeout are the node's own keys.
struct JssComponentId {
  std::string component;  // a component's name, or a kind with one component
  std::uint8_t id = 0;    // its JSS component ID, 1..254
  int line = 0;
  bool operator==(const JssComponentId&) const = default;
};

struct JssConfig {
  bool enabled = true;
  std::optional<std::uint16_t> subsystem;  // 1..65534; absent: the RA subsystem
  std::vector<JssComponentId> components;  // those not listed keep their RA component ID
  std::uint8_t client_alias_subsystem = 250;  // 1..254, no RA node may use it
  // Where JSS broadcasts and datagrams for unknown JSS IDs go; absent = none.
  std::optional<jaus::transport::Ipv4Endpoint> multicast =
      jaus::transport::Ipv4Endpoint{0xEFFF0001, jaus::transport::kJausPort};  // 239.255.0.1:3794
  std::size_t max_clients = 64;            // JSS client nodes at once, 1..254
  std::size_t max_events = 256;            // all clients' events together
  std::size_t max_events_per_client = 32;  // 1..255
  std::uint8_t event_timeout_min = 1;      // Report Event Timeout; 0: events never expire
  double change_poll_period_s = 0.1;       // every-change events look this often
  std::size_t max_packet_contents = 1400;  // larger contents go as a large message
};

// metrics: the node's counters over HTTP in Prometheus's text format
// (jaus/host/metrics_server.hpp; docs/configuration.md "metrics").
struct MetricsConfig {
  std::optional<jaus::transport::Ipv4Endpoint> listen;  // none: off (the default)
  std::string token;                                    // needed beyond loopback
};

struct JausdConfig {
  // identification
  std::uint8_t subsystem = 1;  // 1..254
  std::uint8_t node = 1;       // 1..254
  std::string subsystem_name = "jaus-node";
  std::uint16_t subsystem_type = 10001;
  std::string node_name = "node";
  std::uint16_t node_type = 40001;

  double heartbeat_hz = 1.0;           // node manager's Report Heartbeat Pulse
  double controller_timeout_s = 3.0;   // controller silence that drops control; 0 disables...
  bool unsafe_no_controller_timeout = false;  // ...and is refused unless this says it is meant
  bool reject_refused_control = false; // refused control requests get Reject, not Confirm 2
  ServiceConnectionSettings service_connections;
  LivenessSettings liveness;
  std::string dialect = "ra";          // "ra" or "openjaus": how payloads from peers are read
  TransportConfig transport;
  jaus::components::SimulatedVehicleConfig vehicle;  // what the mobility components drive and read
  PlatformChoice platform;      // what carries it: a simulated Clearpath platform by default
  ClearpathOptions clearpath;   // the bridge's mapping, for a Clearpath platform (platform_config.hpp)
  jaus::components::VisualSensorConfig cameras = default_cameras();  // the visual sensor's (hardware_config.hpp)
  jaus::components::ArmConfig manipulator = default_arm();           // the primitive manipulator's arm
  // Loaded from `plugins:` (docs/plugins.md) before the components were
  // read: their kinds are in jaus::host::component_kinds().
  std::vector<jaus::host::LoadedPlugin> plugins;
  std::vector<ComponentSpec> components = default_components();
  std::string log_level = "info";      // debug, info, warn, error
  // Set Emergency to one moving component holds them all (vehicle) or only it (component).
  jaus::host::EmergencyScope emergency_scope = jaus::host::EmergencyScope::vehicle;
  // Where Set Emergency holds persist across restarts; empty: $STATE_DIRECTORY
  // (systemd's StateDirectory=), else not persisted (a warning at start).
  std::string state_directory;
  JssConfig jss;
  MetricsConfig metrics;

  // Every built-in kind that says it is in the default node
  // (ComponentKind::default_node_authority), each at its own ID, instance 1.
  static std::vector<ComponentSpec> default_components();
  // Two cameras (front pan-tilt-zoom, rear fixed) and a six-joint arm.
  static jaus::components::VisualSensorConfig default_cameras();
  static jaus::components::ArmConfig default_arm();
};

// A configuration that cannot be used: invalid_argument, field = where
// ("file:line", or "file" when no line applies), detail = the whole line
// ("file:line: what").
jaus::Error config_error(std::string_view file, int line, std::string what);

using ConfigResult = jaus::Expected<JausdConfig>;

// What in a valid configuration leaves the vehicle open to the network
// (anyone may take control, the node amplifies toward forged addresses): one
// sentence each, for `jausd --check-config` and the log at start.
std::vector<std::string> posture_warnings(const JausdConfig& config);

// Reads and checks a configuration file (parse, ranges, then validate()).
// The plugins it lists are loaded first (paths relative to its folder).
// Never throws.
ConfigResult load_config_file(const std::string& path);
// The same for text in memory; `name` stands for the file in errors. Plugins
// are loaded relative to `plugin_folder`; without one a `plugins:` list is an
// error (text from memory names no place to load code from).
ConfigResult load_config_string(std::string_view yaml, std::string_view name,
                                const std::optional<std::filesystem::path>& plugin_folder = std::nullopt);

// jss.components resolved: the JSS component ID of each RA component ID it
// renames (a name is a component's name, else a kind that exactly one
// component has), or the first problem (an unknown or ambiguous name, a JSS ID
// given twice or already another component's) with the entry's line.
struct JssComponentProblem {
  int line = 0;
  std::string what;
};
jaus::Expected<std::map<std::uint8_t, std::uint8_t>, JssComponentProblem> jss_component_ids(const JausdConfig& config);

// One line per loaded plugin, its name, file and kinds, for the log at start.
std::vector<std::string> plugin_summaries(const JausdConfig& config);

// Every range and cross-field rule on the values (a loaded file passes; run
// it again after command-line overrides). Good, or the first problem
// (invalid_argument, the whole sentence in its message).
jaus::Expected<void> validate(const JausdConfig& config);

}  // namespace jausd
