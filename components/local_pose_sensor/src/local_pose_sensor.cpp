#include "jaus/components/local_pose_sensor.hpp"

#include "jaus/components/pose_reports.hpp"

namespace jaus::components {

LocalPoseSensor::LocalPoseSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source,
                                 SensorOptions options)
    : SensorComponent(std::move(config), std::move(env), source, options) {
  // A sample without a local position (a source whose frame is turned off,
  // and which had no sample when the kind checked it) is said once in the log.
  const std::function<msg::ReportLocalPose(const PoseSample&)> local = [this](const PoseSample& sample) {
    if (!sample.local_position && !said_no_local_frame_) {
      said_no_local_frame_ = true;
      log(rt::LogLevel::warn,
          "its pose source gives no local position (vehicle.local_frame: false?): Report Local Pose carries no x, y, z");
    }
    return local_pose(sample);
  };
  serve<msg::QueryLocalPose>(available_fields(local), local);
}

// The global pose sensor's Local Pose is the same report (pose_reports.hpp).
msg::ReportLocalPose LocalPoseSensor::local_pose(const PoseSample& sample) { return local_pose_report(sample); }

}  // namespace jaus::components
