// A PID loop with output limits and anti-windup: the one feedback law of the
// heading and speed loops. Sans-I/O: the caller gives each error and the time
// step since the last one (the drivers step on the runtime's clock, the tests
// on virtual time), so it is deterministic and needs no clock.
//
// Anti-windup by conditional integration: the integral grows only while the
// output is inside its limits, or while the error drives it back inside. A
// loop held at its limit (a vehicle at full effort, a turn at the maximum
// yaw rate) therefore does not store error it cannot act on, and does not
// overshoot when it leaves the limit. The integral term is also kept within
// the output limits on its own.
#pragma once

#include "jaus/base/expected.hpp"

namespace jaus::components::guidance {

struct PidGains {
  double kp = 0, ki = 0, kd = 0;
  double output_min = -1, output_max = 1;
};

// The gains are finite and not negative, and output_min <= output_max.
Expected<void> validate(const PidGains& gains);

class Pid {
 public:
  // Gains that fail validate() are an error; the loop is then not built.
  static Expected<Pid> make(const PidGains& gains);

  // The output for `error` after `dt_s` seconds. A first update, or one with
  // dt_s <= 0 or not finite, has no derivative and integrates nothing (a
  // repeated or out-of-order time is no reason to jump). A non-finite error
  // counts as 0. The result is always within the output limits.
  double update(double error, double dt_s);
  // The same within narrower limits for this step (clamped to the gains'),
  // for a loop whose output is added to a feedforward: the sum's limits
  // minus the feedforward, so anti-windup sees the real saturation.
  double update(double error, double dt_s, double output_min, double output_max);
  // Forgets the integral and the last error (a new target, a stop).
  void reset();

  double integral_term() const { return integral_; }
  double last_output() const { return output_; }
  const PidGains& gains() const { return gains_; }

 private:
  explicit Pid(const PidGains& gains) : gains_(gains) {}
  PidGains gains_;
  double integral_ = 0;  // ki * integral of the error: the integral's share of the output
  double last_error_ = 0;
  bool has_last_ = false;
  double output_ = 0;
};

}  // namespace jaus::components::guidance
