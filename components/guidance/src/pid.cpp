#include "jaus/components/guidance/pid.hpp"

#include <algorithm>
#include <cmath>

namespace jaus::components::guidance {

Expected<void> validate(const PidGains& g) {
  for (double v : {g.kp, g.ki, g.kd}) {
    if (!std::isfinite(v) || v < 0) {
      return unexpected(make_error(ErrorCode::invalid_argument, "PID gains must be finite and not negative"));
    }
  }
  if (!std::isfinite(g.output_min) || !std::isfinite(g.output_max) || g.output_min > g.output_max) {
    return unexpected(make_error(ErrorCode::invalid_argument, "PID output limits must be finite with min <= max"));
  }
  return {};
}

Expected<Pid> Pid::make(const PidGains& gains) {
  if (auto ok = validate(gains); !ok) return unexpected(ok.error());
  return Pid(gains);
}

double Pid::update(double error, double dt_s) { return update(error, dt_s, gains_.output_min, gains_.output_max); }

double Pid::update(double error, double dt_s, double output_min, double output_max) {
  if (!std::isfinite(error)) error = 0;
  const bool stepped = has_last_ && std::isfinite(dt_s) && dt_s > 0;
  const double derivative = stepped ? (error - last_error_) / dt_s : 0;
  const double lo = std::isfinite(output_min) ? std::clamp(output_min, gains_.output_min, gains_.output_max)
                                              : gains_.output_min;
  const double hi = std::isfinite(output_max) ? std::clamp(output_max, lo, gains_.output_max) : gains_.output_max;

  const double proportional = gains_.kp * error;
  const double differential = gains_.kd * derivative;
  if (stepped && gains_.ki > 0) {
    const double candidate = integral_ + gains_.ki * error * dt_s;
    const double unclamped = proportional + candidate + differential;
    // Integrate while inside the limits, or where the error pulls the output back in.
    const bool winding_up = (unclamped > hi && error > 0) || (unclamped < lo && error < 0);
    if (!winding_up) integral_ = std::clamp(candidate, lo, hi);
  }
  output_ = std::clamp(proportional + integral_ + differential, lo, hi);
  last_error_ = error;
  has_last_ = true;
  return output_;
}

void Pid::reset() {
  integral_ = 0;
  last_error_ = 0;
  has_last_ = false;
  output_ = 0;
}

}  // namespace jaus::components::guidance
