#include "host_config.hpp"

namespace jausd {

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

  h.link.bind = config.transport.bind;
  h.link.framing = config.transport.framing;
  h.link.multicast = config.transport.multicast;
  h.link.broadcast_to_peers = config.transport.broadcast_to_peers;
  h.link.peers = config.transport.peers;
  h.link.allow = config.transport.allow;
  h.link.routes.max_entries = config.transport.max_peers;

  rt::ComponentConfig& c = h.settings.defaults;
  c.controller_timeout = seconds(config.controller_timeout_s);
  c.reject_refused_requests = config.reject_refused_control;
  c.service_connections.max_rate_hz = config.service_connections.max_rate_hz;
  c.service_connections.max_connections = config.service_connections.max_connections;
  c.service_connections.deadman_periods = config.service_connections.deadman_periods;
  c.service_connections.deadman_minimum = seconds(config.service_connections.deadman_minimum_s);

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
  return h;
}

}  // namespace jausd
