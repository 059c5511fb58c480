#include "jaus/components/pose_reports.hpp"

#include "jaus/components/sensor_component.hpp"  // time_stamp_of

namespace jaus::components {

namespace {
// Attitude, as both poses carry it; angles wrapped to (-pi, pi], the range
// their fields encode (a yaw of 3pi/2 would otherwise be clamped to pi).
template <class Pose>
void set_attitude(Pose& pose, const PoseSample& sample) {
  if (!sample.attitude) return;
  pose.roll_rad = wrap_angle(sample.attitude->roll);
  pose.pitch_rad = wrap_angle(sample.attitude->pitch);
  pose.yaw_rad = wrap_angle(sample.attitude->yaw);
  // An RMS goes with its value: the RMS of an absent attitude means nothing.
  pose.attitude_rms_rad = sample.attitude_rms_rad;
}
}  // namespace

msg::ReportGlobalPose global_pose_report(const PoseSample& sample) {
  msg::ReportGlobalPose pose;
  if (sample.position) {
    pose.latitude_deg = sample.position->latitude_deg;
    pose.longitude_deg = sample.position->longitude_deg;
    pose.elevation_m = sample.position->altitude_m;
    pose.position_rms_m = sample.position_rms_m;
  }
  set_attitude(pose, sample);
  // When the sample was taken, not when it is reported.
  pose.time_stamp = time_stamp_of(sample.taken_utc);
  return pose;
}

msg::ReportLocalPose local_pose_report(const PoseSample& sample) {
  msg::ReportLocalPose pose;
  if (sample.local_position) {
    pose.x_m = sample.local_position->x_m;
    pose.y_m = sample.local_position->y_m;
    pose.z_m = sample.local_position->z_m;
    pose.position_rms_m = sample.position_rms_m;
  }
  set_attitude(pose, sample);
  pose.time_stamp = time_stamp_of(sample.taken_utc);
  return pose;
}

}  // namespace jaus::components
