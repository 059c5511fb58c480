// The configuration as data: its defaults and the rules every configuration
// must keep (validate(); the file reader, config_file.cpp, checks the same
// rules and names the line).
#include "jausd_config.hpp"

#include "config_reader.hpp"
#include "config_rules.hpp"
#include "hardware_config.hpp"
#include "host_config.hpp"

#include "jaus/base/quoted.hpp"
#include "jaus/host/component_options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace jausd {

using namespace yaml_reader;
using namespace config_rules;

using jaus::transport::Cidr;
using jaus::transport::Ipv4Endpoint;
using jaus::host::component_kinds;
using jaus::host::ComponentKind;
using jaus::host::find_component_kind;

std::vector<ComponentSpec> JausdConfig::default_components() {
  // Each built-in kind that says it is in the default node
  // (ComponentKind::default_node_authority), in the registry's order: at its
  // own RA ID, instance 1, named as its kind, with the authority it gives.
  std::vector<ComponentSpec> components;
  for (const ComponentKind* kind : jaus::host::builtin_component_kinds())
    if (kind->default_node_authority)
      components.push_back(ComponentSpec{std::string(kind->name), kind->default_id, 1, *kind->default_node_authority,
                                         std::string(kind->name), {}, 0, {}});
  return components;
}

jaus::components::VisualSensorConfig JausdConfig::default_cameras() { return jausd::default_cameras(); }
jaus::components::ArmConfig JausdConfig::default_arm() { return jausd::default_arm(); }

// ---------------------------------------------------------------- errors

jaus::Error config_error(std::string_view file, int line, std::string what) {
  std::string where(file);
  if (line > 0) where += ":" + std::to_string(line);
  std::string detail = where + ": " + what;
  return jaus::Error{jaus::ErrorCode::invalid_argument, 0, std::move(where), std::move(detail)};
}

// ---------------------------------------------------------------- validation

namespace config_rules {

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


namespace {



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
  if (t.send_rate_kbit != 0 &&
      (t.send_rate_kbit < static_cast<std::uint64_t>(kMinSendRateKbit) ||
       t.send_rate_kbit > static_cast<std::uint64_t>(kMaxSendRateKbit)))
    return Issue{0, "'send_rate_kbit' must be 0 (no budget) or " + std::to_string(kMinSendRateKbit) + ".." +
                        std::to_string(kMaxSendRateKbit) + ", got " + std::to_string(t.send_rate_kbit)};
  if (t.send_queue_bytes < static_cast<std::size_t>(kMinSendQueueBytes) ||
      t.send_queue_bytes > static_cast<std::size_t>(kMaxSendQueueBytes))
    return Issue{0, "'send_queue_bytes' must be " + std::to_string(kMinSendQueueBytes) + ".." +
                        std::to_string(kMaxSendQueueBytes) + ", got " + std::to_string(t.send_queue_bytes)};
  if (t.receive_buffer_bytes > static_cast<std::size_t>(kMaxReceiveBufferBytes))
    return Issue{0, "'receive_buffer_bytes' must be 0.." + std::to_string(kMaxReceiveBufferBytes) + ", got " +
                        std::to_string(t.receive_buffer_bytes)};
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

}  // namespace

// What is wrong with `c`, and where when `lines` knows (config_rules.hpp).
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

}  // namespace config_rules

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

