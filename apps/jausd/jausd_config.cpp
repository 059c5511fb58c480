#include "jausd_config.hpp"

#include "config_reader.hpp"
#include "hardware_config.hpp"
#include "host_config.hpp"
#include "plugins_config.hpp"

#include "jaus/base/quoted.hpp"
#include "jaus/host/component_options.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <system_error>

namespace jausd {

using namespace yaml_reader;

using jaus::transport::Cidr;
using jaus::transport::Framing;
using jaus::transport::Ipv4Endpoint;
using jaus::transport::StaticPeer;
using jaus::host::component_kinds;
using jaus::host::ComponentKind;
using jaus::host::find_component_kind;

std::vector<ComponentSpec> JausdConfig::default_components() {
  // Each kind at its own RA ID (ComponentKind::default_id), instance 1, named
  // as its kind.
  const auto at_its_id = [](std::string kind, std::uint8_t authority) {
    const ComponentKind* known = find_component_kind(kind);
    return ComponentSpec{kind, known ? known->default_id : std::uint8_t{0}, 1, authority, kind, {}, 0, {}};
  };
  return {at_its_id("node_manager", 0), at_its_id("communicator", 0), at_its_id("primitive_driver", 0),
          at_its_id("global_pose_sensor", 0), at_its_id("local_pose_sensor", 0),
          at_its_id("velocity_state_sensor", 0), at_its_id("visual_sensor", 0), at_its_id("primitive_manipulator", 0),
          // The drivers above the primitive driver, each with authority 1:
          // below an operator's, who takes the primitive driver over at once.
          at_its_id("global_vector_driver", 1), at_its_id("local_vector_driver", 1),
          at_its_id("global_waypoint_driver", 1), at_its_id("local_waypoint_driver", 1),
          at_its_id("global_path_segment_driver", 1), at_its_id("local_path_segment_driver", 1)};
}

jaus::components::VisualSensorConfig JausdConfig::default_cameras() { return jausd::default_cameras(); }
jaus::components::ArmConfig JausdConfig::default_arm() { return jausd::default_arm(); }

// ---------------------------------------------------------------- limits

namespace {

// Ranges shared by the file reader (which reports the line) and validate().
constexpr long long kAddressMin = 1, kAddressMax = 254;  // subsystem, node, component ID, instance
constexpr std::size_t kMaxIdentification = 80;           // Report Identification carries 80 bytes
constexpr double kMaxSeconds = 86400;                     // keeps every duration representable
constexpr std::size_t kMaxConnectionsLimit = 255;
constexpr std::size_t kMaxPeersLimit = 65535;
// The unverified endpoints' budgets (bytes, bytes a second): up to 1 MiB per
// endpoint, 16 MiB all together; 0 allows nothing beyond what they sent.
constexpr long long kMaxUnverifiedBytes = 1 << 20;
constexpr long long kMaxUnverifiedTotalBytes = 16 << 20;
// 254 subsystems x 254 nodes x a few components is the most JAUS IDs name;
// the floor leaves room for this node's own peers and one OCU.
constexpr std::size_t kMinLivenessEntries = 16;
constexpr std::size_t kMaxLivenessEntries = 1u << 20;

constexpr std::array<std::string_view, 4> kLogLevels{"debug", "info", "warn", "error"};
constexpr std::array<std::string_view, 2> kDialects{"ra", "openjaus"};
constexpr std::array<std::string_view, 2> kFramings{"opc", "judp"};
constexpr std::array<std::string_view, 2> kEmergencyScopes{"vehicle", "component"};

constexpr NumberRange kHeartbeatRange{0, false, 100, "a number > 0 and <= 100"};
// The simulated vehicle: each range is what the reports can encode or what keeps the model sane.
constexpr NumberRange kSpeedRange{0, false, 65.534, "a number > 0 and <= 65.534"};
constexpr NumberRange kYawRateRange{0, false, 32.767, "a number > 0 and <= 32.767"};
constexpr NumberRange kSteeringRange{0, false, 1.5, "a number > 0 and <= 1.5"};
constexpr NumberRange kLengthRange{0, false, 65.535, "a number > 0 and <= 65.535"};
constexpr NumberRange kAccelerationRange{0, false, 100, "a number > 0 and <= 100"};
constexpr NumberRange kUpdateRateRange{0, false, 1000, "a number > 0 and <= 1000"};
constexpr NumberRange kAccuracyRange{0, true, 100, "a number 0..100"};
constexpr NumberRange kPercentRange{0, true, 100, "a number 0..100"};
constexpr NumberRange kLatitudeRange{-90, true, 90, "a number -90..90"};
constexpr NumberRange kLongitudeRange{-180, true, 180, "a number -180..180"};
constexpr NumberRange kAltitudeRange{-10000, true, 35000, "a number -10000..35000"};
constexpr NumberRange kHeadingRange{-360, true, 360, "a number of degrees -360..360"};
constexpr std::array<std::string_view, 2> kSteerings{"differential", "ackermann"};
constexpr std::size_t kMaxPlatformName = 15;  // Report Platform Specifications' name field
constexpr NumberRange kTimeoutRange{0, true, kMaxSeconds, "a number of seconds 0..86400"};
constexpr NumberRange kPositiveTimeoutRange{0, false, kMaxSeconds, "a number of seconds > 0 and <= 86400"};
constexpr NumberRange kRateRange{0, false, 1092, "a number > 0 and <= 1092"};
constexpr NumberRange kTotalRateRange{0, false, 1'000'000, "a number > 0 and <= 1000000"};
constexpr NumberRange kDeadmanPeriodsRange{1, true, 1000, "a number 1..1000"};
// The JSS face: subsystem IDs are 16-bit there (65535 = all); event IDs and
// alias slots are 8-bit; AS5669A peers take up to 4079 contents bytes a packet.
constexpr long long kJssSubsystemMax = 65534;
constexpr long long kMaxJssClients = 254;
constexpr long long kMaxJssEvents = 65535;
constexpr long long kMaxJssEventsPerClient = 255;
constexpr long long kMinPacketContents = 64, kMaxPacketContents = 4079;
constexpr NumberRange kPollPeriodRange{0.01, true, 10, "a number of seconds 0.01..10"};

// Empty when `text` is a valid identification string, else what is wrong.
std::string identification_problem(std::string_view key, std::string_view text) {
  const bool printable = std::all_of(text.begin(), text.end(), [](char ch) {
    const auto c = static_cast<unsigned char>(ch);
    return c >= 0x20 && c <= 0x7E;
  });
  if (text.empty() || text.size() > kMaxIdentification || !printable)
    return "'" + std::string(key) + "' must be 1..80 printable ASCII characters, got " + jaus::quoted(text) + " (" +
           std::to_string(text.size()) + " bytes" + (printable ? "" : ", not all printable ASCII") + ")";
  return {};
}

}  // namespace

// ---------------------------------------------------------------- errors

jaus::Error config_error(std::string_view file, int line, std::string what) {
  std::string where(file);
  if (line > 0) where += ":" + std::to_string(line);
  std::string detail = where + ": " + what;
  return jaus::Error{jaus::ErrorCode::invalid_argument, 0, std::move(where), std::move(detail)};
}

// ---------------------------------------------------------------- validation

namespace {

struct Issue {
  int line = 0;
  std::string what;
};

// Lines of what the file declared, for cross-field errors (0 = unknown).
struct SourceLines {
  int control = 0;          // the 'control' key
  int service_connections = 0;  // the 'service_connections' key
  int components = 0;       // the 'components' key
  int cameras = 0;          // the 'cameras' key
  int manipulator = 0;      // the 'manipulator' key
  int platform = 0;         // the 'platform' key
  int clearpath = 0;        // the 'clearpath' key
  std::vector<int> peers;   // one per transport.peers entry
  int jss = 0;              // the 'jss' key
};

int line_at(const std::vector<int>& lines, std::size_t i) { return i < lines.size() ? lines[i] : 0; }

// Where a platform kind's problem is (jaus::host::PlatformKind::check): the
// first of the places its field names that the file declared (an option of
// `platform:`, or a section), else the `platform` key.
int platform_problem_line(const JausdConfig& c, const SourceLines& lines, std::string_view field) {
  const std::map<std::string_view, int> sections{{"platform", lines.platform},   {"clearpath", lines.clearpath},
                                                 {"cameras", lines.cameras},     {"manipulator", lines.manipulator}};
  while (!field.empty()) {
    const std::string_view place = field.substr(0, field.find('|'));
    field.remove_prefix(std::min(field.size(), place.size() + 1));
    if (const auto it = c.platform.option_lines.find(std::string(place)); it != c.platform.option_lines.end())
      return it->second;
    if (const auto it = sections.find(place); it != sections.end() && it->second != 0) return it->second;
  }
  return lines.platform;
}


std::optional<Issue> check_number(std::string_view key, double v, const NumberRange& range) {
  if (range.contains(v)) return std::nullopt;
  return Issue{0, "'" + std::string(key) + "' must be " + std::string(range.text) + ", got " + number_text(v)};
}

// The kind, one per node, whose ID `id` is (nullptr: none's).
const ComponentKind* one_per_node_at(std::uint8_t id) {
  for (const auto& k : component_kinds())
    if (k.one_per_node && k.default_id == id) return &k;
  return nullptr;
}

std::optional<Issue> check_components(const JausdConfig& c, const SourceLines& lines) {
  std::map<std::string_view, const ComponentSpec*> one_per_node;  // kind -> its component
  std::map<std::pair<int, int>, int> seen;  // (id, instance) -> line
  for (const auto& spec : c.components) {
    const ComponentKind* kind = find_component_kind(spec.kind);
    if (!kind) {
      std::vector<std::string_view> names;
      for (const auto& k : component_kinds()) names.push_back(k.name);
      return Issue{spec.line, "unknown component kind " + jaus::quoted(spec.kind) + " (known: " + join(names) + ")"};
    }
    for (const auto& [key, value] : spec.options)
      if (!one_of(key, kind->options))
        return Issue{spec.line, "unknown option " + jaus::quoted(key) + " for " + spec.kind + " (known: " +
                                    join(kind->options) + ")"};
    if (spec.id < kAddressMin || spec.id > kAddressMax)
      return Issue{spec.line, "component 'id' must be an integer 1..254, got " + std::to_string(spec.id)};
    if (spec.instance < kAddressMin || spec.instance > kAddressMax)
      return Issue{spec.line, "component 'instance' must be an integer 1..254, got " + std::to_string(spec.instance)};
    if (auto problem = identification_problem("name", spec.name); !problem.empty()) return Issue{spec.line, problem};
    if (kind->one_per_node) {
      if (const ComponentSpec* first = one_per_node[kind->name])
        return Issue{spec.line, "only one " + spec.kind + " per node" + first_at(first->line)};
      if (spec.id != kind->default_id || spec.instance != 1)
        return Issue{spec.line, "the " + spec.kind + " must have id " + std::to_string(kind->default_id) +
                                    " and instance 1, got id " + std::to_string(spec.id) + " instance " +
                                    std::to_string(spec.instance)};
      one_per_node[kind->name] = &spec;
    } else if (const ComponentKind* owner = one_per_node_at(spec.id)) {
      return Issue{spec.line, "component id " + std::to_string(spec.id) + " is the " + std::string(owner->name) +
                                  "'s (" + spec.kind + " has RA id " + std::to_string(kind->default_id) + ")"};
    }
    if (auto checked = jaus::host::check_component_options(spec); !checked)
      return Issue{checked.error().line, checked.error().what};
    const auto [it, inserted] = seen.emplace(std::pair<int, int>{spec.id, spec.instance}, spec.line);
    if (!inserted)
      return Issue{spec.line, "duplicate component id " + std::to_string(spec.id) + " instance " +
                                  std::to_string(spec.instance) + first_at(it->second)};
  }
  for (const auto& k : component_kinds())
    if (k.one_per_node && !one_per_node.contains(k.name))
      return Issue{lines.components, "a " + std::string(k.name) + " component is required (id " +
                                         std::to_string(k.default_id) + ", instance 1)"};
  return std::nullopt;
}

std::optional<Issue> check_transport(const TransportConfig& t, const SourceLines& lines) {
  using jaus::transport::ipv4_to_string;
  using jaus::transport::to_string;
  if (t.bind.port == 0) return Issue{0, "'bind' port must be 1..65535, got 0"};
  if (t.multicast) {
    if (!t.multicast->is_multicast())
      return Issue{0, "'multicast' must be a group 224.0.0.0..239.255.255.255, got " +
                          jaus::quoted(ipv4_to_string(t.multicast->address))};
    if (t.multicast->port == 0) return Issue{0, "'multicast' port must be 1..65535, got 0"};
  }
  if (t.max_peers < 1 || t.max_peers > kMaxPeersLimit)
    return Issue{0, "'max_peers' must be an integer 1..65535, got " + std::to_string(t.max_peers)};
  for (const auto& cidr : t.allow)
    if (cidr.prefix_length > 32) return Issue{0, "'allow' prefix length must be 0..32, got " +
                                                     std::to_string(cidr.prefix_length)};
  std::map<Ipv4Endpoint, int> seen;  // peer -> line
  for (std::size_t i = 0; i < t.peers.size(); ++i) {
    const Ipv4Endpoint& peer = t.peers[i].endpoint;
    const int line = line_at(lines.peers, i);
    if (peer.is_any() || peer.is_multicast())
      return Issue{line, "peer 'address' must be a unicast IPv4 address, got " +
                             jaus::quoted(ipv4_to_string(peer.address)) +
                             (peer.is_any() ? "" : " (multicast groups go in transport.multicast)")};
    if (peer.port == 0) return Issue{line, "peer 'address' port must be 1..65535, got 0"};
    if (peer == t.bind) return Issue{line, "peer " + to_string(peer) + " is this node's own bind address"};
    if (!t.allow.empty() &&
        std::none_of(t.allow.begin(), t.allow.end(), [&](const Cidr& cidr) { return cidr.contains(peer.address); }))
      return Issue{line, "peer " + to_string(peer) + " is not in 'allow': its datagrams would be dropped"};
    const auto [it, inserted] = seen.emplace(peer, line);
    if (!inserted) return Issue{line, "duplicate peer " + to_string(peer) + first_at(it->second)};
  }
  return std::nullopt;
}

std::optional<Issue> check_jss(const JausdConfig& c, const SourceLines& lines) {
  const JssConfig& j = c.jss;
  if (!j.enabled) return std::nullopt;
  if (j.subsystem && (*j.subsystem < 1 || *j.subsystem > kJssSubsystemMax))
    return Issue{lines.jss, "'jss.subsystem' must be an integer 1..65534, got " + std::to_string(*j.subsystem)};
  if (j.client_alias_subsystem < kAddressMin || j.client_alias_subsystem > kAddressMax)
    return Issue{lines.jss, "'client_alias_subsystem' must be an integer 1..254, got " +
                                std::to_string(j.client_alias_subsystem)};
  if (j.client_alias_subsystem == c.subsystem)
    return Issue{lines.jss, "'client_alias_subsystem' (" + std::to_string(j.client_alias_subsystem) +
                                ") must differ from the node's subsystem: JSS clients' RA aliases would pose as "
                                "nodes of this subsystem"};
  if (j.multicast && (!j.multicast->is_multicast() || j.multicast->port == 0))
    return Issue{lines.jss, "'jss.multicast' must be a group 224.0.0.0..239.255.255.255 with a port, got " +
                                jaus::transport::to_string(*j.multicast)};
  if (j.max_clients < 1 || j.max_clients > kMaxJssClients)
    return Issue{lines.jss, "'max_clients' must be an integer 1..254, got " + std::to_string(j.max_clients)};
  if (j.max_events < 1 || j.max_events > kMaxJssEvents)
    return Issue{lines.jss, "'max_events' must be an integer 1..65535, got " + std::to_string(j.max_events)};
  if (j.max_events_per_client < 1 || j.max_events_per_client > kMaxJssEventsPerClient)
    return Issue{lines.jss, "'max_events_per_client' must be an integer 1..255, got " +
                                std::to_string(j.max_events_per_client)};
  if (j.max_events_per_client > j.max_events)
    return Issue{lines.jss, "'max_events_per_client' (" + std::to_string(j.max_events_per_client) +
                                ") must not exceed 'max_events' (" + std::to_string(j.max_events) + ")"};
  if (auto issue = check_number("change_poll_period_s", j.change_poll_period_s, kPollPeriodRange)) {
    issue->line = lines.jss;
    return issue;
  }
  if (j.max_packet_contents < static_cast<std::size_t>(kMinPacketContents) ||
      j.max_packet_contents > static_cast<std::size_t>(kMaxPacketContents))
    return Issue{lines.jss, "'max_packet_contents' must be an integer 64..4079, got " +
                                std::to_string(j.max_packet_contents)};
  if (auto ids = jss_component_ids(c); !ids) return Issue{ids.error().line ? ids.error().line : lines.jss, ids.error().what};
  return std::nullopt;
}

std::optional<Issue> check(const JausdConfig& c, const SourceLines& lines) {
  if (c.subsystem < kAddressMin || c.subsystem > kAddressMax)
    return Issue{0, "'subsystem' must be an integer 1..254, got " + std::to_string(c.subsystem)};
  if (c.node < kAddressMin || c.node > kAddressMax)
    return Issue{0, "'node' must be an integer 1..254, got " + std::to_string(c.node)};
  if (auto problem = identification_problem("subsystem_name", c.subsystem_name); !problem.empty())
    return Issue{0, problem};
  if (auto problem = identification_problem("node_name", c.node_name); !problem.empty()) return Issue{0, problem};
  struct NumberCheck {
    std::string_view key;
    double value;
    const NumberRange* range;
  };
  const auto& sc = c.service_connections;
  const NumberCheck numbers[] = {
      {"heartbeat_hz", c.heartbeat_hz, &kHeartbeatRange},
      {"controller_timeout_s", c.controller_timeout_s, &kTimeoutRange},
      {"max_rate_hz", sc.max_rate_hz, &kRateRange},
      {"max_total_rate_hz", sc.max_total_rate_hz, &kTotalRateRange},
      {"deadman_periods", sc.deadman_periods, &kDeadmanPeriodsRange},
      {"deadman_minimum_s", sc.deadman_minimum_s, &kTimeoutRange},
      {"deadman_maximum_s", sc.deadman_maximum_s, &kPositiveTimeoutRange},
      {"component_timeout_s", c.liveness.component_timeout_s, &kPositiveTimeoutRange},
      {"node_timeout_s", c.liveness.node_timeout_s, &kPositiveTimeoutRange},
      {"subsystem_timeout_s", c.liveness.subsystem_timeout_s, &kPositiveTimeoutRange},
      {"max_speed_mps", c.vehicle.max_speed_mps, &kSpeedRange},
      {"max_yaw_rate_rps", c.vehicle.max_yaw_rate_rps, &kYawRateRange},
      {"max_steering_rad", c.vehicle.max_steering_rad, &kSteeringRange},
      {"wheel_base_m", c.vehicle.wheel_base_m, &kLengthRange},
      {"max_acceleration_mps2", c.vehicle.max_acceleration_mps2, &kAccelerationRange},
      {"max_deceleration_mps2", c.vehicle.max_deceleration_mps2, &kAccelerationRange},
      {"max_yaw_acceleration_rps2", c.vehicle.max_yaw_acceleration_rps2, &kAccelerationRange},
      {"update_rate_hz", c.vehicle.update_rate_hz, &kUpdateRateRange},
      {"latitude_deg", c.vehicle.start.latitude_deg, &kLatitudeRange},
      {"longitude_deg", c.vehicle.start.longitude_deg, &kLongitudeRange},
      {"altitude_m", c.vehicle.start.altitude_m, &kAltitudeRange},
      {"position_rms_m", c.vehicle.position_rms_m, &kAccuracyRange},
      {"position_rms_per_m", c.vehicle.position_rms_per_m, &kAccuracyRange},
      {"attitude_rms_rad", c.vehicle.attitude_rms_rad, &kAccuracyRange},
      {"velocity_rms_mps", c.vehicle.velocity_rms_mps, &kAccuracyRange},
      {"rate_rms_rps", c.vehicle.rate_rms_rps, &kAccuracyRange},
      {"battery_drain_percent_per_hour", c.vehicle.battery_drain_percent_per_hour, &kPercentRange},
  };
  for (const auto& n : numbers)
    if (auto issue = check_number(n.key, n.value, *n.range)) return issue;
  if (sc.deadman_minimum_s > sc.deadman_maximum_s)
    return Issue{lines.service_connections, "'deadman_minimum_s' (" + number_text(sc.deadman_minimum_s) +
                        ") must not exceed 'deadman_maximum_s' (" + number_text(sc.deadman_maximum_s) + ")"};
  // Safety: without the controller-silence timeout an OCU that vanishes keeps
  // control, and the vehicle its last command, until someone else steps in.
  if (c.controller_timeout_s == 0 && !c.unsafe_no_controller_timeout)
    return Issue{lines.control, "'controller_timeout_s: 0' keeps a silent controller in control for ever; "
                    "set 'unsafe_no_controller_timeout: true' in control if that is meant"};
  if (sc.max_connections < 1 || sc.max_connections > kMaxConnectionsLimit)
    return Issue{0, "'max_connections' must be an integer 1..255, got " + std::to_string(sc.max_connections)};
  if (!one_of(c.dialect, kDialects))
    return Issue{0, "'dialect' must be one of " + join(kDialects) + ", got " + jaus::quoted(c.dialect)};
  if (!one_of(c.log_level, kLogLevels))
    return Issue{0, "'level' must be one of " + join(kLogLevels) + ", got " + jaus::quoted(c.log_level)};
  if (auto issue = check_transport(c.transport, lines)) return issue;
  if (auto issue = check_jss(c, lines)) return issue;
  if (auto ok = jaus::components::check_cameras_config(c.cameras); !ok) return Issue{lines.cameras, ok.error().message()};
  if (auto ok = jaus::components::check_arm_config(c.manipulator); !ok)
    return Issue{lines.manipulator, ok.error().message()};
  // The platform's kind checks its options and how the `clearpath:` mapping,
  // the vehicle, cameras and arm agree with it (no kind is named here).
  if (auto ok = jaus::host::check_platform(platform_settings(c), jaus::host::SimulationSettings{c.vehicle, c.cameras,
                                                                                                 c.manipulator});
      !ok)
    return Issue{platform_problem_line(c, lines, ok.error().field), ok.error().message()};
  if (c.clearpath.setpoint_max_age_s < 0.05 || c.clearpath.setpoint_max_age_s > 10)
    return Issue{lines.clearpath, "'setpoint_max_age_s' must be a number of seconds 0.05..10"};
  return check_components(c, lines);
}

}  // namespace

jaus::Expected<std::map<std::uint8_t, std::uint8_t>, JssComponentProblem> jss_component_ids(const JausdConfig& config) {
  using Problem = JssComponentProblem;
  std::map<std::uint8_t, std::uint8_t> ids;   // RA component ID -> JSS component ID
  std::map<std::uint8_t, int> renamed_at;     // RA component ID -> the entry's line
  for (const auto& entry : config.jss.components) {
    if (entry.id < kAddressMin || entry.id > kAddressMax)
      return jaus::unexpected(Problem{entry.line, "JSS component ID of " + jaus::quoted(entry.component) +
                                                      " must be an integer 1..254, got " + std::to_string(entry.id)});
    std::vector<const ComponentSpec*> named;
    for (const auto& spec : config.components)
      if (spec.name == entry.component) named.push_back(&spec);
    if (named.empty())
      for (const auto& spec : config.components)
        if (spec.kind == entry.component) named.push_back(&spec);
    if (named.empty()) {
      std::vector<std::string> known;
      for (const auto& spec : config.components) known.push_back(spec.name);
      return jaus::unexpected(Problem{entry.line, "jss.components: no component named " +
                                                      jaus::quoted(entry.component) + " (components: " + join(known) +
                                                      ")"});
    }
    // One RA component ID is one JSS component (instances share it).
    const std::uint8_t ra = named.front()->id;
    if (std::any_of(named.begin(), named.end(), [&](const ComponentSpec* spec) { return spec->id != ra; })) {
      std::vector<std::string> names;
      for (const auto* spec : named) names.push_back(spec->name);
      return jaus::unexpected(Problem{entry.line, "jss.components: " + jaus::quoted(entry.component) +
                                                      " is the kind of several components (" + join(names) +
                                                      "): name one of them"});
    }
    if (const auto [at, inserted] = renamed_at.emplace(ra, entry.line); !inserted)
      return jaus::unexpected(Problem{entry.line, "jss.components: RA component " + std::to_string(ra) +
                                                      " given a JSS ID twice" + first_at(at->second)});
    ids[ra] = entry.id;
  }
  // No two RA components may end up as one JSS component.
  std::map<std::uint8_t, std::uint8_t> owner;  // JSS ID -> RA component ID
  for (const auto& spec : config.components) {
    const auto mapped = ids.find(spec.id);
    const std::uint8_t jss_id = mapped == ids.end() ? spec.id : mapped->second;
    const auto [it, inserted] = owner.emplace(jss_id, spec.id);
    if (!inserted && it->second != spec.id) {
      const auto line = renamed_at.contains(spec.id) ? renamed_at[spec.id] : renamed_at[it->second];
      return jaus::unexpected(Problem{line, "jss.components: JSS component ID " + std::to_string(jss_id) +
                                                " would be both RA component " + std::to_string(it->second) +
                                                " and RA component " + std::to_string(spec.id)});
    }
  }
  return ids;
}

jaus::Expected<void> validate(const JausdConfig& config) {
  if (auto issue = check(config, SourceLines{}))
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, issue->what));
  return {};
}

// ---------------------------------------------------------------- YAML reader

namespace {


std::string identification(const Entry& e) {
  const std::string& text = e.scalar("1..80 printable ASCII characters");
  if (auto problem = identification_problem(e.key, text); !problem.empty()) fail(e.value_line(), problem);
  return text;
}

Framing framing(const Entry& e) { return choice(e, kFramings) == "judp" ? Framing::judp : Framing::opc; }

Ipv4Endpoint endpoint(const Entry& e) {
  auto parsed = jaus::transport::parse_endpoint(e.scalar("an IPv4 address a.b.c.d[:port]"));
  if (!parsed) fail(e.value_line(), "'" + e.key + "': " + parsed.error().message());
  return *parsed;
}

// One entry of transport.peers: {address: a.b.c.d[:port], framing: opc|judp},
// or just the address. The framing defaults to transport.framing, read later.
struct PeerEntry {
  Ipv4Endpoint endpoint;
  std::optional<Framing> framing;
  int line;
};

PeerEntry peer(const YAML::Node& node) {
  PeerEntry p{{}, std::nullopt, line_of(node)};
  if (node.IsScalar()) {
    p.endpoint = endpoint(Entry{"peers", p.line, node});
    return p;
  }
  if (!node.IsMap()) fail(p.line, "a peer must be an address or a map with 'address', got " + describe(node));
  bool has_address = false;
  read_map(node, "transport.peers", p.line,
           {{"address", [&](const Entry& e) { p.endpoint = endpoint(e), has_address = true; }},
            {"framing", [&](const Entry& e) { p.framing = framing(e); }}});
  if (!has_address) fail(p.line, "a peer needs an 'address'");
  return p;
}

ComponentSpec component(const YAML::Node& node) {
  ComponentSpec spec;
  spec.line = line_of(node);
  if (!node.IsMap()) fail(spec.line, "a component must be a map with a 'kind', got " + describe(node));
  std::optional<std::uint8_t> id;
  std::optional<std::string> name;
  YAML::Node options;
  int options_line = 0;
  read_map(node, "components", spec.line,
           {{"kind",
             [&](const Entry& e) {
               spec.kind = e.scalar("a component kind");
               if (!find_component_kind(spec.kind)) {
                 std::vector<std::string_view> names;
                 for (const auto& k : component_kinds()) names.push_back(k.name);
                 fail(e.value_line(),
                      "unknown component kind " + jaus::quoted(spec.kind) + " (known: " + join(names) + ")");
               }
             }},
            {"id", [&](const Entry& e) { id = integer<std::uint8_t>(e, kAddressMin, kAddressMax); }},
            {"instance", [&](const Entry& e) { spec.instance = integer<std::uint8_t>(e, kAddressMin, kAddressMax); }},
            {"authority", [&](const Entry& e) { spec.authority = integer<std::uint8_t>(e, 0, 255); }},
            {"name", [&](const Entry& e) { name = identification(e); }},
            {"options", [&](const Entry& e) { options = e.value, options_line = e.key_line; }}});
  const ComponentKind* kind = find_component_kind(spec.kind);
  if (!kind) {
    std::vector<std::string_view> names;
    for (const auto& k : component_kinds()) names.push_back(k.name);
    fail(spec.line, "a component needs a 'kind' (one of " + join(names) + ")");
  }
  spec.id = id.value_or(kind->default_id);
  spec.name = name.value_or(std::string(kind->name));
  // Option keys depend on the kind, so the map is read here.
  if (options.IsDefined() && !options.IsNull()) {
    if (!options.IsMap()) fail(options_line, "'options' must be a map of keys, got " + describe(options));
    for (auto it = options.begin(); it != options.end(); ++it) {
      const YAML::Node key_node = it->first;
      const YAML::Node value = it->second;
      const int line = line_of(key_node);
      const std::string key = key_node.IsScalar() ? key_node.Scalar() : "";
      if (key.empty() || !one_of(key, kind->options))
        fail(line, "unknown option " + jaus::quoted(key) + " for " + spec.kind + " (known: " + join(kind->options) + ")");
      if (spec.options.contains(key)) fail(line, "duplicate option " + jaus::quoted(key));
      spec.option_lines[key] = line;
      if (!value.IsScalar())
        fail(line, "option " + jaus::quoted(key) + " must be a single value, got " + describe(value));
      spec.options[key] = value.Scalar();
    }
  }
  return spec;
}

// The simulated vehicle of the mobility components (components/vehicle/simulated_vehicle.hpp).
// jss: the JSS face (docs/configuration.md "jss").
void read_jss(const Entry& section, JssConfig& j) {
  read_map(
      section.value, "jss", section.key_line,
      {{"enabled", [&](const Entry& e) { j.enabled = boolean(e); }},
       {"subsystem",
        [&](const Entry& e) {
          if (e.is_null()) j.subsystem.reset();
          else j.subsystem = integer<std::uint16_t>(e, 1, kJssSubsystemMax);
        }},
       {"components",
        [&](const Entry& e) {
          j.components.clear();
          if (e.is_null()) return;
          if (!e.value.IsMap()) e.must_be("a map of component names (or kinds) to JSS component IDs 1..254");
          std::map<std::string, int> seen;
          for (auto it = e.value.begin(); it != e.value.end(); ++it) {
            const YAML::Node key = it->first;
            const YAML::Node value = it->second;
            if (!key.IsScalar()) fail(line_of(key), "jss.components keys must be component names, got " + describe(key));
            const int line = line_of(key);
            if (const auto [first, inserted] = seen.emplace(key.Scalar(), line); !inserted)
              fail(line, "duplicate key " + jaus::quoted(key.Scalar()) + " in jss.components" + first_at(first->second));
            const Entry id{key.Scalar(), line, value};
            j.components.push_back(JssComponentId{key.Scalar(), integer<std::uint8_t>(id, kAddressMin, kAddressMax), line});
          }
        }},
       {"client_alias_subsystem",
        [&](const Entry& e) { j.client_alias_subsystem = integer<std::uint8_t>(e, kAddressMin, kAddressMax); }},
       {"multicast",
        [&](const Entry& e) {
          if (e.is_null()) j.multicast.reset();
          else j.multicast = endpoint(e);
          if (j.multicast && !j.multicast->is_multicast())
            fail(e.value_line(), "'multicast' must be a group 224.0.0.0..239.255.255.255, got " +
                                     jaus::quoted(jaus::transport::ipv4_to_string(j.multicast->address)));
        }},
       {"max_clients", [&](const Entry& e) { j.max_clients = integer<std::size_t>(e, 1, kMaxJssClients); }},
       {"max_events", [&](const Entry& e) { j.max_events = integer<std::size_t>(e, 1, kMaxJssEvents); }},
       {"max_events_per_client",
        [&](const Entry& e) { j.max_events_per_client = integer<std::size_t>(e, 1, kMaxJssEventsPerClient); }},
       {"event_timeout_min", [&](const Entry& e) { j.event_timeout_min = integer<std::uint8_t>(e, 0, 255); }},
       {"change_poll_period_s", [&](const Entry& e) { j.change_poll_period_s = number(e, kPollPeriodRange); }},
       {"max_packet_contents", [&](const Entry& e) {
          j.max_packet_contents = integer<std::size_t>(e, kMinPacketContents, kMaxPacketContents);
        }}});
}

void read_vehicle(const Entry& section, jaus::components::SimulatedVehicleConfig& v) {
  const auto in_range = [](const NumberRange& range) {
    return [&range](double& target) { return [&range, &target](const Entry& e) { target = number(e, range); }; };
  };
  const auto speed = in_range(kSpeedRange), length = in_range(kLengthRange), accel = in_range(kAccelerationRange),
             accuracy = in_range(kAccuracyRange);
  read_map(
      section.value, "vehicle", section.key_line,
      {{"name",
        [&](const Entry& e) {
          const std::string& text = e.scalar("1..15 printable ASCII characters");
          if (text.empty() || text.size() > kMaxPlatformName ||
              !std::all_of(text.begin(), text.end(), [](char ch) { return ch >= 0x20 && ch < 0x7F; }))
            e.must_be("1..15 printable ASCII characters");
          v.specifications.name = text;
        }},
       {"steering",
        [&](const Entry& e) {
          v.steering = choice(e, kSteerings) == "ackermann" ? jaus::components::Steering::ackermann
                                                             : jaus::components::Steering::differential;
        }},
       {"max_speed_mps", speed(v.max_speed_mps)},
       {"max_yaw_rate_rps", in_range(kYawRateRange)(v.max_yaw_rate_rps)},
       {"max_steering_rad", in_range(kSteeringRange)(v.max_steering_rad)},
       {"wheel_base_m", length(v.wheel_base_m)},
       {"track_width_m", [&](const Entry& e) { v.specifications.track_width_m = number(e, kLengthRange); }},
       {"max_acceleration_mps2", accel(v.max_acceleration_mps2)},
       {"max_deceleration_mps2", accel(v.max_deceleration_mps2)},
       {"max_yaw_acceleration_rps2", accel(v.max_yaw_acceleration_rps2)},
       {"update_rate_hz", in_range(kUpdateRateRange)(v.update_rate_hz)},
       {"local_frame", [&](const Entry& e) { v.local_frame = boolean(e); }},
       {"battery_drain_percent_per_hour", in_range(kPercentRange)(v.battery_drain_percent_per_hour)},
       {"start",
        [&](const Entry& s) {
          read_map(s.value, "vehicle.start", s.key_line,
                   {{"latitude_deg", in_range(kLatitudeRange)(v.start.latitude_deg)},
                    {"longitude_deg", in_range(kLongitudeRange)(v.start.longitude_deg)},
                    {"altitude_m", in_range(kAltitudeRange)(v.start.altitude_m)},
                    {"heading_deg", [&](const Entry& e) {
                       v.start_heading_rad = number(e, kHeadingRange) * std::numbers::pi / 180;
                     }}});
        }},
       {"accuracy", [&](const Entry& s) {
          read_map(s.value, "vehicle.accuracy", s.key_line,
                   {{"position_rms_m", accuracy(v.position_rms_m)},
                    {"position_rms_per_m", accuracy(v.position_rms_per_m)},
                    {"attitude_rms_rad", accuracy(v.attitude_rms_rad)},
                    {"velocity_rms_mps", accuracy(v.velocity_rms_mps)},
                    {"rate_rms_rps", accuracy(v.rate_rms_rps)}});
        }}});
  // The specifications follow the model, so Report Platform Specifications says what it drives like.
  v.specifications.wheel_base_m = v.wheel_base_m;
}

JausdConfig read_config(const YAML::Node& root, SourceLines& lines) {
  JausdConfig c;
  const int no_line = 0;
  read_map(
      root, "", no_line,
      {{"identification",
        [&](const Entry& s) {
          read_map(s.value, "identification", s.key_line,
                   {{"subsystem",
                     [&](const Entry& e) { c.subsystem = integer<std::uint8_t>(e, kAddressMin, kAddressMax); }},
                    {"subsystem_name", [&](const Entry& e) { c.subsystem_name = identification(e); }},
                    {"subsystem_type",
                     [&](const Entry& e) { c.subsystem_type = integer<std::uint16_t>(e, 0, 65535); }},
                    {"node", [&](const Entry& e) { c.node = integer<std::uint8_t>(e, kAddressMin, kAddressMax); }},
                    {"node_name", [&](const Entry& e) { c.node_name = identification(e); }},
                    {"node_type", [&](const Entry& e) { c.node_type = integer<std::uint16_t>(e, 0, 65535); }}});
        }},
       {"dialect", [&](const Entry& e) { c.dialect = choice(e, kDialects); }},
       {"heartbeat_hz", [&](const Entry& e) { c.heartbeat_hz = number(e, kHeartbeatRange); }},
       {"control",
        [&](const Entry& s) {
          lines.control = s.key_line;
          read_map(s.value, "control", s.key_line,
                   {{"controller_timeout_s",
                     [&](const Entry& e) { c.controller_timeout_s = number(e, kTimeoutRange); }},
                    {"reject_refused", [&](const Entry& e) { c.reject_refused_control = boolean(e); }},
                    {"unsafe_no_controller_timeout",
                     [&](const Entry& e) { c.unsafe_no_controller_timeout = boolean(e); }}});
        }},
       {"service_connections",
        [&](const Entry& s) {
          lines.service_connections = s.key_line;
          auto& sc = c.service_connections;
          read_map(s.value, "service_connections", s.key_line,
                   {{"max_rate_hz", [&](const Entry& e) { sc.max_rate_hz = number(e, kRateRange); }},
                    {"max_connections",
                     [&](const Entry& e) { sc.max_connections = integer<std::size_t>(e, 1, kMaxConnectionsLimit); }},
                    {"max_total_rate_hz", [&](const Entry& e) { sc.max_total_rate_hz = number(e, kTotalRateRange); }},
                    {"deadman_periods", [&](const Entry& e) { sc.deadman_periods = number(e, kDeadmanPeriodsRange); }},
                    {"deadman_minimum_s", [&](const Entry& e) { sc.deadman_minimum_s = number(e, kTimeoutRange); }},
                    {"deadman_maximum_s",
                     [&](const Entry& e) { sc.deadman_maximum_s = number(e, kPositiveTimeoutRange); }}});
        }},
       {"liveness",
        [&](const Entry& s) {
          auto& l = c.liveness;
          read_map(s.value, "liveness", s.key_line,
                   {{"component_timeout_s",
                     [&](const Entry& e) { l.component_timeout_s = number(e, kPositiveTimeoutRange); }},
                    {"node_timeout_s", [&](const Entry& e) { l.node_timeout_s = number(e, kPositiveTimeoutRange); }},
                    {"subsystem_timeout_s",
                     [&](const Entry& e) { l.subsystem_timeout_s = number(e, kPositiveTimeoutRange); }},
                    {"max_entries", [&](const Entry& e) {
                       l.max_entries = integer<std::size_t>(e, kMinLivenessEntries, kMaxLivenessEntries);
                     }}});
        }},
       {"transport",
        [&](const Entry& s) {
          auto& t = c.transport;
          std::vector<PeerEntry> peers;
          read_map(
              s.value, "transport", s.key_line,
              {{"bind", [&](const Entry& e) { t.bind = endpoint(e); }},
               {"framing", [&](const Entry& e) { t.framing = framing(e); }},
               {"multicast",
                [&](const Entry& e) {
                  if (e.is_null()) t.multicast.reset();
                  else t.multicast = endpoint(e);
                  if (t.multicast && !t.multicast->is_multicast())
                    fail(e.value_line(), "'multicast' must be a group 224.0.0.0..239.255.255.255, got " +
                                             jaus::quoted(jaus::transport::ipv4_to_string(t.multicast->address)));
                }},
               {"multicast_framing", [&](const Entry& e) { t.multicast_framing = framing(e); }},
               {"broadcast_to_peers", [&](const Entry& e) { t.broadcast_to_peers = boolean(e); }},
               {"relay", [&](const Entry& e) { t.relay = boolean(e); }},
               {"peers",
                [&](const Entry& e) {
                  for (const auto& item : read_list(e)) peers.push_back(peer(item));
                }},
               {"allow",
                [&](const Entry& e) {
                  for (const auto& item : read_list(e)) {
                    if (!item.IsScalar())
                      fail(line_of(item), "'allow' entries must be a.b.c.d/prefix, got " + describe(item));
                    auto cidr = jaus::transport::parse_cidr(item.Scalar());
                    if (!cidr) fail(line_of(item), "'allow': " + cidr.error().message());
                    t.allow.push_back(*cidr);
                  }
                }},
               {"control_from",
                [&](const Entry& e) {
                  t.control_from.clear();
                  t.control_from_local = false;  // the list given replaces the default [local]
                  for (const auto& item : read_list(e)) {
                    if (!item.IsScalar())
                      fail(line_of(item), "'control_from' entries must be a.b.c.d/prefix or local, got " +
                                              describe(item));
                    if (item.Scalar() == "local") {
                      t.control_from_local = true;
                      continue;
                    }
                    auto cidr = jaus::transport::parse_cidr(item.Scalar());
                    if (!cidr) fail(line_of(item), "'control_from': " + cidr.error().message() + " (or local)");
                    t.control_from.push_back(*cidr);
                  }
                }},
               {"verify_endpoints", [&](const Entry& e) { t.verify_endpoints = boolean(e); }},
               {"unverified_burst_bytes",
                [&](const Entry& e) { t.unverified_burst_bytes = integer<std::size_t>(e, 0, kMaxUnverifiedBytes); }},
               {"unverified_bytes_per_second",
                [&](const Entry& e) {
                  t.unverified_bytes_per_second = integer<std::size_t>(e, 0, kMaxUnverifiedBytes);
                }},
               {"unverified_total_burst_bytes",
                [&](const Entry& e) {
                  t.unverified_total_burst_bytes = integer<std::size_t>(e, 0, kMaxUnverifiedTotalBytes);
                }},
               {"unverified_total_bytes_per_second",
                [&](const Entry& e) {
                  t.unverified_total_bytes_per_second = integer<std::size_t>(e, 0, kMaxUnverifiedTotalBytes);
                }},
               {"max_peers",
                [&](const Entry& e) { t.max_peers = integer<std::size_t>(e, 1, kMaxPeersLimit); }}});
          for (const auto& p : peers) {
            t.peers.push_back(StaticPeer{p.endpoint, p.framing.value_or(t.framing)});
            lines.peers.push_back(p.line);
          }
        }},
       {"jss",
        [&](const Entry& s) {
          lines.jss = s.key_line;
          read_jss(s, c.jss);
        }},
       {"emergency_scope",
        [&](const Entry& e) {
          c.emergency_scope = choice(e, kEmergencyScopes) == "component" ? jaus::host::EmergencyScope::component
                                                                          : jaus::host::EmergencyScope::vehicle;
        }},
       {"state_directory", [&](const Entry& e) { c.state_directory = e.scalar("a directory jausd may write"); }},
       {"vehicle", [&](const Entry& s) { read_vehicle(s, c.vehicle); }},
       {"platform",
        [&](const Entry& s) {
          lines.platform = s.key_line;
          read_platform(s, c.platform);
        }},
       {"clearpath",
        [&](const Entry& s) {
          lines.clearpath = s.key_line;
          read_clearpath(s, c.clearpath);
        }},
       {"cameras",
        [&](const Entry& s) {
          lines.cameras = s.key_line;
          read_cameras(s, c.cameras);
        }},
       {"manipulator",
        [&](const Entry& s) {
          lines.manipulator = s.key_line;
          read_manipulator(s, c.manipulator);
        }},
       {"plugins", [](const Entry&) {}},  // loaded before this read (load_config_string)
       {"components",
        [&](const Entry& e) {
          lines.components = e.key_line;
          if (e.is_null()) return;  // defaults
          c.components.clear();
          for (const auto& item : read_list(e)) c.components.push_back(component(item));
        }},
       {"logging", [&](const Entry& s) {
          read_map(s.value, "logging", s.key_line,
                   {{"level", [&](const Entry& e) { c.log_level = choice(e, kLogLevels); }}});
        }}});
  return c;
}

}  // namespace

// ---------------------------------------------------------------- loading

namespace {

// What the text holds besides comments and blank lines: the first line with
// content, and the line of a second document's separator, if any. Needed
// because yaml-cpp 0.7's LoadAll never returns on some inputs (",1" loops
// allocating), so documents are told apart here and only Load is used.
struct TextShape {
  int first_content_line = 0;   // 0: nothing but comments and blank lines
  std::string first_content;
  int second_document_line = 0;
};

TextShape shape_of(std::string_view text) {
  TextShape shape;
  int line = 0;
  bool content_since_separator = false;
  while (!text.empty()) {
    ++line;
    const std::size_t end = text.find('\n');
    std::string_view l = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
    std::string_view trimmed = l;
    while (!trimmed.empty() && (trimmed.front() == ' ' || trimmed.front() == '\t')) trimmed.remove_prefix(1);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    const bool separator = l == "---" || l.starts_with("--- ") || l == "...";
    if (separator) {
      if (content_since_separator && shape.second_document_line == 0 && l != "...") shape.second_document_line = line;
      continue;
    }
    if (shape.second_document_line != 0 && !content_since_separator) break;
    content_since_separator = true;
    if (shape.first_content_line == 0) {
      shape.first_content_line = line;
      shape.first_content = std::string(trimmed);
    }
  }
  return shape;
}

}  // namespace

namespace {

// The plugins come first, wherever the key is in the file: the components
// that name their kinds are read and checked as the file's other keys.
std::vector<jaus::host::LoadedPlugin> load_listed_plugins(const YAML::Node& root,
                                                          const std::optional<std::filesystem::path>& folder) {
  if (!root.IsMap()) return {};
  for (auto it = root.begin(); it != root.end(); ++it) {
    const YAML::Node key = it->first;
    if (key.IsScalar() && key.Scalar() == "plugins") return load_plugins(Entry{"plugins", line_of(key), it->second}, folder);
  }
  return {};
}

}  // namespace

ConfigResult load_config_string(std::string_view yaml, std::string_view name,
                                const std::optional<std::filesystem::path>& plugin_folder) {
  const std::string file(name);
  try {
    const TextShape shape = shape_of(yaml);
    if (shape.second_document_line != 0)
      return jaus::unexpected(config_error(file, shape.second_document_line,
                                           "a configuration holds one YAML document, this starts a second one"));
    const YAML::Node root = YAML::Load(std::string(yaml));
    // yaml-cpp reads some junk (",1") as an empty document: only an empty
    // file, or an explicit null, means "all defaults".
    const bool explicit_null = shape.first_content == "~" || shape.first_content == "null" ||
                               shape.first_content == "Null" || shape.first_content == "NULL";
    if ((!root.IsDefined() || root.IsNull()) && shape.first_content_line != 0 && !explicit_null)
      return jaus::unexpected(
          config_error(file, shape.first_content_line,
                       "not a YAML mapping of settings: '" + shape.first_content.substr(0, 40) + "'"));
    SourceLines lines;
    auto plugins = load_listed_plugins(root, plugin_folder);
    JausdConfig config = read_config(root, lines);
    config.plugins = std::move(plugins);
    if (auto issue = check(config, lines)) return jaus::unexpected(config_error(file, issue->line, issue->what));
    return config;
  } catch (const Failure& f) {
    return jaus::unexpected(config_error(file, f.line, f.what));
  } catch (const YAML::Exception& e) {
    const int line = e.mark.is_null() ? 0 : e.mark.line + 1;
    return jaus::unexpected(config_error(file, line, "YAML syntax error: " + e.msg));
  } catch (const std::exception& e) {
    return jaus::unexpected(config_error(file, 0, std::string("cannot read the configuration: ") + e.what()));
  }
}

ConfigResult load_config_file(const std::string& path) {
  constexpr std::uintmax_t kMaxFileSize = 1024 * 1024;
  const auto cannot_open = [&](const std::string& reason) {
    return jaus::unexpected(config_error(path, 0, "cannot open " + path + ": " + reason));
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return cannot_open("is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) return cannot_open(std::strerror(errno));
  std::string text;
  char buffer[4096];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileSize) return cannot_open("larger than 1 MiB, not a configuration file");
  }
  if (in.bad()) return cannot_open(std::strerror(errno));
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  return load_config_string(text, path, folder.empty() ? std::filesystem::path(".") : folder);
}

std::vector<std::string> posture_warnings(const JausdConfig& c) {
  const auto& t = c.transport;
  std::vector<std::string> warnings;
  // A node bound to loopback is reachable from this machine only: nothing to warn about.
  if ((t.bind.address >> 24) == 127) return warnings;
  const bool anyone = (t.control_from.empty() && !t.control_from_local) ||
                      std::any_of(t.control_from.begin(), t.control_from.end(),
                                  [](const jaus::transport::Cidr& cidr) { return cidr.prefix_length == 0; });
  if (anyone)
    warnings.push_back("transport.control_from lets any host that reaches " + jaus::transport::to_string(t.bind) +
                       " take control of this node's components and change their state; list the operators' "
                       "networks instead (default: [local], this machine's own networks)");
  if (!t.verify_endpoints)
    warnings.push_back("transport.verify_endpoints is off: a small query with a forged source address gets a "
                       "large reply (Report Image), so this node can be used to flood another host");
  return warnings;
}

}  // namespace jausd
