// Timed joint motions (Set Joint Motion, Set End-Effector Path Motion): from
// where the arm is when the motion starts (time 0) through poses, each
// reached at its time. Between two poses every joint follows a trapezoidal
// profile: it speeds up at its max acceleration, cruises at the lowest speed
// that arrives in time, and slows down at its max deceleration, arriving at
// rest at the pose's time (an unlimited acceleration and deceleration gives
// constant speed, which does not stop at the pose). A pose that a joint
// cannot reach in time within its limits makes the whole motion refused.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/arm_config.hpp"

namespace jaus::components {

struct JointMotionLimit {
  double max_velocity = 0;      // > 0
  double max_acceleration = 0;  // 0: not limited
  double max_deceleration = 0;  // 0: not limited
};

struct TimedJointPose {
  double time_s = 0;                     // from the start of the motion, not before the previous pose's
  std::vector<double> positions;         // one per joint, within its limits
  std::vector<JointMotionLimit> limits;  // one per joint
};

class JointTrajectory {
 public:
  // The motion from `start` through `poses`; an error naming the pose and the
  // joint when a pose cannot be reached at its time within its limits.
  static Expected<JointTrajectory> plan(const ArmConfig& config, const std::vector<double>& start,
                                        const std::vector<TimedJointPose>& poses);

  // The setpoints `t_s` seconds after the start (the start before 0, the last pose after the end).
  std::vector<double> at(double t_s) const;
  double duration_s() const { return segments_.empty() ? 0.0 : segments_.back().end_s; }

 private:
  struct Profile {  // one joint between two poses
    double from = 0, to = 0;
    double cruise = 0, accel_s = 0, decel_s = 0;  // speed and ramp durations
    double position(double tau, double duration) const;
  };
  struct Segment {
    double start_s = 0, end_s = 0;
    std::vector<Profile> joints;
  };
  std::vector<double> start_;
  std::vector<Segment> segments_;
};

}  // namespace jaus::components
