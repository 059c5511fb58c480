#include "jaus/host/component_kinds.hpp"

#include "jaus/components/communicator.hpp"
#include "jaus/components/global_pose_sensor.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/components/primitive_manipulator.hpp"
#include "jaus/components/visual_sensor.hpp"
#include "jaus/components/velocity_state_sensor.hpp"
#include "jaus/host/component_options.hpp"

namespace jaus::host {

namespace {

const std::vector<ComponentKind>& kinds() {
  // Register a kind only once make_component() can build it.
  static const std::vector<ComponentKind> registry{
      {"node_manager", 1, {}},
      {"communicator", 35, {}},
      {"primitive_driver", 33, {"command_timeout_s", "stop_brake_percent"}},
      {"global_pose_sensor", 38, {"stale_after_s", "local_pose"}},
      {"velocity_state_sensor", 42, {"stale_after_s"}},
      {"visual_sensor", 37, {"image_connections_per_requester"}},
      {"primitive_manipulator", 49, {"command_timeout_s"}},
  };
  return registry;
}

}  // namespace

std::span<const ComponentKind> component_kinds() { return kinds(); }

const ComponentKind* find_component_kind(std::string_view name) {
  for (const auto& kind : kinds())
    if (kind.name == name) return &kind;
  return nullptr;
}

Hardware hardware_of(std::string_view kind) {
  if (kind == "primitive_driver" || kind == "global_pose_sensor" || kind == "velocity_state_sensor")
    return Hardware::vehicle;
  if (kind == "visual_sensor") return Hardware::cameras;
  if (kind == "primitive_manipulator") return Hardware::arm;
  return Hardware::none;
}

bool needs_vehicle(std::string_view kind) { return hardware_of(kind) == Hardware::vehicle; }

bool moves_hardware(std::string_view kind) {
  return kind == "primitive_driver" || kind == "primitive_manipulator" || kind == "visual_sensor";
}

Expected<std::unique_ptr<rt::Component>> make_component(const ComponentSpec& spec, const ComponentSettings& settings,
                                                        node::Node& node, const VehicleBackends& vehicle) {
  rt::ComponentConfig c = settings.defaults;
  c.name = spec.name.empty() ? spec.kind : spec.name;
  c.address = Address{node.config().subsystem, node.config().node, spec.id, spec.instance};
  c.authority = spec.authority;
  std::unique_ptr<rt::Component> made;
  if (spec.kind == "node_manager")
    made = std::make_unique<components::NodeManager>(c, node.environment(), node, settings.identity);
  else if (spec.kind == "communicator")
    made = std::make_unique<components::Communicator>(
        c, node.environment(), components::CommunicatorConfig{1, settings.identity.heartbeat_period});
  else if (needs_vehicle(spec.kind)) {
    const bool drives = spec.kind == "primitive_driver";
    if (drives ? !vehicle.drive : !vehicle.pose)
      return unexpected(make_error(ErrorCode::invalid_argument, spec.kind + " needs a vehicle " +
                                                                    (drives ? "drive" : "pose source") +
                                                                    " and the host has none"));
    if (spec.kind == "primitive_driver") {
      auto options = primitive_driver_options(spec);
      if (!options) return unexpected(options.error());
      made = std::make_unique<components::PrimitiveDriver>(c, node.environment(), *vehicle.drive, *options);
    } else if (spec.kind == "global_pose_sensor") {
      auto options = global_pose_sensor_options(spec);
      if (!options) return unexpected(options.error());
      made = std::make_unique<components::GlobalPoseSensor>(c, node.environment(), *vehicle.pose, *options);
    } else {
      auto options = velocity_state_sensor_options(spec);
      if (!options) return unexpected(options.error());
      made = std::make_unique<components::VelocityStateSensor>(c, node.environment(), *vehicle.pose, *options);
    }
  }
  else if (spec.kind == "visual_sensor") {
    if (!vehicle.cameras)
      return unexpected(make_error(ErrorCode::invalid_argument, "visual_sensor needs cameras and the host has none"));
    auto options = visual_sensor_options(spec);
    if (!options) return unexpected(options.error());
    made = std::make_unique<components::VisualSensor>(c, node.environment(), *vehicle.cameras, *options);
  } else if (spec.kind == "primitive_manipulator") {
    if (!vehicle.arm)
      return unexpected(
          make_error(ErrorCode::invalid_argument, "primitive_manipulator needs an arm and the host has none"));
    auto options = primitive_manipulator_options(spec);
    if (!options) return unexpected(options.error());
    made = std::make_unique<components::PrimitiveManipulator>(c, node.environment(), *vehicle.arm, *options);
  }
  if (made) return made;
  return unexpected(make_error(ErrorCode::invalid_argument,
                               "component kind '" + spec.kind + "' cannot be hosted by this build"));
}

}  // namespace jaus::host
