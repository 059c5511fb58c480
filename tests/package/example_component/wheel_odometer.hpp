// The example's own component: a wheel odometer that answers Query Velocity
// State with its forward speed and yaw rate (only the fields asked for).
#pragma once

#include "jaus/messages/platform_messages.hpp"
#include "jaus/runtime/component.hpp"

namespace example {

class WheelOdometer final : public jaus::rt::Component {
 public:
  WheelOdometer(jaus::rt::ComponentConfig config, jaus::rt::Environment env);

  // What the wheels measure (a real one would read its encoders).
  void measured(double speed_mps, double yaw_rate_rps) {
    speed_mps_ = speed_mps;
    yaw_rate_rps_ = yaw_rate_rps;
  }

 private:
  double speed_mps_ = 0;
  double yaw_rate_rps_ = 0;
};

}  // namespace example
