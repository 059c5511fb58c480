// The global pose sensor (component 38): the platform's WGS 84 position and
// attitude (Query/Report Global Pose), and its position in the source's local
// frame (Query/Report Local Pose, Part 3's deprecated-at-4.0 local pose) where
// the source has one, from a PoseSource. Presence, service connections and
// staleness as every sensor (sensor_component.hpp).
#pragma once

#include "jaus/components/sensor_component.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

struct GlobalPoseSensorOptions {
  SensorOptions sensor;
  // Serve Local Pose too, when the source has local positions.
  bool local_pose = true;
};

class GlobalPoseSensor final : public SensorComponent {
 public:
  // Whether the source has local positions is read from its sample now; a
  // source without a sample yet is taken at the option's word.
  GlobalPoseSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source,
                   GlobalPoseSensorOptions options = {});

  // Query Local Pose is handled (and Report Local Pose provided).
  bool serves_local_pose() const { return serves_local_pose_; }

  // The reports of a sample, with every field it has.
  static msg::ReportGlobalPose global_pose(const PoseSample& sample);
  static msg::ReportLocalPose local_pose(const PoseSample& sample);

 private:
  bool serves_local_pose_ = false;
};

}  // namespace jaus::components
