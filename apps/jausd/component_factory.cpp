#include "component_factory.hpp"

#include <cmath>

#include "jaus/runtime/communicator.hpp"
#include "jaus/runtime/node_manager.hpp"

namespace jausd {

namespace {

using namespace jaus;

rt::Duration seconds(double s) {
  return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(s));
}

rt::ComponentConfig component_config(const ComponentSpec& spec, const JausdConfig& config) {
  rt::ComponentConfig c;
  c.name = spec.name.empty() ? spec.kind : spec.name;
  c.address = Address{config.subsystem, config.node, spec.id, spec.instance};
  c.authority = spec.authority;
  c.controller_timeout = seconds(config.controller_timeout_s);
  c.reject_refused_requests = config.reject_refused_control;
  c.service_connections.max_rate_hz = config.service_connections.max_rate_hz;
  c.service_connections.max_connections = config.service_connections.max_connections;
  c.service_connections.deadman_periods = config.service_connections.deadman_periods;
  c.service_connections.deadman_minimum = seconds(config.service_connections.deadman_minimum_s);
  return c;
}

}  // namespace

std::unique_ptr<rt::Component> make_component(const ComponentSpec& spec, const JausdConfig& config,
                                              node::Node& node) {
  const rt::ComponentConfig c = component_config(spec, config);
  if (spec.kind == "node_manager") {
    rt::NodeManagerConfig nm;
    nm.heartbeat_period = seconds(1.0 / config.heartbeat_hz);
    nm.subsystem_name = config.subsystem_name;
    nm.subsystem_type = config.subsystem_type;
    nm.node_name = config.node_name;
    nm.node_type = config.node_type;
    return std::make_unique<rt::NodeManager>(c, node.environment(), node, nm);
  }
  if (spec.kind == "communicator") return std::make_unique<rt::Communicator>(c, node.environment());
  return nullptr;
}

}  // namespace jausd
