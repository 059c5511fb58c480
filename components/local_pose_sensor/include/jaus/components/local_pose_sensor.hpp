// The local pose sensor (component 41): the platform's position and attitude
// in the local frame of its PoseSource (Query/Report Local Pose): origin at
// the source's datum (the vehicle's configured start, `vehicle.start`), x
// north, y east, z down, metres; roll, pitch and yaw as the global pose's
// (yaw the heading from true north, clockwise). The same frame the local
// waypoints use, from the same source as the global pose sensor. RA 3.3 has
// no Set Local Pose: the origin is configuration, the source's datum, and the
// sensor has no origin of its own (a second origin would let two components
// of one vehicle disagree about where (0, 0) is).
//
// Presence, service connections and staleness as every sensor
// (sensor_component.hpp). A sample without a local position (a source
// without a local frame) gives a report without x, y, z and position RMS,
// never a position made up, and a warning in the log, once; the kind refuses
// a source it knows to have no local frame (local_pose_sensor_kind.hpp).
#pragma once

#include "jaus/components/sensor_component.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

class LocalPoseSensor final : public SensorComponent {
 public:
  LocalPoseSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source, SensorOptions options = {});

  // The report of a sample, with every field it has.
  static msg::ReportLocalPose local_pose(const PoseSample& sample);

 private:
  bool said_no_local_frame_ = false;
};

}  // namespace jaus::components
