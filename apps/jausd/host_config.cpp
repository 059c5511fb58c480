#include "host_config.hpp"

#include <algorithm>

#include "jaus/host/clearpath_platform.hpp"

namespace jausd {

// The platform and the bridge's mapping: the vehicle's figures from `vehicle:`,
// the protocol's options from `clearpath:`.
jaus::host::PlatformSettings platform_settings(const JausdConfig& config) {
  namespace cp = jaus::clearpath;
  const auto& v = config.vehicle;
  const auto& o = config.clearpath;
  jaus::host::PlatformSettings settings;
  settings.kind = config.platform.kind;
  settings.options = config.platform.options;
  jaus::host::ClearpathSettings& p = settings.sections.set(jaus::host::ClearpathSettings{});
  const auto max_age = std::chrono::milliseconds(static_cast<long long>(o.setpoint_max_age_s * 1000));
  p.client.setpoint_max_age = max_age;

  // The simulated platform drives like the configured vehicle.
  p.sim.vehicle.drive = v.steering == jaus::components::Steering::ackermann ? cp::sim::Drive::ackermann
                                                                            : cp::sim::Drive::differential;
  p.sim.vehicle.track_width = v.specifications.track_width_m.value_or(0.55);
  p.sim.vehicle.wheelbase = v.wheel_base_m;
  p.sim.vehicle.max_steering_angle = v.max_steering_rad;
  p.sim.name = v.specifications.name;

  auto& b = p.vehicle;
  b.drive = drive_mode(o, v.steering);
  b.brake = o.brake;
  b.gear = o.gear;
  b.main_power = o.main_power;
  b.parking_brake = o.parking_brake;
  b.horn = o.horn;
  b.heading_from_orientation = o.heading_from_orientation;
  b.data_rate_hz = o.data_rate_hz;
  b.setpoint_max_age = max_age;
  b.nominal_battery_v = o.nominal_battery_v;
  b.max_encoder_step_m = o.max_encoder_step_m;
  b.emergency_flags = o.emergency_flags;
  b.platform_stop_flags = o.platform_stop_flags;
  b.platform_status_flags = o.platform_status_flags;
  b.max_speed_mps = v.max_speed_mps;
  b.max_yaw_rate_rps = v.max_yaw_rate_rps;
  b.max_acceleration_mps2 = v.max_acceleration_mps2;
  b.track_width_m = v.specifications.track_width_m.value_or(0.55);
  b.wheel_base_m = v.wheel_base_m;
  b.max_steering_rad = v.max_steering_rad;
  b.specifications = v.specifications;
  b.datum = v.start;
  b.datum_heading_rad = v.start_heading_rad;
  b.local_frame = v.local_frame;
  b.position_rms_m = v.position_rms_m;
  b.position_rms_per_m = v.position_rms_per_m;
  b.attitude_rms_rad = v.attitude_rms_rad;
  b.velocity_rms_mps = v.velocity_rms_mps;
  b.rate_rms_rps = v.rate_rms_rps;

  p.cameras.mounts = camera_mounts(o, config.cameras);
  p.arm.joints = arm_joints(o, config.manipulator);
  // The simulated platform has what they are mapped onto.
  for (const auto& m : p.cameras.mounts)
    p.sim.vehicle.mounts = std::max<std::size_t>(p.sim.vehicle.mounts, m.mount + 1u);
  for (const auto& j : p.arm.joints)
    p.sim.vehicle.joints = std::max<std::size_t>(p.sim.vehicle.joints, j.clearpath_joint + 1u);
  return settings;
}

namespace {

using namespace jaus;

rt::Duration seconds(double s) {
  return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(s));
}

}  // namespace

host::HostConfig host_config(const JausdConfig& config) {
  host::HostConfig h;
  h.node.subsystem = config.subsystem;
  h.node.node = config.node;
  h.node.dialect = config.dialect == "openjaus" ? wire::Dialect::openjaus : wire::Dialect::ra;
  h.node.liveness.component_timeout = seconds(config.liveness.component_timeout_s);
  h.node.liveness.node_timeout = seconds(config.liveness.node_timeout_s);
  h.node.liveness.subsystem_timeout = seconds(config.liveness.subsystem_timeout_s);
  h.node.liveness.max_entries = config.liveness.max_entries;

  h.link.bind = config.transport.bind;
  h.link.framing = config.transport.framing;
  h.link.multicast = config.transport.multicast;
  h.link.multicast_framing = config.transport.multicast_framing;
  h.link.broadcast_to_peers = config.transport.broadcast_to_peers;
  h.link.relay = config.transport.relay;
  h.link.peers = config.transport.peers;
  h.link.allow = config.transport.allow;
  // `local` is read now, at start: the machine's networks are those it has when jausd runs.
  h.link.control_from = config.transport.control_from;
  if (config.transport.control_from_local)
    for (const auto& network : transport::local_networks()) h.link.control_from.push_back(network);
  h.link.verify_endpoints = config.transport.verify_endpoints;
  h.link.amplification.unverified_burst_bytes = config.transport.unverified_burst_bytes;
  h.link.amplification.unverified_bytes_per_second = config.transport.unverified_bytes_per_second;
  h.link.amplification.unverified_total_burst_bytes = config.transport.unverified_total_burst_bytes;
  h.link.amplification.unverified_total_bytes_per_second = config.transport.unverified_total_bytes_per_second;
  h.link.routes.max_entries = config.transport.max_peers;
  h.send_budget.bits_per_second = config.transport.send_rate_kbit * 1000;
  h.send_budget.queue_bytes = config.transport.send_queue_bytes;
  h.link.receive_buffer_bytes = config.transport.receive_buffer_bytes;

  rt::ComponentConfig& c = h.settings.defaults;
  c.controller_timeout = seconds(config.controller_timeout_s);
  c.reject_refused_requests = config.reject_refused_control;
  c.service_connections.max_rate_hz = config.service_connections.max_rate_hz;
  c.service_connections.max_connections = config.service_connections.max_connections;
  c.service_connections.max_total_rate_hz = config.service_connections.max_total_rate_hz;
  c.service_connections.deadman_periods = config.service_connections.deadman_periods;
  c.service_connections.deadman_minimum = seconds(config.service_connections.deadman_minimum_s);
  c.service_connections.deadman_maximum = seconds(config.service_connections.deadman_maximum_s);

  components::NodeManagerConfig& identity = h.settings.identity;
  identity.heartbeat_period = seconds(1.0 / config.heartbeat_hz);
  identity.subsystem_name = config.subsystem_name;
  identity.subsystem_type = config.subsystem_type;
  identity.node_name = config.node_name;
  identity.node_type = config.node_type;

  h.components = config.components;
  h.vehicle = config.vehicle;
  h.cameras = config.cameras;
  h.arm = config.manipulator;
  h.platform = platform_settings(config);
  h.emergency.scope = config.emergency_scope;
  h.emergency.state_directory = config.state_directory;

  // The JSS face; its identification and controller timeout are the node's (the host copies them).
  const JssConfig& j = config.jss;
  h.jss.enabled = j.enabled;
  if (j.enabled) {
    h.jss.subsystem = j.subsystem;
    if (auto ids = jss_component_ids(config)) h.jss.component_ids = std::move(*ids);  // checked when loaded
    h.jss.client_alias_subsystem = j.client_alias_subsystem;
    h.jss.max_clients = j.max_clients;
    h.jss.max_events = j.max_events;
    h.jss.max_events_per_client = j.max_events_per_client;
    h.jss.event_timeout_min = j.event_timeout_min;
    h.jss.change_poll_period = seconds(j.change_poll_period_s);
    h.jss.max_packet_contents = j.max_packet_contents;
    h.link.jss_multicast = j.multicast;
  }
  return h;
}

}  // namespace jausd
