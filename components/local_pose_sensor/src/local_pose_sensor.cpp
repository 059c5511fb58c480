#include "jaus/components/local_pose_sensor.hpp"

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

msg::ReportLocalPose LocalPoseSensor::local_pose(const PoseSample& sample) {
  msg::ReportLocalPose pose;
  if (sample.local_position) {
    pose.x_m = sample.local_position->x_m;
    pose.y_m = sample.local_position->y_m;
    pose.z_m = sample.local_position->z_m;
    // An RMS goes with its value: without a local position it means nothing here.
    pose.position_rms_m = sample.position_rms_m;
  }
  if (sample.attitude) {
    // Wrapped to (-pi, pi], the range the fields encode.
    pose.roll_rad = wrap_angle(sample.attitude->roll);
    pose.pitch_rad = wrap_angle(sample.attitude->pitch);
    pose.yaw_rad = wrap_angle(sample.attitude->yaw);
    pose.attitude_rms_rad = sample.attitude_rms_rad;
  }
  // When the sample was taken, not when it is reported.
  pose.time_stamp = time_stamp_of(sample.taken_utc);
  return pose;
}

}  // namespace jaus::components
