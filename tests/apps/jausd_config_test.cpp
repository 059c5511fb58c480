// jausd configuration: defaults, every key read, and one "file:line: what"
// error for every kind of mistake.
#include "jausd_config.hpp"
#include "host_config.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/component_options.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <tuple>
#include <unistd.h>

#include "jaus/core/component_ids.hpp"
#include "jaus/transport/ipv4.hpp"
#include "jaus/transport/peer.hpp"

// Addresses read in failure messages (gtest finds these through ADL).
namespace jaus::transport {
void PrintTo(const Ipv4Endpoint& endpoint, std::ostream* os) { *os << to_string(endpoint); }
void PrintTo(const Cidr& cidr, std::ostream* os) { *os << to_string(cidr); }
void PrintTo(const StaticPeer& peer, std::ostream* os) {
  *os << to_string(peer.endpoint) << " " << to_string(peer.framing);
}
}  // namespace jaus::transport

namespace {

using namespace jausd;
using jaus::transport::Cidr;
using jaus::transport::Framing;
using jaus::transport::Ipv4Endpoint;
using jaus::transport::StaticPeer;
using jaus::host::component_kinds;
using jaus::host::find_component_kind;

// validate()'s verdict as text: "(valid)" or the problem's sentence.
std::string validation(const JausdConfig& c) {
  const auto checked = validate(c);
  return checked ? std::string("(valid)") : checked.error().message();
}

// "a.b.c.d[:port]" as a value (the text is known to be good).
Ipv4Endpoint endpoint(std::string_view text) {
  const auto parsed = jaus::transport::parse_endpoint(text);
  if (!parsed) ADD_FAILURE() << parsed.error().message();
  return parsed ? *parsed : Ipv4Endpoint{};
}

ConfigResult load(std::string_view yaml) { return load_config_string(yaml, "test.yaml"); }

// The text must load with an error at `line` saying exactly `what`.
void expect_error(std::string_view yaml, int line, std::string_view what) {
  const auto result = load(yaml);
  ASSERT_FALSE(result.has_value()) << "loaded without error:\n" << yaml;
  const std::string where = line > 0 ? "test.yaml:" + std::to_string(line) : "test.yaml";
  EXPECT_EQ(result.error().code, jaus::ErrorCode::invalid_argument);
  EXPECT_EQ(result.error().field, where) << result.error().message();
  EXPECT_EQ(result.error().message(), where + ": " + std::string(what));
}

JausdConfig expect_ok(std::string_view yaml) {
  auto result = load(yaml);
  if (!result) ADD_FAILURE() << result.error().message() << "\n" << yaml;
  return result ? *result : JausdConfig{};
}

// The two cameras and the six-joint arm of the default configuration, whether
// from the code's defaults or from config/jausd.yaml (which must agree).
void expect_default_hardware(const JausdConfig& c) {
  const auto cameras = JausdConfig::default_cameras().cameras;
  ASSERT_EQ(c.cameras.cameras.size(), 2u);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const auto& got = c.cameras.cameras[i];
    const auto& want = cameras[i];
    EXPECT_EQ(got.id, want.id);
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.description, want.description);
    EXPECT_EQ(std::tie(got.x_m, got.y_m, got.z_m), std::tie(want.x_m, want.y_m, want.z_m));
    EXPECT_NEAR(got.home_yaw_rad, want.home_yaw_rad, 1e-12);
    EXPECT_NEAR(got.home_pitch_rad, want.home_pitch_rad, 1e-12);
    for (auto [g, w] : {std::pair{got.pan, want.pan}, std::pair{got.tilt, want.tilt}, std::pair{got.zoom, want.zoom}}) {
      EXPECT_NEAR(g.min, w.min, 1e-12) << want.name;
      EXPECT_NEAR(g.max, w.max, 1e-12) << want.name;
      EXPECT_NEAR(g.max_rate, w.max_rate, 1e-12) << want.name;
    }
    EXPECT_NEAR(got.widest_horizontal_fov_rad, want.widest_horizontal_fov_rad, 1e-12);
    EXPECT_NEAR(got.narrowest_horizontal_fov_rad, want.narrowest_horizontal_fov_rad, 1e-12);
    EXPECT_EQ(std::tie(got.width, got.height, got.min_width, got.min_height, got.max_width, got.max_height),
              std::tie(want.width, want.height, want.min_width, want.min_height, want.max_width, want.max_height));
    EXPECT_EQ(std::tie(got.frame_rate_fps, got.min_frame_rate_fps, got.max_frame_rate_fps),
              std::tie(want.frame_rate_fps, want.min_frame_rate_fps, want.max_frame_rate_fps));
    EXPECT_EQ(got.image_formats, want.image_formats);
    EXPECT_EQ(got.image_directory, "");
  }
  const auto arm = JausdConfig::default_arm();
  ASSERT_EQ(c.manipulator.joints.size(), 6u);
  EXPECT_EQ(std::tie(c.manipulator.base_x_m, c.manipulator.base_y_m, c.manipulator.base_z_m),
            std::tie(arm.base_x_m, arm.base_y_m, arm.base_z_m));
  EXPECT_EQ(c.manipulator.base_quaternion_d, 1);
  EXPECT_EQ(c.manipulator.update_rate_hz, arm.update_rate_hz);
  for (std::size_t i = 0; i < arm.joints.size(); ++i) {
    const auto& got = c.manipulator.joints[i];
    const auto& want = arm.joints[i];
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.prismatic, want.prismatic);
    EXPECT_NEAR(got.link_length_m, want.link_length_m, 1e-12) << want.name;
    EXPECT_NEAR(got.twist_angle_rad, want.twist_angle_rad, 1e-12) << want.name;
    EXPECT_NEAR(got.offset, want.offset, 1e-12) << want.name;
    EXPECT_NEAR(got.min_position, want.min_position, 1e-12) << want.name;
    EXPECT_NEAR(got.max_position, want.max_position, 1e-12) << want.name;
    EXPECT_NEAR(got.max_velocity, want.max_velocity, 1e-12) << want.name;
    EXPECT_EQ(got.max_effort, want.max_effort) << want.name;
    EXPECT_EQ(got.initial_position, 0) << want.name;
  }
}

void expect_defaults(const JausdConfig& c) {
  EXPECT_EQ(c.subsystem, 1);
  EXPECT_EQ(c.node, 1);
  EXPECT_EQ(c.subsystem_name, "jaus-node");
  EXPECT_EQ(c.subsystem_type, 10001);
  EXPECT_EQ(c.node_name, "node");
  EXPECT_EQ(c.node_type, 40001);
  EXPECT_EQ(c.heartbeat_hz, 1.0);
  EXPECT_EQ(c.controller_timeout_s, 3.0);
  EXPECT_FALSE(c.reject_refused_control);
  EXPECT_EQ(c.service_connections.max_rate_hz, 1092);
  EXPECT_EQ(c.service_connections.max_connections, 64u);
  EXPECT_EQ(c.service_connections.deadman_periods, 3);
  EXPECT_EQ(c.service_connections.deadman_minimum_s, 0.2);
  EXPECT_EQ(c.liveness.component_timeout_s, 3);
  EXPECT_EQ(c.liveness.node_timeout_s, 5);
  EXPECT_EQ(c.liveness.subsystem_timeout_s, 5);
  EXPECT_EQ(c.liveness.max_entries, 1024u);
  EXPECT_EQ(c.dialect, "ra");
  EXPECT_EQ(c.transport.bind, endpoint("0.0.0.0:3794"));
  EXPECT_EQ(c.transport.framing, Framing::opc);
  // The group the RA implementations on the LAN share (issue 43), in the framing they read.
  EXPECT_EQ(c.transport.multicast, endpoint("224.1.0.1:3794"));
  EXPECT_EQ(c.transport.multicast_framing, Framing::judp);
  EXPECT_TRUE(c.transport.broadcast_to_peers);
  EXPECT_FALSE(c.transport.relay);
  EXPECT_TRUE(c.transport.peers.empty());
  EXPECT_TRUE(c.transport.allow.empty());
  EXPECT_TRUE(c.transport.control_from.empty());
  EXPECT_TRUE(c.transport.control_from_local);  // [local]: safe by default
  EXPECT_TRUE(c.transport.verify_endpoints);
  EXPECT_EQ(c.transport.unverified_burst_bytes, 4096u);
  EXPECT_EQ(c.transport.unverified_bytes_per_second, 1024u);
  EXPECT_EQ(c.transport.unverified_total_burst_bytes, 32768u);
  EXPECT_EQ(c.transport.unverified_total_bytes_per_second, 16384u);
  EXPECT_EQ(c.transport.max_peers, 256u);
  EXPECT_EQ(c.transport.send_rate_kbit, 0u);  // no send budget: the node sends at once, as on a LAN
  EXPECT_FALSE(jausd::host_config(c).send_budget.enabled());
  EXPECT_EQ(jausd::host_config(c).link.receive_buffer_bytes, 1u << 20);
  EXPECT_TRUE(c.jss.enabled);
  EXPECT_FALSE(c.jss.subsystem);
  EXPECT_TRUE(c.jss.components.empty());
  EXPECT_EQ(c.jss.client_alias_subsystem, 250);
  EXPECT_EQ(c.jss.multicast, endpoint("239.255.0.1:3794"));
  EXPECT_EQ(c.jss.max_clients, 64u);
  EXPECT_EQ(c.jss.max_events, 256u);
  EXPECT_EQ(c.jss.max_events_per_client, 32u);
  EXPECT_EQ(c.jss.event_timeout_min, 1);
  EXPECT_EQ(c.jss.change_poll_period_s, 0.1);
  EXPECT_EQ(c.jss.max_packet_contents, 1400u);
  ASSERT_EQ(c.components.size(), 14u);
  EXPECT_EQ(c.components[0].kind, "node_manager");
  EXPECT_EQ(c.components[0].id, 1);
  EXPECT_EQ(c.components[0].instance, 1);
  EXPECT_EQ(c.components[0].authority, 0);
  EXPECT_EQ(c.components[0].name, "node_manager");
  EXPECT_EQ(c.components[1].kind, "communicator");
  EXPECT_EQ(c.components[1].id, 35);
  EXPECT_EQ(c.components[1].instance, 1);
  EXPECT_EQ(c.components[2].kind, "primitive_driver");
  EXPECT_EQ(c.components[2].id, 33);
  EXPECT_EQ(c.components[3].kind, "global_pose_sensor");
  EXPECT_EQ(c.components[3].id, 38);
  EXPECT_EQ(c.components[4].kind, "local_pose_sensor");
  EXPECT_EQ(c.components[4].id, 41);
  EXPECT_EQ(c.components[5].kind, "velocity_state_sensor");
  EXPECT_EQ(c.components[5].id, 42);
  EXPECT_EQ(c.components[6].kind, "visual_sensor");
  EXPECT_EQ(c.components[6].id, 37);
  EXPECT_EQ(c.components[7].kind, "primitive_manipulator");
  EXPECT_EQ(c.components[7].id, 49);
  // The drivers above the primitive driver, each with authority 1 (below an operator's).
  const std::pair<const char*, int> drivers[] = {{"global_vector_driver", 34},       {"local_vector_driver", 44},
                                                 {"global_waypoint_driver", 45},     {"local_waypoint_driver", 46},
                                                 {"global_path_segment_driver", 47}, {"local_path_segment_driver", 48}};
  for (std::size_t i = 0; i < std::size(drivers); ++i) {
    EXPECT_EQ(c.components[8 + i].kind, drivers[i].first);
    EXPECT_EQ(c.components[8 + i].id, drivers[i].second);
    EXPECT_EQ(c.components[8 + i].instance, 1);
    EXPECT_EQ(c.components[8 + i].authority, 1) << drivers[i].first;
  }
  expect_default_hardware(c);
  // Options written in the default file are their defaults.
  for (const auto& spec : c.components) EXPECT_TRUE(jaus::host::check_component_options(spec)) << spec.kind;
  const jaus::components::SimulatedVehicleConfig vehicle;
  EXPECT_EQ(c.vehicle.specifications.name, vehicle.specifications.name);
  EXPECT_EQ(c.vehicle.steering, vehicle.steering);
  EXPECT_EQ(c.vehicle.max_speed_mps, vehicle.max_speed_mps);
  EXPECT_EQ(c.vehicle.max_yaw_rate_rps, vehicle.max_yaw_rate_rps);
  EXPECT_EQ(c.vehicle.max_acceleration_mps2, vehicle.max_acceleration_mps2);
  EXPECT_EQ(c.vehicle.max_deceleration_mps2, vehicle.max_deceleration_mps2);
  EXPECT_EQ(c.vehicle.update_rate_hz, vehicle.update_rate_hz);
  EXPECT_EQ(c.vehicle.start, vehicle.start);
  EXPECT_EQ(c.vehicle.start_heading_rad, vehicle.start_heading_rad);
  EXPECT_EQ(c.vehicle.position_rms_m, vehicle.position_rms_m);
  EXPECT_EQ(c.vehicle.position_rms_per_m, vehicle.position_rms_per_m);
  EXPECT_EQ(c.vehicle.local_frame, vehicle.local_frame);
  EXPECT_EQ(c.log_level, "info");
}

// A temporary file removed at the end of the test.
struct TempFile {
  std::string path;
  explicit TempFile(std::string_view content) {
    path = (std::filesystem::temp_directory_path() / ("jausd_config_test_" + std::to_string(::getpid()) + ".yaml"))
               .string();
    std::ofstream(path, std::ios::binary) << content;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

// ------------------------------------------------------------ good files

TEST(JausdConfig, EmptyFileIsTheDefaultConfiguration) {
  expect_defaults(expect_ok(""));
  expect_defaults(expect_ok("# nothing but a comment\n\n"));
  expect_defaults(expect_ok("{}"));
  EXPECT_TRUE(validate(JausdConfig{}));
}

TEST(JausdConfig, LivenessTableSizeReachesTheNode) {
  EXPECT_EQ(jausd::host_config(expect_ok("liveness: {max_entries: 4096}\n")).node.liveness.max_entries, 4096u);
  EXPECT_EQ(jausd::host_config(expect_ok("{}")).node.liveness.max_entries, 1024u);
}

TEST(JausdConfig, EmergencyScopeAndStateDirectory) {
  const auto c = expect_ok("emergency_scope: component\nstate_directory: /var/lib/jaus\n");
  EXPECT_EQ(c.emergency_scope, jaus::host::EmergencyScope::component);
  EXPECT_EQ(c.state_directory, "/var/lib/jaus");
  const auto host = jausd::host_config(c);
  EXPECT_EQ(host.emergency.scope, jaus::host::EmergencyScope::component);
  EXPECT_EQ(host.emergency.state_directory, "/var/lib/jaus");
  EXPECT_EQ(expect_ok("{}").emergency_scope, jaus::host::EmergencyScope::vehicle);
  expect_error("emergency_scope: subsystem\n", 1, "'emergency_scope' must be one of vehicle, component, got 'subsystem'");
}

TEST(JausdConfig, MetricsAreOffByDefaultAndBeyondLoopbackNeedAToken) {
  EXPECT_FALSE(expect_ok("{}").metrics.listen);
  const auto local = expect_ok("metrics:\n  listen: 127.0.0.1\n");
  ASSERT_TRUE(local.metrics.listen);
  EXPECT_EQ(*local.metrics.listen, endpoint("127.0.0.1:9794"));  // the default port
  const auto remote = expect_ok("metrics: {listen: '0.0.0.0:9100', token: abc}\n");
  EXPECT_EQ(*remote.metrics.listen, endpoint("0.0.0.0:9100"));
  EXPECT_EQ(remote.metrics.token, "abc");
  EXPECT_FALSE(expect_ok("metrics: {listen: null}\n").metrics.listen);
  expect_error("metrics:\n  listen: 10.0.0.5\n", 2,
               "'metrics.listen' '10.0.0.5:9794' is beyond loopback: give 'metrics.token' too (scrapes then send it "
               "as a bearer token)");
  expect_error("metrics:\n  listen: robot\n", 2,
               "'listen': 'robot' is not an IPv4 address a.b.c.d (host names are not resolved)");
  expect_error("metrics:\n  port: 9100\n", 2, "unknown key 'port' in metrics (known: listen, token)");
}

TEST(JausdConfig, DefaultFileLoadsAndHoldsTheDefaults) {
  const auto result = load_config_file(JAUSD_DEFAULT_CONFIG);
  ASSERT_TRUE(result.has_value()) << result.error().message();
  expect_defaults(*result);
  EXPECT_EQ(result->components[0].line, 177);  // declared in the file
  EXPECT_TRUE(validate(*result));
}

TEST(JausdConfig, DocumentationExamplesLoad) {
  std::ifstream in(JAUSD_CONFIGURATION_DOC);
  ASSERT_TRUE(in) << JAUSD_CONFIGURATION_DOC;
  std::string line, block;
  bool inside = false;
  int examples = 0;
  while (std::getline(in, line)) {
    if (!inside && line == "```yaml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      ++examples;
      EXPECT_TRUE(load(block).has_value()) << block;
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_GE(examples, 2);
}

TEST(JausdConfig, EveryKeyIsRead) {
  const auto c = expect_ok(R"(
identification:
  subsystem: 12
  subsystem_name: "Test vehicle #2"
  subsystem_type: 10002
  node: 254
  node_name: payload node
  node_type: 40002
dialect: openjaus
heartbeat_hz: 100
control:
  controller_timeout_s: 0
  unsafe_no_controller_timeout: true
  reject_refused: true
service_connections:
  max_rate_hz: 50.5
  max_connections: 255
  max_total_rate_hz: 500
  deadman_periods: 1.5
  deadman_minimum_s: 0
  deadman_maximum_s: 2.5
liveness:
  component_timeout_s: 0.5
  node_timeout_s: 10
  subsystem_timeout_s: 86400
  max_entries: 4096
transport:
  bind: 127.0.0.2
  framing: judp
  multicast: 224.1.0.1:3795
  multicast_framing: opc
  broadcast_to_peers: false
  relay: true
  peers:
    - address: 127.0.0.3:3794
      framing: opc
    - address: 127.0.0.4
    - 10.1.2.3:4000
  allow: [127.0.0.0/8, 10.0.0.0/8, 192.168.1.7]
  control_from: [10.20.0.0/24, local]
  verify_endpoints: false
  max_peers: 1
  send_rate_kbit: 230
  send_queue_bytes: 65536
  receive_buffer_bytes: 0
components:
  - kind: node_manager
    authority: 255
    name: NM
  - kind: communicator
    instance: 2
    id: 36
    authority: 7
    options: {}
  - kind: primitive_driver
    options: {command_timeout_s: 0.2, stop_brake_percent: 0}
logging:
  level: debug
)");
  EXPECT_EQ(c.subsystem, 12);
  EXPECT_EQ(c.subsystem_name, "Test vehicle #2");
  EXPECT_EQ(c.subsystem_type, 10002);
  EXPECT_EQ(c.node, 254);
  EXPECT_EQ(c.node_name, "payload node");
  EXPECT_EQ(c.node_type, 40002);
  EXPECT_EQ(c.dialect, "openjaus");
  EXPECT_EQ(c.heartbeat_hz, 100);
  EXPECT_EQ(c.controller_timeout_s, 0);
  EXPECT_TRUE(c.unsafe_no_controller_timeout);
  EXPECT_TRUE(c.reject_refused_control);
  EXPECT_EQ(c.service_connections.max_rate_hz, 50.5);
  EXPECT_EQ(c.service_connections.max_connections, 255u);
  EXPECT_EQ(c.service_connections.max_total_rate_hz, 500);
  EXPECT_EQ(c.service_connections.deadman_periods, 1.5);
  EXPECT_EQ(c.service_connections.deadman_minimum_s, 0);
  EXPECT_EQ(c.service_connections.deadman_maximum_s, 2.5);
  EXPECT_EQ(c.liveness.component_timeout_s, 0.5);
  EXPECT_EQ(c.liveness.node_timeout_s, 10);
  EXPECT_EQ(c.liveness.subsystem_timeout_s, 86400);
  EXPECT_EQ(c.liveness.max_entries, 4096u);
  EXPECT_EQ(c.transport.bind, endpoint("127.0.0.2:3794"));
  EXPECT_EQ(c.transport.framing, Framing::judp);
  EXPECT_EQ(c.transport.multicast, endpoint("224.1.0.1:3795"));
  EXPECT_EQ(c.transport.multicast_framing, Framing::opc);
  EXPECT_FALSE(c.transport.broadcast_to_peers);
  EXPECT_TRUE(c.transport.relay);
  ASSERT_EQ(c.transport.peers.size(), 3u);
  EXPECT_EQ(c.transport.peers[0], (StaticPeer{endpoint("127.0.0.3:3794"), Framing::opc}));
  EXPECT_EQ(c.transport.peers[1], (StaticPeer{endpoint("127.0.0.4:3794"), Framing::judp}));  // transport.framing
  EXPECT_EQ(c.transport.peers[2], (StaticPeer{endpoint("10.1.2.3:4000"), Framing::judp}));
  ASSERT_EQ(c.transport.allow.size(), 3u);
  EXPECT_EQ(c.transport.allow[0], (Cidr{0x7F000000, 8}));
  EXPECT_EQ(c.transport.allow[1], (Cidr{0x0A000000, 8}));
  EXPECT_EQ(c.transport.allow[2], (Cidr{0xC0A80107, 32}));
  ASSERT_EQ(c.transport.control_from.size(), 1u);
  EXPECT_EQ(c.transport.control_from[0], (Cidr{0x0A140000, 24}));
  EXPECT_TRUE(c.transport.control_from_local);
  EXPECT_FALSE(c.transport.verify_endpoints);
  EXPECT_EQ(c.transport.max_peers, 1u);  // learnt peers; static ones come on top
  EXPECT_EQ(c.transport.send_rate_kbit, 230u);
  EXPECT_EQ(c.transport.send_queue_bytes, 65536u);
  const auto budget = jausd::host_config(c).send_budget;
  EXPECT_EQ(budget.bits_per_second, 230'000u);
  EXPECT_EQ(budget.queue_bytes, 65536u);
  EXPECT_EQ(jausd::host_config(c).link.receive_buffer_bytes, 0u);  // the system's default
  ASSERT_EQ(c.components.size(), 3u);
  EXPECT_EQ(c.components[0].authority, 255);
  EXPECT_EQ(c.components[0].name, "NM");
  EXPECT_EQ(c.components[0].line, 47);
  EXPECT_EQ(c.components[1].kind, "communicator");
  EXPECT_EQ(c.components[1].id, 36);
  EXPECT_EQ(c.components[1].instance, 2);
  EXPECT_EQ(c.components[1].authority, 7);
  EXPECT_EQ(c.components[1].name, "communicator");
  EXPECT_EQ(c.components[1].line, 50);
  EXPECT_EQ(c.components[2].options.at("command_timeout_s"), "0.2");
  EXPECT_EQ(c.components[2].options.at("stop_brake_percent"), "0");
  EXPECT_EQ(c.components[2].option_lines.at("command_timeout_s"), 56);
  EXPECT_EQ(c.log_level, "debug");
}

TEST(JausdConfig, PeerFramingDefaultsToTransportFramingWhereverItIsWritten) {
  const auto c = expect_ok("transport:\n  peers: [127.0.0.2]\n  framing: judp\n");
  ASSERT_EQ(c.transport.peers.size(), 1u);
  EXPECT_EQ(c.transport.peers[0].framing, Framing::judp);
}

TEST(JausdConfig, EmptySectionsAndListsAreTheirDefaults) {
  const auto c = expect_ok(
      "identification:\ncontrol:\nservice_connections:\nliveness:\ntransport:\n  peers:\n  allow:\n"
      "components:\nlogging:\n");
  expect_defaults(c);
}

TEST(JausdConfig, MulticastNullMeansNoGroup) {
  const auto c = expect_ok("transport:\n  multicast: ~\n");
  EXPECT_FALSE(c.transport.multicast);
  EXPECT_FALSE(host_config(c).link.multicast);
  // The default reaches the link with its framing.
  const auto h = host_config(expect_ok(""));
  EXPECT_EQ(h.link.multicast, endpoint("224.1.0.1:3794"));
  EXPECT_EQ(h.link.multicast_framing, Framing::judp);
}

TEST(JausdConfig, ScalarSpellings) {
  auto c = expect_ok("identification: {subsystem: \"7\", node: +8}\nheartbeat_hz: 2.5e1\n");
  EXPECT_EQ(c.subsystem, 7);
  EXPECT_EQ(c.node, 8);
  EXPECT_EQ(c.heartbeat_hz, 25);
  c = expect_ok("control: {reject_refused: yes}\ntransport: {broadcast_to_peers: off}\n");
  EXPECT_TRUE(c.reject_refused_control);
  EXPECT_FALSE(c.transport.broadcast_to_peers);
  c = expect_ok("identification: {node_name: 12345}\n");  // a plain number is text where text is wanted
  EXPECT_EQ(c.node_name, "12345");
}

// Safety: a node whose controller may go silent for ever must be asked for in so many words.
TEST(JausdConfig, NoControllerTimeoutNeedsTheUnsafeOption) {
  expect_error("heartbeat_hz: 1\ncontrol:\n  controller_timeout_s: 0\n", 2,
               "'controller_timeout_s: 0' keeps a silent controller in control for ever; "
               "set 'unsafe_no_controller_timeout: true' in control if that is meant");
  expect_error("control: {controller_timeout_s: 0, unsafe_no_controller_timeout: false}\n", 1,
               "'controller_timeout_s: 0' keeps a silent controller in control for ever; "
               "set 'unsafe_no_controller_timeout: true' in control if that is meant");
  const auto c = expect_ok("control: {controller_timeout_s: 0, unsafe_no_controller_timeout: true}\n");
  EXPECT_EQ(c.controller_timeout_s, 0);
  expect_error("\nservice_connections: {deadman_minimum_s: 2}\n", 2,
               "'deadman_minimum_s' (2) must not exceed 'deadman_maximum_s' (1)");
}

TEST(JausdConfig, BoundariesThatAreAllowed) {
  EXPECT_TRUE(load("identification: {subsystem: 254, node: 1}\n"));
  EXPECT_TRUE(load("heartbeat_hz: 0.001\n"));
  EXPECT_TRUE(load("heartbeat_hz: 100\n"));
  EXPECT_TRUE(load("control: {controller_timeout_s: 0, unsafe_no_controller_timeout: true}\n"));
  EXPECT_TRUE(load("service_connections: {deadman_minimum_s: 0.5, deadman_maximum_s: 0.5}\n"));
  EXPECT_TRUE(load("identification: {subsystem_type: 0, node_type: 65535}\n"));
  EXPECT_TRUE(load("transport: {bind: 127.0.0.1:1}\n"));
  EXPECT_TRUE(load("transport: {bind: 127.0.0.1:65535}\n"));
  EXPECT_TRUE(load("transport: {allow: [0.0.0.0/0]}\n"));
  EXPECT_TRUE(load("components: [{kind: node_manager}, {kind: communicator, id: 254, instance: 254, authority: 0}]\n"));
  EXPECT_TRUE(load("identification: {node_name: " + std::string(80, 'x') + "}\n"));
}

TEST(JausdConfig, ComponentsReplaceTheDefaults) {
  const auto c = expect_ok("components:\n  - kind: node_manager\n");
  ASSERT_EQ(c.components.size(), 1u);
  EXPECT_EQ(c.components[0].kind, "node_manager");
  EXPECT_EQ(c.components[0].line, 2);
}

TEST(JausdConfig, SeveralInstancesOfAKind) {
  const auto c = expect_ok(
      "components:\n  - kind: node_manager\n  - kind: communicator\n  - kind: communicator\n    instance: 2\n");
  ASSERT_EQ(c.components.size(), 3u);
  EXPECT_EQ(c.components[2].id, 35);
  EXPECT_EQ(c.components[2].instance, 2);
}

// ------------------------------------------------------------ YAML syntax

TEST(JausdConfigErrors, YamlSyntaxErrorsNameTheLine) {
  expect_error("identification:\n  subsystem: 1\n node: 2\n", 3, "YAML syntax error: end of map not found");
  expect_error("transport:\n  peers: [127.0.0.2\n  framing: opc\n", 3,
               "YAML syntax error: end of sequence flow not found");
  expect_error("heartbeat_hz: 1\nlogging:\n\tlevel: info\n", 3, "YAML syntax error: illegal map value");
  expect_error("dialect: ra\nlogging: {level: info\n", 3, "YAML syntax error: end of map flow not found");
}

TEST(JausdConfigErrors, OneDocumentOnly) {
  expect_error("heartbeat_hz: 1\n---\nheartbeat_hz: 2\n", 2,
               "a configuration holds one YAML document, this starts a second one");
  // A leading separator, or an end marker, is still one document.
  EXPECT_TRUE(jausd::load_config_string("---\nheartbeat_hz: 2\n...\n", "one.yaml"));
}

// yaml-cpp 0.7 reads some junk as an empty document (and its LoadAll never
// returns on it): found by fuzz_jausd_config.
TEST(JausdConfigErrors, JunkIsNotAnEmptyFile) {
  expect_error(",1", 1, "not a YAML mapping of settings: ',1'");
  expect_error("# a comment\n, ,\n", 2, "not a YAML mapping of settings: ', ,'");
  EXPECT_TRUE(jausd::load_config_string("~\n", "null.yaml"));
  EXPECT_TRUE(jausd::load_config_string("# nothing but comments\n\n", "comments.yaml"));
}

TEST(JausdConfigErrors, TheFileMustBeAMap) {
  expect_error("- heartbeat_hz\n", 1, "the configuration must be a map of keys, got a list");
  expect_error("\n\njust words\n", 3, "the configuration must be a map of keys, got 'just words'");
}

// ------------------------------------------------------------ keys

TEST(JausdConfigErrors, UnknownKeysAtEveryLevel) {
  expect_error("heartbeat_hz: 1\nhearbeat_hz: 2\n", 2,
               "unknown key 'hearbeat_hz' (known: identification, dialect, heartbeat_hz, control, "
               "service_connections, liveness, transport, jss, emergency_scope, state_directory, metrics, vehicle, platform, "
               "clearpath, "
               "cameras, manipulator, "
               "plugins, components, logging)");
  expect_error("identification:\n  subsystem: 1\n  sub_system: 2\n", 3,
               "unknown key 'sub_system' in identification (known: subsystem, subsystem_name, subsystem_type, "
               "node, node_name, node_type)");
  expect_error("control:\n  timeout_s: 2\n", 2,
               "unknown key 'timeout_s' in control (known: controller_timeout_s, reject_refused, "
               "unsafe_no_controller_timeout)");
  expect_error("service_connections: {max_rate: 10}\n", 1,
               "unknown key 'max_rate' in service_connections (known: max_rate_hz, max_connections, "
               "max_total_rate_hz, deadman_periods, deadman_minimum_s, deadman_maximum_s)");
  expect_error("liveness:\n\n  peer_timeout_s: 1\n", 3,
               "unknown key 'peer_timeout_s' in liveness (known: component_timeout_s, node_timeout_s, "
               "subsystem_timeout_s, max_entries)");
  expect_error("transport:\n  port: 3794\n", 2,
               "unknown key 'port' in transport (known: bind, framing, multicast, multicast_framing, "
               "broadcast_to_peers, relay, peers, allow, control_from, verify_endpoints, unverified_burst_bytes, "
               "unverified_bytes_per_second, unverified_total_burst_bytes, unverified_total_bytes_per_second, max_peers, "
               "send_rate_kbit, send_queue_bytes, receive_buffer_bytes)");
  expect_error("transport:\n  peers:\n    - address: 127.0.0.2\n      framming: judp\n", 4,
               "unknown key 'framming' in transport.peers (known: address, framing)");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    ID: 35\n", 4,
               "unknown key 'ID' in components (known: kind, id, instance, authority, name, options)");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    options:\n      links: 2\n", 5,
               "unknown option 'links' for communicator (known: none)");
  expect_error("logging:\n  level: info\n  file: /tmp/x\n", 3, "unknown key 'file' in logging (known: level)");
}

TEST(JausdConfigErrors, DuplicateKeys) {
  expect_error("heartbeat_hz: 1\ndialect: ra\nheartbeat_hz: 2\n", 3, "duplicate key 'heartbeat_hz' (first at line 1)");
  expect_error("transport:\n  bind: 127.0.0.1\n  bind: 127.0.0.2\n", 3,
               "duplicate key 'bind' in transport (first at line 2)");
}

TEST(JausdConfigErrors, KeysMustBeNames) {
  expect_error("? [a, b]\n: 1\n", 1, "keys must be plain names, got a list");
}

// ------------------------------------------------------------ types

TEST(JausdConfigErrors, WrongTypes) {
  expect_error("identification:\n  subsystem: abc\n", 2, "'subsystem' must be an integer 1..254, got 'abc'");
  expect_error("identification:\n  node: 1.0\n", 2, "'node' must be an integer 1..254, got '1.0'");
  expect_error("identification:\n  node: 0x10\n", 2, "'node' must be an integer 1..254, got '0x10'");
  expect_error("identification:\n  node: +-5\n", 2, "'node' must be an integer 1..254, got '+-5'");
  expect_error("heartbeat_hz: +-5\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got '+-5'");
  expect_error("heartbeat_hz: 1_000\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got '1_000'");
  expect_error("identification:\n  node: [1]\n", 2, "'node' must be an integer 1..254, got a list");
  expect_error("identification:\n  subsystem_type: vehicle\n", 2,
               "'subsystem_type' must be an integer 0..65535, got 'vehicle'");
  expect_error("heartbeat_hz: fast\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got 'fast'");
  expect_error("heartbeat_hz: .nan\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got '.nan'");
  expect_error("control:\n  reject_refused: maybe\n", 2, "'reject_refused' must be true or false, got 'maybe'");
  expect_error("transport:\n  broadcast_to_peers: {}\n", 2, "'broadcast_to_peers' must be true or false, got a map");
  expect_error("identification:\n  node_name: [a, b]\n", 2,
               "'node_name' must be 1..80 printable ASCII characters, got a list");
  expect_error("transport: 5\n", 1, "'transport' must be a map of keys, got '5'");
  expect_error("control: [1, 2]\n", 1, "'control' must be a map of keys, got a list");
  expect_error("transport:\n  peers: 127.0.0.2\n", 2, "'peers' must be a list, got '127.0.0.2'");
  expect_error("transport:\n  allow: {a: 1}\n", 2, "'allow' must be a list, got a map");
  expect_error("transport:\n  allow:\n    - [10.0.0.0/8]\n", 3, "'allow' entries must be a.b.c.d/prefix, got a list");
  expect_error("transport:\n  peers:\n    - [127.0.0.2]\n", 3,
               "a peer must be an address or a map with 'address', got a list");
  expect_error("transport:\n  peers:\n    - framing: judp\n", 3, "a peer needs an 'address'");
  expect_error("components: node_manager\n", 1, "'components' must be a list, got 'node_manager'");
  expect_error("components:\n  - node_manager\n", 2, "a component must be a map with a 'kind', got 'node_manager'");
  expect_error("components:\n  - kind: node_manager\n    options: [a]\n", 3,
               "'options' must be a map of keys, got a list");
  expect_error("logging: info\n", 1, "'logging' must be a map of keys, got 'info'");
}

TEST(JausdConfigErrors, AMissingValueIsNotTheDefault) {
  // A scalar key written without a value is a mistake, reported on its line.
  expect_error("identification:\n  subsystem:\n  node: 2\n", 2, "'subsystem' must be an integer 1..254, got nothing");
  expect_error("heartbeat_hz: ~\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got nothing");
  expect_error("transport:\n  bind:\n", 2, "'bind' must be an IPv4 address a.b.c.d[:port], got nothing");
  expect_error("logging:\n  level:\n", 2, "'level' must be one of debug, info, warn, error, got nothing");
}

// ------------------------------------------------------------ ranges

TEST(JausdConfigErrors, OutOfRange) {
  expect_error("identification:\n  subsystem: 0\n", 2, "'subsystem' must be an integer 1..254, got '0'");
  expect_error("identification:\n  subsystem: 255\n", 2, "'subsystem' must be an integer 1..254, got '255'");
  expect_error("identification:\n  node: -1\n", 2, "'node' must be an integer 1..254, got '-1'");
  expect_error("identification:\n  node: 99999999999999999999999\n", 2,
               "'node' must be an integer 1..254, got '99999999999999999999999'");
  expect_error("identification:\n  node_type: 65536\n", 2, "'node_type' must be an integer 0..65535, got '65536'");
  expect_error("heartbeat_hz: 0\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got '0'");
  expect_error("heartbeat_hz: 100.5\n", 1, "'heartbeat_hz' must be a number > 0 and <= 100, got '100.5'");
  expect_error("control: {controller_timeout_s: -1}\n", 1,
               "'controller_timeout_s' must be a number of seconds 0..86400, got '-1'");
  expect_error("service_connections:\n  max_rate_hz: 2000\n", 2,
               "'max_rate_hz' must be a number > 0 and <= 1092, got '2000'");
  expect_error("service_connections:\n  max_connections: 0\n", 2,
               "'max_connections' must be an integer 1..255, got '0'");
  expect_error("service_connections:\n  deadman_periods: 0.5\n", 2,
               "'deadman_periods' must be a number 1..1000, got '0.5'");
  expect_error("service_connections:\n  deadman_minimum_s: -0.1\n", 2,
               "'deadman_minimum_s' must be a number of seconds 0..86400, got '-0.1'");
  expect_error("liveness:\n  node_timeout_s: 0\n", 2,
               "'node_timeout_s' must be a number of seconds > 0 and <= 86400, got '0'");
  expect_error("liveness:\n  component_timeout_s: -3\n", 2,
               "'component_timeout_s' must be a number of seconds > 0 and <= 86400, got '-3'");
  expect_error("liveness:\n  max_entries: 8\n", 2, "'max_entries' must be an integer 16..1048576, got '8'");
  expect_error("liveness:\n  subsystem_timeout_s: 1e9\n", 2,
               "'subsystem_timeout_s' must be a number of seconds > 0 and <= 86400, got '1e9'");
  expect_error("transport:\n  max_peers: 0\n", 2, "'max_peers' must be an integer 1..65535, got '0'");
  expect_error("transport:\n  send_rate_kbit: 8\n", 2,
               "'send_rate_kbit' must be 0 (no budget) or 16..10000000, got 8");
  expect_error("transport:\n  send_rate_kbit: -1\n", 2,
               "'send_rate_kbit' must be an integer 0..10000000, got '-1'");
  expect_error("transport:\n  receive_buffer_bytes: 1e12\n", 2,
               "'receive_buffer_bytes' must be an integer 0..268435456, got '1e12'");
  expect_error("transport:\n  send_queue_bytes: 100\n", 2,
               "'send_queue_bytes' must be an integer 8192..67108864, got '100'");
  expect_error("transport:\n  unverified_burst_bytes: -1\n", 2,
               "'unverified_burst_bytes' must be an integer 0..1048576, got '-1'");
  expect_error("transport:\n  unverified_total_bytes_per_second: 1e9\n", 2,
               "'unverified_total_bytes_per_second' must be an integer 0..16777216, got '1e9'");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    id: 0\n", 4,
               "'id' must be an integer 1..254, got '0'");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    id: 255\n", 4,
               "'id' must be an integer 1..254, got '255'");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    instance: 0\n", 4,
               "'instance' must be an integer 1..254, got '0'");
  expect_error("components:\n  - kind: node_manager\n    authority: 256\n", 3,
               "'authority' must be an integer 0..255, got '256'");
}

TEST(JausdConfigErrors, Choices) {
  expect_error("logging:\n  level: verbose\n", 2, "'level' must be one of debug, info, warn, error, got 'verbose'");
  expect_error("logging:\n  level: INFO\n", 2, "'level' must be one of debug, info, warn, error, got 'INFO'");
  expect_error("dialect: jaus\n", 1, "'dialect' must be one of ra, openjaus, got 'jaus'");
  expect_error("transport:\n  framing: udp\n", 2, "'framing' must be one of opc, judp, got 'udp'");
  expect_error("transport:\n  peers:\n    - address: 127.0.0.2\n      framing: tcp\n", 4,
               "'framing' must be one of opc, judp, got 'tcp'");
}

TEST(JausdConfigErrors, IdentificationStrings) {
  const std::string long_name(81, 'x');
  expect_error("identification:\n  subsystem_name: " + long_name + "\n", 2,
               "'subsystem_name' must be 1..80 printable ASCII characters, got '" + std::string(60, 'x') +
                   "...' (81 bytes)");
  expect_error("identification:\n  node_name: \"\"\n", 2,
               "'node_name' must be 1..80 printable ASCII characters, got '' (0 bytes)");
  expect_error("identification:\n  node_name: \"caf\xC3\xA9\"\n", 2,
               "'node_name' must be 1..80 printable ASCII characters, got 'caf\xC3\xA9' (5 bytes, not all "
               "printable ASCII)");
  expect_error("identification:\n  node_name: \"a\\tb\"\n", 2,
               "'node_name' must be 1..80 printable ASCII characters, got 'a\\tb' (3 bytes, not all printable "
               "ASCII)");
  expect_error("components:\n  - kind: node_manager\n    name: " + long_name + "\n", 3,
               "'name' must be 1..80 printable ASCII characters, got '" + std::string(60, 'x') + "...' (81 bytes)");
}

// ------------------------------------------------------------ addresses

TEST(JausdConfigErrors, Addresses) {
  expect_error("transport:\n  bind: localhost:3794\n", 2,
               "'bind': 'localhost' is not an IPv4 address a.b.c.d (host names are not resolved)");
  expect_error("transport:\n  bind: 0.0.0.0:0\n", 2, "'bind': port '0' of '0.0.0.0:0' must be 1..65535");
  expect_error("transport:\n  bind: 0.0.0.0:65536\n", 2, "'bind': port '65536' of '0.0.0.0:65536' must be 1..65535");
  expect_error("transport:\n  multicast: 10.0.0.1:3794\n", 2,
               "'multicast' must be a group 224.0.0.0..239.255.255.255, got '10.0.0.1'");
  expect_error("transport:\n  multicast: jaus-group\n", 2,
               "'multicast': 'jaus-group' is not an IPv4 address a.b.c.d (host names are not resolved)");
  expect_error("transport:\n  peers:\n    - address: robot.local\n", 3,
               "'address': 'robot.local' is not an IPv4 address a.b.c.d (host names are not resolved)");
  expect_error("transport:\n  peers:\n    - 127.0.0.2:99999\n", 3,
               "'peers': port '99999' of '127.0.0.2:99999' must be 1..65535");
  expect_error("transport:\n  allow: [10.0.0.0/33]\n", 2, "'allow': prefix length '33' of '10.0.0.0/33' must be 0..32");
  expect_error("transport:\n  allow:\n    - 127.0.0.0/8\n    - lan\n", 4,
               "'allow': 'lan' is not an IPv4 address a.b.c.d (host names are not resolved)");
  expect_error("transport:\n  allow: [10.1.2.3/8]\n", 2,
               "'allow': '10.1.2.3/8' has host bits set below the prefix (the network is 10.0.0.0/8)");
}

TEST(JausdConfigErrors, Peers) {
  expect_error("transport:\n  peers:\n    - 127.0.0.2\n    - address: 127.0.0.2:3794\n", 4,
               "duplicate peer 127.0.0.2:3794 (first at line 3)");
  expect_error("transport:\n  peers:\n    - 0.0.0.0\n", 3,
               "peer 'address' must be a unicast IPv4 address, got '0.0.0.0'");
  expect_error("transport:\n  peers:\n    - 224.1.0.1\n", 3,
               "peer 'address' must be a unicast IPv4 address, got '224.1.0.1' (multicast groups go in "
               "transport.multicast)");
  expect_error("transport:\n  bind: 127.0.0.2\n  peers:\n    - 127.0.0.2:3794\n", 4,
               "peer 127.0.0.2:3794 is this node's own bind address");
  expect_error("transport:\n  allow: [127.0.0.0/8]\n  peers:\n    - 127.0.0.2\n    - 10.0.0.2\n", 5,
               "peer 10.0.0.2:3794 is not in 'allow': its datagrams would be dropped");
}

// ------------------------------------------------------------ components

TEST(JausdConfigErrors, ComponentKinds) {
  expect_error("components:\n  - kind: node_manager\n  - kind: world_model_vector_store\n", 3,
               "unknown component kind 'world_model_vector_store' (known: node_manager, communicator, "
               "primitive_driver, global_pose_sensor, local_pose_sensor, velocity_state_sensor, visual_sensor, "
               "primitive_manipulator, global_vector_driver, local_vector_driver, global_waypoint_driver, "
               "local_waypoint_driver, global_path_segment_driver, local_path_segment_driver)");
  expect_error("components:\n  - kind: node_manager\n  - id: 35\n", 3,
               "a component needs a 'kind' (one of node_manager, communicator, primitive_driver, "
               "global_pose_sensor, local_pose_sensor, velocity_state_sensor, visual_sensor, "
               "primitive_manipulator, global_vector_driver, local_vector_driver, global_waypoint_driver, "
               "local_waypoint_driver, global_path_segment_driver, local_path_segment_driver)");
}

TEST(JausdConfigErrors, ComponentOptionValuesPointAtTheirLine) {
  expect_error("components:\n  - kind: node_manager\n  - kind: primitive_driver\n    options:\n"
               "      stop_brake_percent: 50\n      command_timeout_s: soon\n",
               6, "primitive_driver option 'command_timeout_s' must be a number 0..60, got 'soon'");
  expect_error("components:\n  - kind: node_manager\n  - kind: global_pose_sensor\n    options:\n"
               "      local_pose: maybe\n",
               5, "global_pose_sensor option 'local_pose' must be true or false, got 'maybe'");
  expect_error("components:\n  - kind: node_manager\n  - kind: velocity_state_sensor\n    options:\n"
               "      stale_after_s: 0\n",
               5, "velocity_state_sensor option 'stale_after_s' must be a number > 0 and <= 60, got '0'");
  expect_error("components:\n  - kind: node_manager\n  - kind: primitive_driver\n    options:\n"
               "      brake: 50\n",
               5, "unknown option 'brake' for primitive_driver (known: command_timeout_s, stop_brake_percent)");
}

// Issue 42: a driver's authority ceiling, max_authority, is a whole number
// 0..254: an operator must be able to ask for more than it.
TEST(JausdConfigErrors, ADriversMaxAuthorityIsAWholeNumberUpTo254) {
  const auto c = expect_ok("components:\n  - kind: node_manager\n  - kind: local_waypoint_driver\n    authority: 3\n"
                           "    options:\n      max_authority: 3\n");
  ASSERT_EQ(c.components.size(), 2u);
  EXPECT_EQ(c.components[1].options.at("max_authority"), "3");
  expect_error("components:\n  - kind: node_manager\n  - kind: local_waypoint_driver\n    options:\n"
               "      max_authority: 255\n",
               5,
               "local_waypoint_driver option 'max_authority' must be a whole number 0..254 (an operator must be able "
               "to ask for more), got '255'");
  expect_error("components:\n  - kind: node_manager\n  - kind: global_vector_driver\n    options:\n"
               "      command_rate_hz: 10\n      max_authority: 1.5\n",
               6,
               "global_vector_driver option 'max_authority' must be a whole number 0..254 (an operator must be able "
               "to ask for more), got '1.5'");
}

// A driver's authority above its ceiling is a configuration error where the
// file is checked (`jausd --check-config` says so), not only when jausd
// starts: an operator above the ceiling must always be able to take over.
TEST(JausdConfigErrors, ADriversAuthorityAboveItsCeilingIsRefusedAtItsComponent) {
  expect_error("components:\n  - kind: node_manager\n  - kind: global_vector_driver\n    authority: 5\n", 3,
               "global_vector_driver: authority 5 is above its max_authority 1 (an operator above max_authority must "
               "always be able to take the primitive driver from it; raise max_authority, at most 254, or lower "
               "authority)");
  const auto raised = expect_ok("components:\n  - kind: node_manager\n  - kind: global_vector_driver\n"
                                "    authority: 5\n    options:\n      max_authority: 5\n");
  EXPECT_EQ(raised.components[1].authority, 5);
}

// The local pose sensor (issue 30): configured by its kind, at its RA ID, its
// one option checked at the option's line; its origin is the vehicle's
// start, not an option of its own.
TEST(JausdConfig, ALocalPoseSensorIsConfiguredByItsKind) {
  const auto c = expect_ok("components:\n  - kind: node_manager\n  - kind: local_pose_sensor\n    options:\n"
                           "      stale_after_s: 0.5\n");
  ASSERT_EQ(c.components.size(), 2u);
  EXPECT_EQ(c.components[1].kind, "local_pose_sensor");
  EXPECT_EQ(c.components[1].id, 41);
  EXPECT_EQ(c.components[1].instance, 1);
  EXPECT_EQ(c.components[1].options.at("stale_after_s"), "0.5");
  EXPECT_EQ(c.components[1].line, 3);
  expect_error("components:\n  - kind: node_manager\n  - kind: local_pose_sensor\n    options:\n"
               "      stale_after_s: 61\n",
               5, "local_pose_sensor option 'stale_after_s' must be a number > 0 and <= 60, got '61'");
  expect_error("components:\n  - kind: node_manager\n  - kind: local_pose_sensor\n    options:\n"
               "      origin: 10\n",
               5, "unknown option 'origin' for local_pose_sensor (known: stale_after_s)");
  expect_error("components:\n  - kind: node_manager\n  - kind: local_pose_sensor\n    options:\n"
               "      local_pose: true\n",
               5, "unknown option 'local_pose' for local_pose_sensor (known: stale_after_s)");
}

TEST(JausdConfig, VehicleKeysAreRead) {
  const auto c = expect_ok(R"(
vehicle:
  name: husky
  steering: ackermann
  max_speed_mps: 2.5
  max_yaw_rate_rps: 0.8
  max_steering_rad: 0.6
  wheel_base_m: 0.9
  track_width_m: 0.7
  max_acceleration_mps2: 0.5
  max_deceleration_mps2: 4
  max_yaw_acceleration_rps2: 2
  update_rate_hz: 100
  local_frame: false
  battery_drain_percent_per_hour: 0
  start: {latitude_deg: -33.9, longitude_deg: 151.2, altitude_m: 12, heading_deg: 90}
  accuracy: {position_rms_m: 2, position_rms_per_m: 0.05, attitude_rms_rad: 0.1, velocity_rms_mps: 0.3,
             rate_rms_rps: 0.2}
)");
  const auto& v = c.vehicle;
  EXPECT_EQ(v.specifications.name, "husky");
  EXPECT_EQ(v.steering, jaus::components::Steering::ackermann);
  EXPECT_EQ(v.max_speed_mps, 2.5);
  EXPECT_EQ(v.max_yaw_rate_rps, 0.8);
  EXPECT_EQ(v.max_steering_rad, 0.6);
  EXPECT_EQ(v.wheel_base_m, 0.9);
  EXPECT_EQ(v.specifications.wheel_base_m, 0.9);
  EXPECT_EQ(v.specifications.track_width_m, 0.7);
  EXPECT_EQ(v.max_acceleration_mps2, 0.5);
  EXPECT_EQ(v.max_deceleration_mps2, 4);
  EXPECT_EQ(v.max_yaw_acceleration_rps2, 2);
  EXPECT_EQ(v.update_rate_hz, 100);
  EXPECT_FALSE(v.local_frame);
  EXPECT_EQ(v.battery_drain_percent_per_hour, 0);
  EXPECT_EQ(v.start, (jaus::components::GeoPosition{-33.9, 151.2, 12}));
  EXPECT_NEAR(v.start_heading_rad, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(v.position_rms_m, 2);
  EXPECT_EQ(v.position_rms_per_m, 0.05);
  EXPECT_EQ(v.attitude_rms_rad, 0.1);
  EXPECT_EQ(v.velocity_rms_mps, 0.3);
  EXPECT_EQ(v.rate_rms_rps, 0.2);
}

TEST(JausdConfigErrors, VehicleValues) {
  expect_error("vehicle:\n  max_speed_mps: 0\n", 2, "'max_speed_mps' must be a number > 0 and <= 65.534, got '0'");
  expect_error("vehicle:\n  steering: tank\n", 2,
               "'steering' must be one of differential, ackermann, got 'tank'");
  expect_error("vehicle:\n  name: a name far too long\n", 2,
               "'name' must be 1..15 printable ASCII characters, got 'a name far too long'");
  expect_error("vehicle:\n  start:\n    latitude_deg: 91\n", 3, "'latitude_deg' must be a number -90..90, got '91'");
  expect_error("vehicle:\n  accuracy:\n    rms: 1\n", 3,
               "unknown key 'rms' in vehicle.accuracy (known: position_rms_m, position_rms_per_m, attitude_rms_rad, "
               "velocity_rms_mps, rate_rms_rps)");
  expect_error("vehicle: [1]\n", 1, "'vehicle' must be a map of keys, got a list");
}

// The `clearpath:` mapping as the host gets it: the section a Clearpath platform reads.
const jaus::host::ClearpathSettings& clearpath_section(const jaus::host::HostConfig& config) {
  const auto* section = config.platform.sections.find<jaus::host::ClearpathSettings>();
  if (section == nullptr) throw std::logic_error("no clearpath section");
  return *section;
}

TEST(JausdConfig, PlatformAndClearpathMappingAreRead) {
  // The kinds by the names the host's list gives them; the endpoint is the
  // `clearpath` kind's reading of its options.
  EXPECT_EQ(expect_ok("").platform.kind, "clearpath_sim");  // the default: a simulated Clearpath platform
  EXPECT_EQ(expect_ok("platform: sim\n").platform.kind, "clearpath_sim");
  EXPECT_EQ(expect_ok("platform: model\n").platform.kind, "model");
  EXPECT_EQ(jausd::host_config(expect_ok("platform: model\n")).platform.kind, "model");
  const auto serial = expect_ok("platform: {serial: /dev/ttyS3, baud: 57600}\n");
  EXPECT_EQ(serial.platform.kind, "clearpath");
  const auto serial_endpoint = jaus::host::clearpath_endpoint(jausd::host_config(serial).platform);
  ASSERT_TRUE(serial_endpoint) << serial_endpoint.error().message();
  EXPECT_EQ(serial_endpoint->kind, jaus::clearpath::PlatformEndpoint::Kind::serial);
  EXPECT_EQ(serial_endpoint->device, "/dev/ttyS3");
  EXPECT_EQ(serial_endpoint->baud, 57600u);
  const auto udp = jaus::host::clearpath_endpoint(jausd::host_config(expect_ok("platform: {udp: 10.0.0.5:7000}\n")).platform);
  ASSERT_TRUE(udp) << udp.error().message();
  EXPECT_EQ(udp->kind, jaus::clearpath::PlatformEndpoint::Kind::udp);
  EXPECT_EQ(udp->host, "10.0.0.5");
  EXPECT_EQ(udp->port, 7000);

  const auto c = expect_ok(R"(
platform: {tcp: robot:2000}
clearpath:
  drive: velocity
  brake: ignore
  gear: true
  main_power: {safety_flag: 0x02, active_high: false}
  parking_brake: {gpio: 0x01}
  horn: none
  heading: encoders
  data_rate_hz: 10
  setpoint_max_age_s: 0.3
  nominal_battery_v: 12
  max_encoder_step_m: 1
  emergency_flags: 0x08
  platform_stop_flags: 0
  platform_status_flags: 0x01
)");
  const auto& o = c.clearpath;
  EXPECT_EQ(o.drive, jaus::bridge::DriveMode::velocity);
  EXPECT_EQ(o.brake, jaus::bridge::BrakeMode::ignore);
  EXPECT_TRUE(o.gear);
  EXPECT_EQ(o.main_power.kind, jaus::bridge::DeviceOutput::Kind::safety_flag);
  EXPECT_EQ(o.main_power.bits, 0x02u);
  EXPECT_FALSE(o.main_power.active_high);
  EXPECT_EQ(o.parking_brake.kind, jaus::bridge::DeviceOutput::Kind::gpio);
  EXPECT_EQ(o.horn.kind, jaus::bridge::DeviceOutput::Kind::none);
  EXPECT_FALSE(o.heading_from_orientation);
  EXPECT_EQ(o.data_rate_hz, 10);
  EXPECT_EQ(o.setpoint_max_age_s, 0.3);
  EXPECT_EQ(o.emergency_flags, 0x08);
  EXPECT_EQ(o.platform_stop_flags, 0);
  EXPECT_EQ(o.platform_status_flags, 0x01);

  // What the host gets: the vehicle's figures and the mapping together.
  const auto host_config = jausd::host_config(c);
  EXPECT_EQ(host_config.platform.kind, "clearpath");
  const auto& host = clearpath_section(host_config);
  EXPECT_EQ(host.client.setpoint_max_age, std::chrono::milliseconds(300));
  EXPECT_EQ(host.vehicle.setpoint_max_age, std::chrono::milliseconds(300));
  EXPECT_EQ(host.vehicle.drive, jaus::bridge::DriveMode::velocity);
  EXPECT_EQ(host.vehicle.max_speed_mps, c.vehicle.max_speed_mps);
  EXPECT_EQ(host.vehicle.datum, c.vehicle.start);
  // By default the pan-tilt camera is on mount 0 and the six joints on Clearpath joints 0..5.
  const auto defaults_config = jausd::host_config(expect_ok(""));
  const auto& defaults = clearpath_section(defaults_config);
  ASSERT_EQ(defaults.cameras.mounts.size(), 1u);
  EXPECT_EQ(defaults.cameras.mounts[0].camera_id, 1);
  EXPECT_EQ(defaults.cameras.mounts[0].mount, 0);
  ASSERT_EQ(defaults.arm.joints.size(), 6u);
  EXPECT_EQ(defaults.arm.joints[5].clearpath_joint, 5);
  const auto mapped_config = jausd::host_config(expect_ok(R"(
clearpath:
  mounts: [{camera_id: 1, mount: 1, pan_sign: -1, pan_offset_deg: 10, zoom_min_factor: 1, zoom_max_factor: 4}]
  arm_joints: [{clearpath_joint: 5, sign: -1, offset_deg: 90}, {clearpath_joint: 4}, {clearpath_joint: 3},
               {clearpath_joint: 2}, {clearpath_joint: 1}, {clearpath_joint: 0}]
)"));
  const auto& mapped = clearpath_section(mapped_config);
  EXPECT_EQ(mapped.cameras.mounts[0].mount, 1);
  EXPECT_EQ(mapped.cameras.mounts[0].pan_sign, -1);
  EXPECT_EQ(mapped.cameras.mounts[0].zoom_max_factor, 4);
  EXPECT_EQ(mapped.arm.joints[0].clearpath_joint, 5);
  EXPECT_NEAR(mapped.arm.joints[0].offset_rad, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(mapped.sim.vehicle.mounts, 2u);
  // An Ackermann vehicle drives with Ackermann commands unless told otherwise.
  const auto ackermann_config = jausd::host_config(expect_ok("vehicle: {steering: ackermann}\n"));
  const auto& ackermann = clearpath_section(ackermann_config);
  EXPECT_EQ(ackermann.vehicle.drive, jaus::bridge::DriveMode::ackermann);
  EXPECT_EQ(ackermann.sim.vehicle.drive, jaus::clearpath::sim::Drive::ackermann);
}

// Safe by default (issue 28): only this machine's networks may command; the
// open postures load (an operator may mean them) but are named.
TEST(JausdConfig, ControlFromIsLocalByDefaultAndAnOpenPostureIsWarnedAbout) {
  const auto defaults = expect_ok("");
  EXPECT_TRUE(jausd::posture_warnings(defaults).empty());
  const auto host = jausd::host_config(defaults);
  ASSERT_FALSE(host.link.control_from.empty());  // `local` read at start: never an empty (open) list
  EXPECT_TRUE(std::any_of(host.link.control_from.begin(), host.link.control_from.end(),
                          [](const Cidr& cidr) { return cidr.contains(0x7F000001); }));
  EXPECT_FALSE(std::any_of(host.link.control_from.begin(), host.link.control_from.end(),
                           [](const Cidr& cidr) { return cidr.prefix_length == 0; }));
  EXPECT_TRUE(host.link.verify_endpoints);
  const auto budgets = jausd::host_config(expect_ok(
      "transport: {unverified_burst_bytes: 0, unverified_bytes_per_second: 10, unverified_total_burst_bytes: 20, "
      "unverified_total_bytes_per_second: 30}\n"));
  EXPECT_EQ(budgets.link.amplification.unverified_burst_bytes, 0u);
  EXPECT_EQ(budgets.link.amplification.unverified_bytes_per_second, 10u);
  EXPECT_EQ(budgets.link.amplification.unverified_total_burst_bytes, 20u);
  EXPECT_EQ(budgets.link.amplification.unverified_total_bytes_per_second, 30u);

  const auto named = jausd::host_config(expect_ok("transport: {control_from: [10.20.0.0/24]}\n"));
  ASSERT_EQ(named.link.control_from.size(), 1u);  // the list replaces [local]
  EXPECT_EQ(named.link.control_from[0], (Cidr{0x0A140000, 24}));

  for (const auto* open : {"transport: {control_from: [0.0.0.0/0]}\n", "transport: {control_from: []}\n"}) {
    const auto warnings = jausd::posture_warnings(expect_ok(open));
    ASSERT_EQ(warnings.size(), 1u) << open;
    EXPECT_NE(warnings[0].find("transport.control_from lets any host that reaches 0.0.0.0:3794 take control"),
              std::string::npos)
        << warnings[0];
  }
  const auto unverified = jausd::posture_warnings(expect_ok("transport: {verify_endpoints: false}\n"));
  ASSERT_EQ(unverified.size(), 1u);
  EXPECT_NE(unverified[0].find("transport.verify_endpoints is off"), std::string::npos);
  // Bound to loopback, nothing off the machine reaches it.
  EXPECT_TRUE(jausd::posture_warnings(
                  expect_ok("transport: {bind: 127.0.0.2, control_from: [0.0.0.0/0], verify_endpoints: false}\n"))
                  .empty());
  const auto bad = load("transport:\n  control_from: [everyone]\n");
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().message().rfind("test.yaml:2: 'control_from': ", 0), 0u) << bad.error().message();
  EXPECT_NE(bad.error().message().find("(or local)"), std::string::npos) << bad.error().message();
}

TEST(JausdConfigErrors, PlatformAndClearpathValues) {
  expect_error("platform: hardware\n", 1, "'platform' must be one of sim, model, got 'hardware'");
  expect_error("platform: {serial: /dev/ttyS0, udp: 1.2.3.4:5}\n", 1,
               "'platform' needs exactly one of serial, udp or tcp");
  expect_error("platform: {udp: 1.2.3.4:5, baud: 9600}\n", 1, "'platform': baud applies to a serial port only");
  expect_error("platform:\n  udp: nowhere\n", 2, "'udp' must be HOST:PORT, got 'nowhere'");
  expect_error("clearpath:\n  drive: tank\n", 2,
               "'drive' must be one of differential_output, differential_speeds, velocity, ackermann, got 'tank'");
  expect_error("clearpath:\n  horn: {gpio: 0}\n", 2,
               "'gpio' must be bits 1..4294967295 (decimal or 0x hexadecimal), got '0'");
  expect_error("clearpath:\n  emergency_flags: 0x1G\n", 2,
               "'emergency_flags' must be bits 0..65535 (decimal or 0x hexadecimal), got '0x1G'");
  expect_error("clearpath:\n  setpoint_max_age_s: 60\n", 2,
               "'setpoint_max_age_s' must be a number of seconds 0.05..10, got '60'");
  expect_error("clearpath:\n  arm_joints: [{clearpath_joint: 0}]\n", 1,
               "Clearpath arm: 1 joint mappings for an arm of 6 joints");
  expect_error("clearpath:\n  mounts: [{mount: 0}]\n", 2, "a clearpath.mounts entry needs camera_id and mount");
  expect_error("clearpath:\n  drive: ackermann\n", 1,
               "'clearpath.drive' ackermann needs vehicle.steering ackermann on the simulated platform");
  expect_error("vehicle: {steering: ackermann}\nclearpath:\n  drive: velocity\n", 2,
               "'clearpath.drive' commands a differential platform: vehicle.steering must be differential on the "
               "simulated platform");
  // The kinds and their options come from the host's list of platform kinds.
  expect_error("platform: [serial]\n", 1,
               "'platform' must be sim, model or a map of a platform's options (serial, baud, udp, tcp), got a list");
  expect_error("platform: {ssh: robot}\n", 1, "unknown key 'ssh' in platform (known: serial, baud, udp, tcp)");
  expect_error("platform:\n  serial: /dev/ttyS0\n  baud: 12\n", 3, "'baud' must be an integer 1200..4000000, got '12'");
  expect_error("platform:\n  serial: [a]\n", 2, "'serial' must be a value, got a list");
}

// A platform kind jausd has never heard of (as a plugin brings one): named
// alone as it is written, or by its options; its check's problem points at
// the option's line, and `platform: model` takes no option of it.
TEST(JausdConfig, APlatformKindOfOnesOwnIsReadByTheList) {
  jaus::host::PlatformKind kind;
  kind.name = "test_rig";
  kind.written = "rig";
  kind.options = {"wheels"};
  kind.check = [](const jaus::host::PlatformSettings& settings,
                  const jaus::host::SimulationSettings&) -> jaus::Expected<void> {
    const auto it = settings.options.find("wheels");
    if (it == settings.options.end() || (it->second >= "2" && it->second <= "8" && it->second.size() == 1)) return {};
    jaus::Error e = jaus::make_error(jaus::ErrorCode::invalid_argument,
                                     "'wheels' must be an integer 2..8, got '" + it->second + "'");
    e.field = "wheels";
    return jaus::unexpected(e);
  };
  kind.make = [](const jaus::host::PlatformSettings&, const jaus::host::SimulationSettings&,
                 jaus::host::PlatformEnvironment) -> jaus::Expected<std::unique_ptr<jaus::host::Platform>> {
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, "not made here"));
  };
  ASSERT_TRUE(jaus::host::add_platform_kind(std::move(kind)));
  struct Removed {
    ~Removed() { jaus::host::remove_platform_kind("test_rig"); }
  } removed;
  EXPECT_EQ(expect_ok("platform: rig\n").platform.kind, "test_rig");
  const auto six = expect_ok("platform: {wheels: 6}\n");
  EXPECT_EQ(six.platform.kind, "test_rig");
  EXPECT_EQ(six.platform.options.at("wheels"), "6");
  EXPECT_EQ(jausd::host_config(six).platform.options.at("wheels"), "6");
  expect_error("platform:\n  wheels: 1\n", 2, "'wheels' must be an integer 2..8, got '1'");
  expect_error("platform:\n  wheels: 4\n  udp: 1.2.3.4:5\n", 3,
               "'platform': 'udp' is an option of platform clearpath, not of test_rig");
  expect_error("platform: hardware\n", 1, "'platform' must be one of sim, model, rig, got 'hardware'");
}

TEST(JausdConfig, CamerasAndManipulatorAreRead) {
  const std::string images = std::filesystem::temp_directory_path().string();
  const auto c = expect_ok(R"(
cameras:
  - id: 7
    name: mast
    description: mast camera
    position_m: [0.1, -0.2, -1.5]
    home_yaw_deg: 90
    home_pitch_deg: -45
    pan: {min_deg: -90, max_deg: 90, max_rate_deg_s: 30}
    tilt: {min_deg: -10, max_deg: 10, max_rate_deg_s: 5}
    zoom: {max_rate_percent_s: 25}
    field_of_view_deg: {widest: 90, narrowest: 30}
    width: 64
    height: 48
    min_width: 32
    min_height: 24
    max_width: 640
    max_height: 480
    frame_rate_fps: 2
    min_frame_rate_fps: 1
    max_frame_rate_fps: 4
    formats: [jpeg, png]
    image_directory: )" + images + R"(
manipulator:
  base: {position_m: [0.5, 0, -0.1], quaternion: [0, 0, 0, 1]}
  update_rate_hz: 50
  joints:
    - {name: turret, type: revolute, link_length_m: 0.2, twist_deg: 90, offset_m: 0.1,
       min_deg: -45, max_deg: 45, max_speed_deg_s: 90, max_torque_nm: 30, initial_deg: 10}
    - {name: slide, type: prismatic, twist_deg: 0, offset_deg: 90,
       min_m: 0, max_m: 0.4, max_speed_m_s: 0.2, max_force_n: 150, initial_m: 0.1}
)");
  const double deg = std::numbers::pi / 180;
  ASSERT_EQ(c.cameras.cameras.size(), 1u);
  const auto& cam = c.cameras.cameras[0];
  EXPECT_EQ(cam.id, 7);
  EXPECT_EQ(cam.name, "mast");
  EXPECT_EQ(cam.description, "mast camera");
  EXPECT_EQ(std::tie(cam.x_m, cam.y_m, cam.z_m), std::make_tuple(0.1, -0.2, -1.5));
  EXPECT_NEAR(cam.home_yaw_rad, 90 * deg, 1e-12);
  EXPECT_NEAR(cam.home_pitch_rad, -45 * deg, 1e-12);
  EXPECT_NEAR(cam.pan.min, -90 * deg, 1e-12);
  EXPECT_NEAR(cam.pan.max_rate, 30 * deg, 1e-12);
  EXPECT_NEAR(cam.tilt.max, 10 * deg, 1e-12);
  EXPECT_EQ(cam.zoom.min, 0);
  EXPECT_EQ(cam.zoom.max, 100);
  EXPECT_EQ(cam.zoom.max_rate, 25);
  EXPECT_NEAR(cam.widest_horizontal_fov_rad, 90 * deg, 1e-12);
  EXPECT_NEAR(cam.narrowest_horizontal_fov_rad, 30 * deg, 1e-12);
  EXPECT_EQ(std::tie(cam.width, cam.height, cam.min_width, cam.min_height, cam.max_width, cam.max_height),
            std::make_tuple(64, 48, 32, 24, 640, 480));
  EXPECT_EQ(std::tie(cam.frame_rate_fps, cam.min_frame_rate_fps, cam.max_frame_rate_fps), std::make_tuple(2, 1, 4));
  EXPECT_EQ(cam.image_formats, (std::vector<std::uint8_t>{7, 11}));
  EXPECT_EQ(cam.image_directory, images);

  const auto& arm = c.manipulator;
  EXPECT_EQ(std::tie(arm.base_x_m, arm.base_y_m, arm.base_z_m), std::make_tuple(0.5, 0.0, -0.1));
  EXPECT_EQ(std::tie(arm.base_quaternion_d, arm.base_quaternion_c), std::make_tuple(0.0, 1.0));
  EXPECT_EQ(arm.update_rate_hz, 50);
  ASSERT_EQ(arm.joints.size(), 2u);
  const auto& turret = arm.joints[0];
  EXPECT_FALSE(turret.prismatic);
  EXPECT_EQ(turret.link_length_m, 0.2);
  EXPECT_NEAR(turret.twist_angle_rad, 90 * deg, 1e-12);
  EXPECT_EQ(turret.offset, 0.1);
  EXPECT_NEAR(turret.min_position, -45 * deg, 1e-12);
  EXPECT_NEAR(turret.max_velocity, 90 * deg, 1e-12);
  EXPECT_EQ(turret.max_effort, 30);
  EXPECT_NEAR(turret.initial_position, 10 * deg, 1e-12);
  const auto& slide = arm.joints[1];
  EXPECT_TRUE(slide.prismatic);
  EXPECT_NEAR(slide.offset, 90 * deg, 1e-12);  // a prismatic joint's fixed parameter is its angle
  EXPECT_EQ(std::tie(slide.min_position, slide.max_position, slide.max_velocity, slide.max_effort,
                     slide.initial_position),
            std::make_tuple(0.0, 0.4, 0.2, 150.0, 0.1));
}

TEST(JausdConfigErrors, CameraValues) {
  expect_error("cameras:\n  - id: 1\n    name: a\n  - id: 1\n    name: b\n", 4,
               "duplicate camera id 1 (first at line 2)");
  expect_error("cameras:\n  - id: 1\n    formats: [png, gif]\n", 3,
               "'formats' must be one of png, jpeg, got 'gif'");
  expect_error("cameras:\n  - name: far too long a name\n", 2,
               "'name' must be 1..15 printable ASCII characters, got 'far too long a name'");
  expect_error("cameras:\n  - field_of_view_deg: {widest: 10, narrowest: 20}\n", 2,
               "camera 1 (camera): 'field_of_view_deg' needs 0 < narrowest <= widest <= 180");
  expect_error("cameras:\n  - width: 2000\n", 2,
               "camera 1 (camera): 'width' and 'height' must be within min_width..max_width and "
               "min_height..max_height");
  expect_error("cameras:\n  - image_directory: /no/such/directory\n", 2,
               "'image_directory' '/no/such/directory' is not a directory");
  expect_error("cameras:\n  - pan: {min_deg: -10, max_deg: 10, rate: 5}\n", 2,
               "unknown key 'rate' in cameras.pan (known: min_deg, max_deg, max_rate_deg_s)");
  expect_error("cameras: []\n", 1, "'cameras' must list 1..255 cameras");
}

TEST(JausdConfigErrors, JointValues) {
  expect_error("manipulator:\n  joints:\n    - {type: revolute, min_m: 0}\n", 3,
               "'min_m' is for prismatic joints; joint 1 is revolute: use 'min_deg'");
  expect_error("manipulator:\n  joints:\n    - {name: lift, min_deg: 0}\n", 3,
               "joint 1 (lift) needs a 'type' (revolute or prismatic)");
  expect_error("manipulator:\n  joints:\n    - {type: revolute, min_deg: 10, max_deg: 10}\n", 3,
               "joint 1: the minimum position must be below the maximum");
  expect_error("manipulator:\n  joints:\n    - {type: prismatic, max_m: 0.5, initial_m: 0.6}\n", 3,
               "joint 1: the initial position must be within its limits");
  expect_error("manipulator:\n  joints:\n    - {type: telescopic}\n", 3,
               "'type' must be one of revolute, prismatic, got 'telescopic'");
  expect_error("manipulator:\n  joints: []\n", 2, "'joints' must be a list of 1..255 joints, got an empty list");
  expect_error("manipulator:\n  base: {quaternion: [1, 1, 0, 0]}\n", 2,
               "'quaternion' must be a unit quaternion [d, a, b, c], got a list");
}

TEST(JausdConfigErrors, DuplicateComponent) {
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n\n  - kind: communicator\n", 5,
               "duplicate component id 35 instance 1 (first at line 3)");
  expect_error(
      "components:\n  - kind: node_manager\n  - kind: communicator\n    instance: 3\n"
      "  - {kind: communicator, id: 35, instance: 3}\n",
      5, "duplicate component id 35 instance 3 (first at line 3)");
}

TEST(JausdConfigErrors, ExactlyOneNodeManagerAtOneOne) {
  expect_error("heartbeat_hz: 1\ncomponents:\n  - kind: communicator\n", 2,
               "a node_manager component is required (id 1, instance 1)");
  expect_error("components: []\n", 1, "a node_manager component is required (id 1, instance 1)");
  expect_error("components:\n  - kind: node_manager\n    id: 2\n", 2,
               "the node_manager must have id 1 and instance 1, got id 2 instance 1");
  expect_error("components:\n  - kind: node_manager\n  - kind: node_manager\n    instance: 2\n", 3,
               "only one node_manager per node (first at line 2)");
  expect_error("components:\n  - kind: node_manager\n  - kind: communicator\n    id: 1\n    instance: 2\n", 3,
               "component id 1 is the node_manager's (communicator has RA id 35)");
}

// ------------------------------------------------------------ files

TEST(JausdConfigFile, MissingFile) {
  const std::string path = "/nonexistent/jausd.yaml";
  const auto result = load_config_file(path);
  ASSERT_FALSE(result.has_value());
  EXPECT_EQ(result.error().field, path);  // no line
  EXPECT_EQ(result.error().message(),
            "/nonexistent/jausd.yaml: cannot open /nonexistent/jausd.yaml: No such file or directory");
}

TEST(JausdConfigFile, DirectoryIsNotAFile) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  const auto result = load_config_file(dir);
  ASSERT_FALSE(result.has_value());
  EXPECT_EQ(result.error().message(), dir + ": cannot open " + dir + ": is a directory");
}

TEST(JausdConfigFile, ErrorsNameTheFileAndLine) {
  TempFile file("identification:\n  subsystem: 1\n  node: abc\n");
  const auto result = load_config_file(file.path);
  ASSERT_FALSE(result.has_value());
  EXPECT_EQ(result.error().message(), file.path + ":3: 'node' must be an integer 1..254, got 'abc'");
}

TEST(JausdConfigFile, GoodFile) {
  TempFile file("identification: {subsystem: 9}\n");
  const auto result = load_config_file(file.path);
  ASSERT_TRUE(result.has_value()) << result.error().message();
  EXPECT_EQ(result->subsystem, 9);
}

TEST(JausdConfigFile, HugeFileIsRefused) {
  TempFile file(std::string(1024 * 1024 + 1, '#'));
  const auto result = load_config_file(file.path);
  ASSERT_FALSE(result.has_value());
  EXPECT_EQ(result.error().message(),
            file.path + ": cannot open " + file.path + ": larger than 1 MiB, not a configuration file");
}

TEST(JausdConfigFile, ErrorText) {
  EXPECT_EQ(config_error("a.yaml", 3, "bad").message(), "a.yaml:3: bad");
  EXPECT_EQ(config_error("a.yaml", 0, "bad").message(), "a.yaml: bad");
}

TEST(JausdConfigFile, NothingThrows) {
  const std::string inputs[] = {
      std::string(100000, '['),                     // nesting deeper than yaml-cpp allows
      std::string("\x00\x01\xFF\xFE", 4),
      "&a [*a]",
      "*undefined",
      "key: !!binary \"%%%\"",
      "{a: 1, a: 2, b: [}",
      "components:\n  - &c {kind: communicator}\n  - *c\n",
      std::string(2000, '-') + " x",
  };
  for (const auto& input : inputs) {
    ConfigResult result = JausdConfig{};
    EXPECT_NO_THROW(result = load(input)) << input.substr(0, 40);
    EXPECT_FALSE(result.has_value()) << input.substr(0, 40);
  }
}

// ------------------------------------------------------------ validate (after command-line overrides)

TEST(JausdConfigValidate, Overrides) {
  JausdConfig c;
  EXPECT_TRUE(validate(c));
  c.subsystem = 0;
  EXPECT_EQ(validation(c), "'subsystem' must be an integer 1..254, got 0");
  c.subsystem = 255;
  EXPECT_EQ(validation(c), "'subsystem' must be an integer 1..254, got 255");
  c.subsystem = 3;
  c.node = 0;
  EXPECT_EQ(validation(c), "'node' must be an integer 1..254, got 0");
  c.node = 2;
  c.log_level = "trace";
  EXPECT_EQ(validation(c), "'level' must be one of debug, info, warn, error, got 'trace'");
  c.log_level = "warn";
  c.transport.bind = endpoint("127.0.0.5:4000");
  EXPECT_TRUE(validate(c));
  c.transport.bind.port = 0;
  EXPECT_EQ(validation(c), "'bind' port must be 1..65535, got 0");
  c.transport.bind = endpoint("127.0.0.5:3794");
  c.transport.peers.push_back({endpoint("127.0.0.5:3794"), Framing::opc});
  EXPECT_EQ(validation(c), "peer 127.0.0.5:3794 is this node's own bind address");
}

TEST(JausdConfigValidate, EveryRuleAlsoHoldsForValues) {
  auto broken = [](auto change) {
    JausdConfig c;
    change(c);
    return validation(c);
  };
  EXPECT_EQ(broken([](JausdConfig& c) { c.heartbeat_hz = 0; }),
            "'heartbeat_hz' must be a number > 0 and <= 100, got 0");
  EXPECT_EQ(broken([](JausdConfig& c) { c.controller_timeout_s = -1; }),
            "'controller_timeout_s' must be a number of seconds 0..86400, got -1");
  EXPECT_EQ(broken([](JausdConfig& c) { c.controller_timeout_s = 0; }),
            "'controller_timeout_s: 0' keeps a silent controller in control for ever; "
            "set 'unsafe_no_controller_timeout: true' in control if that is meant");
  EXPECT_EQ(broken([](JausdConfig& c) { c.service_connections.deadman_maximum_s = 0.1; }),
            "'deadman_minimum_s' (0.2) must not exceed 'deadman_maximum_s' (0.1)");
  EXPECT_EQ(broken([](JausdConfig& c) { c.liveness.node_timeout_s = 0; }),
            "'node_timeout_s' must be a number of seconds > 0 and <= 86400, got 0");
  EXPECT_EQ(broken([](JausdConfig& c) { c.service_connections.max_connections = 0; }),
            "'max_connections' must be an integer 1..255, got 0");
  EXPECT_EQ(broken([](JausdConfig& c) { c.dialect = "RA"; }), "'dialect' must be one of ra, openjaus, got 'RA'");
  EXPECT_EQ(broken([](JausdConfig& c) { c.node_name = std::string(81, 'n'); }),
            "'node_name' must be 1..80 printable ASCII characters, got '" + std::string(60, 'n') +
                "...' (81 bytes)");
  // A host name cannot be a value any more (Ipv4Endpoint holds the address);
  // the loader's and --bind's message for it is in JausdConfigErrors.Addresses.
  EXPECT_EQ(broken([](JausdConfig& c) { c.transport.peers.push_back({endpoint("0.0.0.0"), Framing::opc}); }),
            "peer 'address' must be a unicast IPv4 address, got '0.0.0.0'");
  EXPECT_EQ(broken([](JausdConfig& c) { c.transport.multicast = Ipv4Endpoint{0xE0010001, 0}; }),
            "'multicast' port must be 1..65535, got 0");
  EXPECT_EQ(broken([](JausdConfig& c) { c.transport.multicast = endpoint("10.0.0.1:3794"); }),
            "'multicast' must be a group 224.0.0.0..239.255.255.255, got '10.0.0.1'");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components.clear(); }),
            "a node_manager component is required (id 1, instance 1)");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components.push_back(c.components[1]); }),
            "duplicate component id 35 instance 1");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components[1].kind = "world_model_vector_store"; }),
            "unknown component kind 'world_model_vector_store' (known: node_manager, communicator, "
            "primitive_driver, global_pose_sensor, local_pose_sensor, velocity_state_sensor, visual_sensor, "
               "primitive_manipulator, global_vector_driver, local_vector_driver, global_waypoint_driver, "
               "local_waypoint_driver, global_path_segment_driver, local_path_segment_driver)");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components[2].options["stop_brake_percent"] = "150"; }),
            "primitive_driver option 'stop_brake_percent' must be a number 0..100, got '150'");
  EXPECT_EQ(broken([](JausdConfig& c) { c.vehicle.update_rate_hz = 0; }),
            "'update_rate_hz' must be a number > 0 and <= 1000, got 0");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components[1].options["x"] = "1"; }),
            "unknown option 'x' for communicator (known: none)");
  EXPECT_EQ(broken([](JausdConfig& c) { c.components[1].instance = 255; }),
            "component 'instance' must be an integer 1..254, got 255");
  EXPECT_EQ(broken([](JausdConfig& c) { c.transport.allow.push_back(Cidr{0, 40}); }),
            "'allow' prefix length must be 0..32, got 40");
}

// ------------------------------------------------------------ registry

// ---- jss: the JSS face -------------------------------------------------------

TEST(JausdConfigJss, TheSectionIsReadAndReachesTheHost) {
  const auto c = expect_ok(R"(
identification: {subsystem: 7, node: 3, subsystem_name: judge vehicle}
control: {controller_timeout_s: 4.5}
transport: {multicast: 224.1.0.1:3794}
jss:
  enabled: true
  subsystem: 4242
  components:
    primitive_driver: 133      # by kind
    local_waypoint_driver: 146
    communicator: 135
  client_alias_subsystem: 200
  multicast: 239.255.0.9:3795
  max_clients: 8
  max_events: 40
  max_events_per_client: 5
  event_timeout_min: 0
  change_poll_period_s: 0.25
  max_packet_contents: 4079
)");
  EXPECT_EQ(c.jss.subsystem, 4242);
  ASSERT_EQ(c.jss.components.size(), 3u);
  EXPECT_EQ(c.jss.components[0], (JssComponentId{"primitive_driver", 133, 9}));
  EXPECT_EQ(c.jss.client_alias_subsystem, 200);
  EXPECT_EQ(c.jss.multicast, endpoint("239.255.0.9:3795"));
  EXPECT_EQ(c.jss.max_clients, 8u);
  EXPECT_EQ(c.jss.max_events, 40u);
  EXPECT_EQ(c.jss.max_events_per_client, 5u);
  EXPECT_EQ(c.jss.event_timeout_min, 0);
  EXPECT_EQ(c.jss.change_poll_period_s, 0.25);
  EXPECT_EQ(c.jss.max_packet_contents, 4079u);

  const auto h = host_config(c);
  EXPECT_TRUE(h.jss.enabled);
  EXPECT_EQ(h.jss.subsystem, 4242);
  EXPECT_EQ(h.jss.component_ids, (std::map<std::uint8_t, std::uint8_t>{{33, 133}, {46, 146}, {35, 135}}));
  EXPECT_EQ(h.jss.client_alias_subsystem, 200);
  EXPECT_EQ(h.jss.max_clients, 8u);
  EXPECT_EQ(h.jss.max_events, 40u);
  EXPECT_EQ(h.jss.max_events_per_client, 5u);
  EXPECT_EQ(h.jss.event_timeout_min, 0);
  EXPECT_EQ(h.jss.change_poll_period, std::chrono::milliseconds(250));
  EXPECT_EQ(h.jss.max_packet_contents, 4079u);
  EXPECT_EQ(h.link.jss_multicast, endpoint("239.255.0.9:3795"));
  EXPECT_EQ(h.link.multicast, endpoint("224.1.0.1:3794"));  // the RA group stays the RA group
}

TEST(JausdConfigJss, OffMeansNoFaceAndNoGroup) {
  const auto h = host_config(expect_ok("jss: {enabled: false}\n"));
  EXPECT_FALSE(h.jss.enabled);
  EXPECT_FALSE(h.link.jss_multicast);
  EXPECT_FALSE(host_config(expect_ok("jss: {multicast: null}\n")).link.jss_multicast);
  // On by default, on the JSS group.
  EXPECT_EQ(host_config(expect_ok("")).link.jss_multicast, endpoint("239.255.0.1:3794"));
}

TEST(JausdConfigJss, AComponentIsNamedByItsNameOrItsOnlyKind) {
  const auto c = expect_ok(R"(
components:
  - kind: node_manager
  - {kind: visual_sensor, name: front camera}
  - {kind: visual_sensor, name: rear camera, id: 57}
jss:
  components: {rear camera: 37, front camera: 57, node_manager: 1}
)");
  const auto ids = jss_component_ids(c);
  ASSERT_TRUE(ids) << ids.error().what;
  EXPECT_EQ(*ids, (std::map<std::uint8_t, std::uint8_t>{{57, 37}, {37, 57}, {1, 1}}));
}

TEST(JausdConfigErrors, JssValues) {
  expect_error("jss:\n  subsystem: 0\n", 2, "'subsystem' must be an integer 1..65534, got '0'");
  expect_error("jss:\n  subsystem: 65535\n", 2, "'subsystem' must be an integer 1..65534, got '65535'");
  expect_error("jss:\n  client_alias_subsystem: 255\n", 2,
               "'client_alias_subsystem' must be an integer 1..254, got '255'");
  expect_error("identification: {subsystem: 250}\njss:\n  max_clients: 3\n", 2,
               "'client_alias_subsystem' (250) must differ from the node's subsystem: JSS clients' RA aliases would "
               "pose as nodes of this subsystem");
  expect_error("jss:\n  multicast: 10.0.0.1:3794\n", 2,
               "'multicast' must be a group 224.0.0.0..239.255.255.255, got '10.0.0.1'");
  expect_error("jss:\n  max_clients: 255\n", 2, "'max_clients' must be an integer 1..254, got '255'");
  expect_error("jss:\n  max_events: 0\n", 2, "'max_events' must be an integer 1..65535, got '0'");
  expect_error("jss:\n  max_events: 4\n  max_events_per_client: 5\n", 1,
               "'max_events_per_client' (5) must not exceed 'max_events' (4)");
  expect_error("jss:\n  event_timeout_min: 256\n", 2, "'event_timeout_min' must be an integer 0..255, got '256'");
  expect_error("jss:\n  change_poll_period_s: 0\n", 2,
               "'change_poll_period_s' must be a number of seconds 0.01..10, got '0'");
  expect_error("jss:\n  max_packet_contents: 5000\n", 2,
               "'max_packet_contents' must be an integer 64..4079, got '5000'");
  expect_error("jss:\n  enabled: maybe\n", 2, "'enabled' must be true or false, got 'maybe'");
  expect_error("jss:\n  port: 3794\n", 2,
               "unknown key 'port' in jss (known: enabled, subsystem, components, client_alias_subsystem, multicast, "
               "max_clients, max_events, max_events_per_client, event_timeout_min, change_poll_period_s, "
               "max_packet_contents)");
}

TEST(JausdConfigErrors, JssComponents) {
  const std::string components =
      " (components: node_manager, communicator, primitive_driver, global_pose_sensor, local_pose_sensor, "
      "velocity_state_sensor, visual_sensor, primitive_manipulator, global_vector_driver, local_vector_driver, "
      "global_waypoint_driver, local_waypoint_driver, global_path_segment_driver, local_path_segment_driver)";
  expect_error("jss:\n  components: [33]\n", 2,
               "'components' must be a map of component names (or kinds) to JSS component IDs 1..254, got a list");
  expect_error("jss:\n  components:\n    primitive_driver: 255\n", 3,
               "'primitive_driver' must be an integer 1..254, got '255'");
  expect_error("jss:\n  components:\n    primitive_driver: 3\n    primitive_driver: 4\n", 4,
               "duplicate key 'primitive_driver' in jss.components (first at line 3)");
  expect_error("jss:\n  components:\n    wheel: 3\n", 3, "jss.components: no component named 'wheel'" + components);
  // The primitive driver would become the communicator's JSS ID.
  expect_error("jss:\n  components:\n    primitive_driver: 35\n", 3,
               "jss.components: JSS component ID 35 would be both RA component 35 and RA component 33");
  expect_error(R"(components:
  - kind: node_manager
  - {kind: visual_sensor, name: front}
  - {kind: visual_sensor, name: rear, id: 57}
jss:
  components: {visual_sensor: 60}
)",
               6, "jss.components: 'visual_sensor' is the kind of several components (front, rear): name one of them");
  expect_error("jss:\n  components:\n    communicator: 40\n    comms: 41\n", 4,
               "jss.components: no component named 'comms'" + components);
  // Off: nothing of the section is checked against the node.
  expect_ok("identification: {subsystem: 250}\njss: {enabled: false}\n");
}

TEST(JausdConfigValidate, TheAliasSubsystemRuleHoldsAfterOverrides) {
  auto c = expect_ok("");
  c.subsystem = 250;  // --subsystem 250
  const auto valid = validate(c);
  ASSERT_FALSE(valid);
  EXPECT_NE(valid.error().message().find("'client_alias_subsystem' (250) must differ"), std::string::npos);
}

TEST(ComponentKinds, EachBuiltInKindIsAtTheRaIdOfItsNameAndSoIsTheDefaultNode) {
  for (const jaus::host::ComponentKind* kind : jaus::host::builtin_component_kinds()) {
    std::string ra_kind(jaus::component_id::ra_name(kind->default_id));
    std::replace(ra_kind.begin(), ra_kind.end(), ' ', '_');
    EXPECT_EQ(ra_kind, kind->name) << "id " << int(kind->default_id);
  }
  const auto defaults = JausdConfig::default_components();
  ASSERT_EQ(defaults.size(), jaus::host::builtin_component_kinds().size());
  for (const jaus::host::ComponentSpec& spec : defaults) {
    const jaus::host::ComponentKind* kind = find_component_kind(spec.kind);
    ASSERT_NE(kind, nullptr) << spec.kind;
    EXPECT_EQ(spec.id, kind->default_id) << spec.kind;
    EXPECT_EQ(spec.instance, 1) << spec.kind;
    // Each at the authority its kind gives it there: the drivers above the
    // primitive driver 1 (below any operator's), everything else 0.
    ASSERT_TRUE(kind->default_node_authority.has_value()) << spec.kind;
    EXPECT_EQ(spec.authority, *kind->default_node_authority) << spec.kind;
    const bool above_primitive_driver = spec.kind.ends_with("_vector_driver") ||
                                        spec.kind.ends_with("_waypoint_driver") ||
                                        spec.kind.ends_with("_path_segment_driver");
    EXPECT_EQ(spec.authority, above_primitive_driver ? 1 : 0) << spec.kind;
  }
  // A kind that does not say so (a plugin's, by default) is in no default node.
  EXPECT_FALSE(jaus::rt::ComponentKind{}.default_node_authority.has_value());
}

TEST(ComponentKinds, RegistryHoldsWhatTheNodeImplements) {
  // In the order of components/CMakeLists.txt's folders.
  const std::pair<const char*, int> kinds[] = {
      {"node_manager", 1},           {"communicator", 35},           {"primitive_driver", 33},
      {"global_pose_sensor", 38},    {"local_pose_sensor", 41},      {"velocity_state_sensor", 42},
      {"visual_sensor", 37},         {"primitive_manipulator", 49},  {"global_vector_driver", 34},
      {"local_vector_driver", 44},   {"global_waypoint_driver", 45}, {"local_waypoint_driver", 46},
      {"global_path_segment_driver", 47}, {"local_path_segment_driver", 48}};
  ASSERT_EQ(component_kinds().size(), std::size(kinds));
  for (std::size_t i = 0; i < std::size(kinds); ++i) {
    EXPECT_EQ(component_kinds()[i].name, kinds[i].first);
    EXPECT_EQ(component_kinds()[i].default_id, kinds[i].second) << kinds[i].first;
  }
  ASSERT_NE(find_component_kind("communicator"), nullptr);
  EXPECT_TRUE(find_component_kind("communicator")->options.empty());
  ASSERT_NE(find_component_kind("primitive_manipulator"), nullptr);
  EXPECT_EQ(find_component_kind("primitive_manipulator")->options, std::vector<std::string_view>{"command_timeout_s"});
  EXPECT_EQ(find_component_kind("world_model_vector_store"), nullptr);  // registered when implemented
  EXPECT_EQ(to_string(Framing::opc), "opc");
  EXPECT_EQ(to_string(Framing::judp), "judp");
}

}  // namespace
