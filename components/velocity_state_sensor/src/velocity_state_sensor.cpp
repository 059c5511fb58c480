#include "jaus/components/velocity_state_sensor.hpp"

namespace jaus::components {

VelocityStateSensor::VelocityStateSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source,
                                         SensorOptions options)
    : SensorComponent(std::move(config), std::move(env), source, options) {
  const std::function<msg::ReportVelocityState(const PoseSample&)> build = &VelocityStateSensor::velocity_state;
  serve<msg::QueryVelocityState>(available_fields(build), build);
}

msg::ReportVelocityState VelocityStateSensor::velocity_state(const PoseSample& sample) {
  msg::ReportVelocityState state;
  // An RMS goes with its value: the RMS of an absent velocity means nothing.
  if (sample.velocity_mps) {
    state.velocity_x_mps = sample.velocity_mps->x;
    state.velocity_y_mps = sample.velocity_mps->y;
    state.velocity_z_mps = sample.velocity_mps->z;
    state.velocity_rms_mps = sample.velocity_rms_mps;
  }
  if (sample.rates_rps) {
    state.roll_rate_rps = sample.rates_rps->x;
    state.pitch_rate_rps = sample.rates_rps->y;
    state.yaw_rate_rps = sample.rates_rps->z;
    state.rate_rms_rps = sample.rate_rms_rps;
  }
  // When the sample was taken, not when it is reported.
  state.time_stamp = time_stamp_of(sample.taken_utc);
  return state;
}

}  // namespace jaus::components
