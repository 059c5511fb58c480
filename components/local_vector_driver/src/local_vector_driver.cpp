#include "jaus/components/local_vector_driver.hpp"

namespace jaus::components {

using namespace rt;

LocalVectorDriver::LocalVectorDriver(ComponentConfig config, Environment env, PoseSource& pose,
                                     VectorDriverOptions options)
    : VectorDriver(std::move(config), std::move(env), pose, options) {
  // Moves the vehicle at once: the controller's, in Ready only.
  handle<msg::SetLocalVector>(Access::controller, /*ready_only=*/true,
                              [this](const Header&, const msg::SetLocalVector& m) {
                                command(m.speed_mps, m.heading_rad, "Set Local Vector");
                              });
  handle<msg::QueryLocalVector>(Access::anyone, false,
                                [this](const Header& h, const msg::QueryLocalVector&) { send(h.source, report()); });
  provide<msg::ReportLocalVector>(0, [this] { return report(); });
}

msg::ReportLocalVector LocalVectorDriver::report() {
  msg::ReportLocalVector r;
  r.speed_mps = commanded_speed_mps();
  r.heading_rad = commanded_heading_rad().value_or(vehicle_heading_rad().value_or(0.0));
  return r;
}

}  // namespace jaus::components
