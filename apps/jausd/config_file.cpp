// jausd.yaml read into a JausdConfig (load_config_file, load_config_string):
// every key read where it stands, each error with its file and line, then the
// whole configuration checked by the rules of config_rules.hpp.
#include "jausd_config.hpp"

#include "config_reader.hpp"
#include "config_rules.hpp"
#include "hardware_config.hpp"
#include "host_config.hpp"
#include "plugins_config.hpp"

#include "jaus/base/quoted.hpp"
#include "jaus/host/component_options.hpp"
#include "jaus/host/http_token.hpp"
#include "jaus/host/metrics_server.hpp"

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
using namespace config_rules;

using jaus::transport::Framing;
using jaus::transport::Ipv4Endpoint;
using jaus::transport::StaticPeer;
using jaus::host::component_kinds;
using jaus::host::ComponentKind;
using jaus::host::find_component_kind;

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

// metrics: {listen: ADDR[:PORT] (9794 when left out; null: off), token: TEXT}.
// Beyond loopback only with a token, as jaus-console's page.
void read_metrics(const Entry& section, MetricsConfig& m) {
  int listen_line = section.key_line;
  read_map(section.value, "metrics", section.key_line,
           {{"listen",
             [&](const Entry& e) {
               listen_line = e.value_line();
               if (e.is_null()) {
                 m.listen.reset();
                 return;
               }
               auto parsed = jaus::transport::parse_endpoint(e.scalar("an IPv4 address a.b.c.d[:port]"),
                                                             jaus::host::kDefaultMetricsPort);
               if (!parsed) fail(e.value_line(), "'listen': " + parsed.error().message());
               m.listen = *parsed;
             }},
            {"token", [&](const Entry& e) { m.token = e.scalar("a token scrapes must give"); }}});
  if (m.listen && !jaus::host::is_loopback_address(m.listen->address) && m.token.empty())
    fail(listen_line, "'metrics.listen' " + jaus::quoted(jaus::transport::to_string(*m.listen)) +
                          " is beyond loopback: give 'metrics.token' too (scrapes then send it as a bearer token)");
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
                [&](const Entry& e) { t.max_peers = integer<std::size_t>(e, 1, kMaxPeersLimit); }},
               {"send_rate_kbit",
                [&](const Entry& e) {
                  t.send_rate_kbit = integer<std::uint64_t>(e, 0, kMaxSendRateKbit);
                  if (t.send_rate_kbit != 0 && t.send_rate_kbit < kMinSendRateKbit)
                    fail(e.value_line(), "'send_rate_kbit' must be 0 (no budget) or " +
                                             std::to_string(kMinSendRateKbit) + ".." +
                                             std::to_string(kMaxSendRateKbit) + ", got " +
                                             std::to_string(t.send_rate_kbit));
                }},
               {"send_queue_bytes",
                [&](const Entry& e) {
                  t.send_queue_bytes = integer<std::size_t>(e, kMinSendQueueBytes, kMaxSendQueueBytes);
                }},
               {"receive_buffer_bytes", [&](const Entry& e) {
                  t.receive_buffer_bytes = integer<std::size_t>(e, 0, kMaxReceiveBufferBytes);
                }}});
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
       {"metrics", [&](const Entry& s) { read_metrics(s, c.metrics); }},
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

}  // namespace jausd
