#include "wheel_odometer.hpp"

namespace example {

namespace {
// Report Velocity State presence vector bits (RA Part 3).
constexpr std::uint16_t kVelocityX = 1u << 0;
constexpr std::uint16_t kYawRate = 1u << 6;
}  // namespace

WheelOdometer::WheelOdometer(jaus::rt::ComponentConfig config, jaus::rt::Environment env)
    : Component(std::move(config), std::move(env)) {
  handle<jaus::msg::QueryVelocityState>(Access::anyone, false,
                                        [this](const jaus::Header& header, const jaus::msg::QueryVelocityState& query) {
                                          jaus::msg::ReportVelocityState report;
                                          if (query.presence_vector & kVelocityX) report.velocity_x_mps = speed_mps_;
                                          if (query.presence_vector & kYawRate) report.yaw_rate_rps = yaw_rate_rps_;
                                          send(header.source, report);
                                        });
}

}  // namespace example
