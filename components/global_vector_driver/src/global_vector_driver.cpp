#include "jaus/components/global_vector_driver.hpp"

namespace jaus::components {

using namespace rt;

GlobalVectorDriver::GlobalVectorDriver(ComponentConfig config, Environment env, PoseSource& pose,
                                       VectorDriverOptions options)
    : VectorDriver(std::move(config), std::move(env), pose, options) {
  // Moves the vehicle at once: the controller's, in Ready only.
  handle<msg::SetGlobalVector>(Access::controller, /*ready_only=*/true,
                               [this](const Header&, const msg::SetGlobalVector& m) { on_set(m); });
  handle<msg::QueryGlobalVector>(Access::anyone, false, [this](const Header& h, const msg::QueryGlobalVector& q) {
    auto answer = report();
    wire::mask_presence(answer, q.presence_vector);
    send(h.source, answer);
  });
  provide<msg::ReportGlobalVector>(global_vector_field::kAll, [this] { return report(); });
  // Followed: speed and heading; the rest is stored and echoed.
  declare_input_presence(msg::SetGlobalVector::code, global_vector_field::kSpeed | global_vector_field::kHeading);
  declare_input_presence(msg::QueryGlobalVector::code, global_vector_field::kAll);
}

void GlobalVectorDriver::on_set(const msg::SetGlobalVector& m) {
  if (m.altitude_m) altitude_m_ = m.altitude_m;
  if (m.roll_rad) roll_rad_ = m.roll_rad;
  if (m.pitch_rad) pitch_rad_ = m.pitch_rad;
  command(m.speed_mps, m.heading_rad, "Set Global Vector");
}

msg::ReportGlobalVector GlobalVectorDriver::report() const {
  msg::ReportGlobalVector r;
  r.speed_mps = commanded_speed_mps();
  r.altitude_m = altitude_m_;
  r.heading_rad = commanded_heading_rad();
  r.roll_rad = roll_rad_;
  r.pitch_rad = pitch_rad_;
  return r;
}

void GlobalVectorDriver::forget_command() {
  VectorDriver::forget_command();
  altitude_m_.reset();
  roll_rad_.reset();
  pitch_rad_.reset();
}

}  // namespace jaus::components
