// The RA 3.x component IDs (docs/wire-format.md, "Component IDs"): the one
// table the component kinds, the JSS face, the console, jausd's default node
// and the OCU's names take them from. An ID is what a component is (its
// services); several instances of one ID on a node differ by instance.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace jaus::component_id {

inline constexpr std::uint8_t kNodeManager = 1;
inline constexpr std::uint8_t kSubsystemCommander = 32;
inline constexpr std::uint8_t kPrimitiveDriver = 33;
inline constexpr std::uint8_t kGlobalVectorDriver = 34;
inline constexpr std::uint8_t kCommunicator = 35;
inline constexpr std::uint8_t kMissionSpooler = 36;
inline constexpr std::uint8_t kVisualSensor = 37;
inline constexpr std::uint8_t kGlobalPoseSensor = 38;
inline constexpr std::uint8_t kMissionPlanner = 39;
inline constexpr std::uint8_t kSystemCommander = 40;
inline constexpr std::uint8_t kLocalPoseSensor = 41;
inline constexpr std::uint8_t kVelocityStateSensor = 42;
inline constexpr std::uint8_t kReflexiveDriver = 43;
inline constexpr std::uint8_t kLocalVectorDriver = 44;
inline constexpr std::uint8_t kGlobalWaypointDriver = 45;
inline constexpr std::uint8_t kLocalWaypointDriver = 46;
inline constexpr std::uint8_t kGlobalPathSegmentDriver = 47;
inline constexpr std::uint8_t kLocalPathSegmentDriver = 48;
inline constexpr std::uint8_t kPrimitiveManipulator = 49;
inline constexpr std::uint8_t kRangeSensor = 50;
// 51-59: the manipulator's joint and end-effector sensors and drivers.
inline constexpr std::uint8_t kFirstManipulatorSensorOrDriver = 51;
inline constexpr std::uint8_t kLastManipulatorSensorOrDriver = 59;
inline constexpr std::uint8_t kWorldModelVectorKnowledgeStore = 61;

struct Named {
  std::uint8_t id;
  std::string_view name;
};

inline constexpr std::array kNames{
    Named{kNodeManager, "node manager"},
    Named{kSubsystemCommander, "subsystem commander"},
    Named{kPrimitiveDriver, "primitive driver"},
    Named{kGlobalVectorDriver, "global vector driver"},
    Named{kCommunicator, "communicator"},
    Named{kMissionSpooler, "mission spooler"},
    Named{kVisualSensor, "visual sensor"},
    Named{kGlobalPoseSensor, "global pose sensor"},
    Named{kMissionPlanner, "mission planner"},
    Named{kSystemCommander, "system commander"},
    Named{kLocalPoseSensor, "local pose sensor"},
    Named{kVelocityStateSensor, "velocity state sensor"},
    Named{kReflexiveDriver, "reflexive driver"},
    Named{kLocalVectorDriver, "local vector driver"},
    Named{kGlobalWaypointDriver, "global waypoint driver"},
    Named{kLocalWaypointDriver, "local waypoint driver"},
    Named{kGlobalPathSegmentDriver, "global path segment driver"},
    Named{kLocalPathSegmentDriver, "local path segment driver"},
    Named{kPrimitiveManipulator, "primitive manipulator"},
    Named{kRangeSensor, "range sensor"},
    Named{kWorldModelVectorKnowledgeStore, "world model vector knowledge store"},
};

// The RA's name for the ID ("primitive driver"); empty for an ID the RA
// assigns to no component.
constexpr std::string_view ra_name(std::uint8_t id) {
  for (const Named& named : kNames)
    if (named.id == id) return named.name;
  if (id >= kFirstManipulatorSensorOrDriver && id <= kLastManipulatorSensorOrDriver)
    return "manipulator sensor/driver";
  return {};
}

}  // namespace jaus::component_id
