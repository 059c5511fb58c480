#include "jaus/components/global_pose_sensor.hpp"

#include "jaus/components/pose_reports.hpp"

namespace jaus::components {

GlobalPoseSensor::GlobalPoseSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source,
                                   GlobalPoseSensorOptions options)
    : SensorComponent(std::move(config), std::move(env), source, options.sensor) {
  const std::function<msg::ReportGlobalPose(const PoseSample&)> global = &GlobalPoseSensor::global_pose;
  serve<msg::QueryGlobalPose>(available_fields(global), global);

  // Without local positions Query Local Pose stays unsupported, and Report
  // Services does not list it: answering with attitude alone would pass for a
  // local frame the source does not have.
  const auto sample = source.sample();
  serves_local_pose_ = options.local_pose && (!sample || sample->local_position.has_value());
  if (serves_local_pose_) {
    const std::function<msg::ReportLocalPose(const PoseSample&)> local = &GlobalPoseSensor::local_pose;
    serve<msg::QueryLocalPose>(available_fields(local), local);
  }
}

// The reports are the vehicle's pose reports (pose_reports.hpp), shared with
// the local pose sensor.
msg::ReportGlobalPose GlobalPoseSensor::global_pose(const PoseSample& sample) { return global_pose_report(sample); }

msg::ReportLocalPose GlobalPoseSensor::local_pose(const PoseSample& sample) { return local_pose_report(sample); }

}  // namespace jaus::components
