#include "jaus/components/joint_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "jaus/components/manipulator_arm.hpp"

namespace jaus::components {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kTimeSlack = 1e-9;  // s

// 0 (not limited) -> infinity; negative limits count by their size.
double rate_limit(double v) { return v == 0 || !std::isfinite(v) ? kInfinity : std::abs(v); }

Expected<JointTrajectory> refused_motion(std::string why) {
  return unexpected(make_error(ErrorCode::out_of_range, std::move(why)));
}

}  // namespace

double JointTrajectory::Profile::position(double tau, double duration) const {
  if (tau <= 0) return from;
  if (tau >= duration) return to;
  const double sign = to >= from ? 1.0 : -1.0;
  const double distance = std::abs(to - from);
  double x = 0;
  if (tau < accel_s) {
    x = 0.5 * (cruise / accel_s) * tau * tau;
  } else if (tau <= duration - decel_s) {
    x = cruise * (tau - accel_s / 2);
  } else {
    const double left = duration - tau;
    x = distance - 0.5 * (cruise / decel_s) * left * left;
  }
  return from + sign * std::clamp(x, 0.0, distance);
}

Expected<JointTrajectory> JointTrajectory::plan(const ArmConfig& config, const std::vector<double>& start,
                                                const std::vector<TimedJointPose>& poses) {
  const std::size_t n = config.joints.size();
  if (start.size() != n) return refused_motion("the motion starts from " + std::to_string(start.size()) + " joints");
  if (poses.empty()) return refused_motion("a motion has at least one pose");
  JointTrajectory out;
  out.start_ = start;
  std::vector<double> from = start;
  double from_s = 0;
  for (std::size_t p = 0; p < poses.size(); ++p) {
    const TimedJointPose& pose = poses[p];
    std::ostringstream where;
    where << "pose " << p + 1 << " at " << pose.time_s << " s";
    if (pose.positions.size() != n || pose.limits.size() != n)
      return refused_motion(where.str() + " has " + std::to_string(pose.positions.size()) + " joints, the arm " +
                     std::to_string(n));
    if (!std::isfinite(pose.time_s) || pose.time_s < from_s - kTimeSlack) {
      std::ostringstream why;
      why << where.str() << " comes before the previous pose (" << from_s << " s)";
      return refused_motion(why.str());
    }
    Segment segment;
    segment.start_s = from_s;
    segment.end_s = std::max(pose.time_s, from_s);
    const double duration = segment.end_s - segment.start_s;
    for (std::size_t i = 0; i < n; ++i) {
      Profile profile{from[i], pose.positions[i], 0, 0, 0};
      const double distance = std::abs(profile.to - profile.from);
      const JointMotionLimit& limit = pose.limits[i];
      const double vmax = std::abs(limit.max_velocity);
      const double accel = rate_limit(limit.max_acceleration), decel = rate_limit(limit.max_deceleration);
      if (distance > 0) {
        // distance = v * T - k * v^2, k = 1/(2 accel) + 1/(2 decel): the lowest v that covers it.
        const double k = 0.5 / accel + 0.5 / decel;
        const double discriminant = duration * duration - 4 * k * distance;
        const double cruise = discriminant >= 0 && duration > 0 ? 2 * distance / (duration + std::sqrt(discriminant))
                                                                : kInfinity;
        if (!(cruise <= vmax * (1 + 1e-9) + 1e-12)) {
          std::ostringstream why;
          why << where.str() << ": " << joint_label(config, i) << " cannot move " << distance << " in " << duration
              << " s within its limits (velocity " << vmax;
          if (std::isfinite(accel)) why << ", acceleration " << accel;
          if (std::isfinite(decel)) why << ", deceleration " << decel;
          why << ")";
          return refused_motion(why.str());
        }
        profile.cruise = cruise;
        profile.accel_s = std::isfinite(accel) ? cruise / accel : 0.0;
        profile.decel_s = std::isfinite(decel) ? cruise / decel : 0.0;
      }
      segment.joints.push_back(profile);
    }
    out.segments_.push_back(std::move(segment));
    from = pose.positions;
    from_s = out.segments_.back().end_s;
  }
  return out;
}

std::vector<double> JointTrajectory::at(double t_s) const {
  if (segments_.empty() || !(t_s > 0)) return start_;
  for (const Segment& segment : segments_) {
    if (t_s > segment.end_s) continue;
    std::vector<double> out(segment.joints.size());
    const double duration = segment.end_s - segment.start_s;
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = segment.joints[i].position(t_s - segment.start_s, duration);
    return out;
  }
  std::vector<double> out;
  for (const Profile& p : segments_.back().joints) out.push_back(p.to);
  return out;
}

}  // namespace jaus::components
