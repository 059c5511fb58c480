// Forward kinematics on the DH table (see kinematics.hpp for the convention),
// the geometric Jacobian of the tool point, and damped least squares for the
// inverse problems (pose -> joints, twist -> joint rates).
#include "jaus/components/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace jaus::components::kinematics {

Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double k, const Vec3& v) { return {k * v.x, k * v.y, k * v.z}; }
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

Vec3 Rotation::operator*(const Vec3& v) const {
  return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
          m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

Rotation Rotation::operator*(const Rotation& o) const {
  Rotation r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[3 * i + j] = m[3 * i] * o.m[j] + m[3 * i + 1] * o.m[3 + j] + m[3 * i + 2] * o.m[6 + j];
  return r;
}

Rotation Rotation::transposed() const { return {{m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]}}; }

Rotation rot_x(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {{1, 0, 0, 0, c, -s, 0, s, c}};
}

Rotation rot_z(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {{c, -s, 0, s, c, 0, 0, 0, 1}};
}

Rotation to_rotation(const Quaternion& q) {
  const double n = std::sqrt(q.d * q.d + q.a * q.a + q.b * q.b + q.c * q.c);
  if (!std::isfinite(n) || n < 1e-12) return {};
  const double w = q.d / n, x = q.a / n, y = q.b / n, z = q.c / n;
  return {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),  //
           2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),  //
           2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
}

Quaternion to_quaternion(const Rotation& r) {
  const auto& m = r.m;
  const double trace = m[0] + m[4] + m[8];
  Quaternion q;
  if (trace > 0) {
    const double s = std::sqrt(trace + 1) * 2;
    q = {0.25 * s, (m[7] - m[5]) / s, (m[2] - m[6]) / s, (m[3] - m[1]) / s};
  } else if (m[0] > m[4] && m[0] > m[8]) {
    const double s = std::sqrt(1 + m[0] - m[4] - m[8]) * 2;
    q = {(m[7] - m[5]) / s, 0.25 * s, (m[1] + m[3]) / s, (m[2] + m[6]) / s};
  } else if (m[4] > m[8]) {
    const double s = std::sqrt(1 + m[4] - m[0] - m[8]) * 2;
    q = {(m[2] - m[6]) / s, (m[1] + m[3]) / s, 0.25 * s, (m[5] + m[7]) / s};
  } else {
    const double s = std::sqrt(1 + m[8] - m[0] - m[4]) * 2;
    q = {(m[3] - m[1]) / s, (m[2] + m[6]) / s, (m[5] + m[7]) / s, 0.25 * s};
  }
  if (q.d < 0) q = {-q.d, -q.a, -q.b, -q.c};
  const double n = std::sqrt(q.d * q.d + q.a * q.a + q.b * q.b + q.c * q.c);
  return {q.d / n, q.a / n, q.b / n, q.c / n};
}

Vec3 rotation_error(const Rotation& from, const Rotation& to) {
  const Quaternion q = to_quaternion(to * from.transposed());  // d >= 0: the short way round
  const Vec3 v{q.a, q.b, q.c};
  const double s = norm(v);
  if (s < 1e-12) return 2.0 * v;
  return (2 * std::atan2(s, q.d) / s) * v;
}

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kMinDamping = 1e-4;
constexpr double kRateDamping = 1e-4;
constexpr double kMaxIkStep = 0.5;  // rad or m per iteration

// Solves a * x = b (a is k x k, row-major) by Gaussian elimination with
// partial pivoting. Damping keeps every matrix given here regular.
std::vector<double> solve(std::vector<double> a, std::vector<double> b) {
  const std::size_t k = b.size();
  for (std::size_t col = 0; col < k; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < k; ++r)
      if (std::abs(a[r * k + col]) > std::abs(a[pivot * k + col])) pivot = r;
    if (std::abs(a[pivot * k + col]) < 1e-300) return std::vector<double>(k, 0.0);
    if (pivot != col) {
      for (std::size_t c = 0; c < k; ++c) std::swap(a[col * k + c], a[pivot * k + c]);
      std::swap(b[col], b[pivot]);
    }
    for (std::size_t r = col + 1; r < k; ++r) {
      const double f = a[r * k + col] / a[col * k + col];
      if (f == 0) continue;
      for (std::size_t c = col; c < k; ++c) a[r * k + c] -= f * a[col * k + c];
      b[r] -= f * b[col];
    }
  }
  std::vector<double> x(k, 0.0);
  for (std::size_t i = k; i-- > 0;) {
    double s = b[i];
    for (std::size_t c = i + 1; c < k; ++c) s -= a[i * k + c] * x[c];
    x[i] = s / a[i * k + i];
  }
  return x;
}

// Damped least squares: the q' minimising |J q' - e|^2 + lambda^2 |q'|^2.
// Solved in joint space for arms of up to 6 joints, in task space beyond.
std::vector<double> damped_least_squares(const Jacobian& j, const std::array<double, 6>& e, double lambda) {
  const std::size_t n = j.size();
  const double l2 = lambda * lambda;
  if (n <= 6) {
    std::vector<double> a(n * n), b(n);
    for (std::size_t r = 0; r < n; ++r) {
      for (std::size_t c = 0; c < n; ++c) {
        double s = 0;
        for (int k = 0; k < 6; ++k) s += j[r][k] * j[c][k];
        a[r * n + c] = s + (r == c ? l2 : 0);
      }
      double s = 0;
      for (int k = 0; k < 6; ++k) s += j[r][k] * e[k];
      b[r] = s;
    }
    return solve(std::move(a), std::move(b));
  }
  std::vector<double> a(36), b(e.begin(), e.end());
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      double s = 0;
      for (std::size_t i = 0; i < n; ++i) s += j[i][r] * j[i][c];
      a[r * 6 + c] = s + (r == c ? l2 : 0);
    }
  const std::vector<double> y = solve(std::move(a), std::move(b));
  std::vector<double> out(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 6; ++k) out[i] += j[i][k] * y[k];
  return out;
}

struct PoseError {
  std::array<double, 6> e{};
  double position = 0, orientation = 0;
  double cost() const { return position * position + orientation * orientation; }
};

PoseError pose_error(const Pose& at, const Pose& target) {
  PoseError out;
  const Vec3 dp = target.position - at.position;
  const Vec3 dr = rotation_error(at.orientation, target.orientation);
  out.e = {dp.x, dp.y, dp.z, dr.x, dr.y, dr.z};
  out.position = norm(dp);
  out.orientation = norm(dr);
  return out;
}

// A low-discrepancy point of the joint box (Kronecker sequence): start k, joint i.
double spread_fraction(int k, std::size_t i) {
  const double alpha = std::fmod(std::sqrt(2.0 + 3.0 * static_cast<double>(i)) * 0.7548776662466927, 1.0);
  return std::fmod(0.5 + static_cast<double>(k) * alpha, 1.0);
}

}  // namespace

ArmKinematics::ArmKinematics(const ArmConfig& config) : config_(config) {
  base_.rotation = to_rotation({config.base_quaternion_d, config.base_quaternion_a, config.base_quaternion_b,
                                config.base_quaternion_c});
  base_.origin = {config.base_x_m, config.base_y_m, config.base_z_m};
}

std::vector<Transform> ArmKinematics::frames(const std::vector<double>& q) const {
  const std::size_t n = joint_count();
  std::vector<Transform> out;
  out.reserve(n + 1);
  Transform t = base_;
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(t);
    const JointConfig& joint = config_.joints[i];
    const double value = i < q.size() ? q[i] : 0.0;
    const double theta = joint.prismatic ? joint.offset : value;
    const double d = joint.prismatic ? value : joint.offset;
    t = t * Transform{rot_z(theta), {0, 0, d}};
    if (i + 1 < n) t = t * Transform{rot_x(joint.twist_angle_rad), {joint.link_length_m, 0, 0}};
  }
  out.push_back(t);
  return out;
}

Transform ArmKinematics::end_effector_frame(const std::vector<double>& q) const { return frames(q).back(); }

Pose ArmKinematics::tool_pose(const std::vector<double>& q, const Vec3& tool_point) const {
  const Transform effector = end_effector_frame(q);
  return {effector * tool_point, effector.rotation};
}

Jacobian ArmKinematics::jacobian(const std::vector<double>& q, const Vec3& tool_point) const {
  const std::vector<Transform> f = frames(q);
  const Vec3 p = f.back() * tool_point;
  Jacobian j(joint_count());
  for (std::size_t i = 0; i < joint_count(); ++i) {
    const Vec3 z = f[i].rotation.column(2);
    if (config_.joints[i].prismatic) {
      j[i] = {z.x, z.y, z.z, 0, 0, 0};
    } else {
      const Vec3 v = cross(z, p - f[i].origin);
      j[i] = {v.x, v.y, v.z, z.x, z.y, z.z};
    }
  }
  return j;
}

std::vector<double> ArmKinematics::within_limits(std::vector<double> q) const {
  for (std::size_t i = 0; i < q.size() && i < joint_count(); ++i) {
    const JointConfig& joint = config_.joints[i];
    double& v = q[i];
    if (!std::isfinite(v)) v = (joint.min_position + joint.max_position) / 2;
    if (!joint.prismatic && (v < joint.min_position || v > joint.max_position)) {
      // The same angle a whole number of turns away, if that is within the limits.
      const double wrapped = v - kTwoPi * std::floor((v - joint.min_position) / kTwoPi);
      if (wrapped <= joint.max_position) v = wrapped;
    }
    v = std::clamp(v, joint.min_position, joint.max_position);
  }
  return q;
}

Expected<std::vector<double>> ArmKinematics::inverse(const Pose& target, const Vec3& tool_point,
                                                     const std::vector<double>& seed, const IkOptions& options) const {
  const std::size_t n = joint_count();
  if (n == 0 || seed.size() != n)
    return unexpected(make_error(ErrorCode::invalid_argument, "inverse kinematics needs one seed value per joint"));
  double best_position = std::numeric_limits<double>::infinity();
  double best_orientation = std::numeric_limits<double>::infinity();
  for (int start = 0; start < std::max(options.starts, 1); ++start) {
    std::vector<double> q = seed;
    if (start > 0)
      for (std::size_t i = 0; i < n; ++i) {
        const JointConfig& joint = config_.joints[i];
        q[i] = joint.min_position + spread_fraction(start, i) * (joint.max_position - joint.min_position);
      }
    q = within_limits(std::move(q));
    PoseError error = pose_error(tool_pose(q, tool_point), target);
    double lambda = 0.01;
    for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
      if (error.position <= options.position_tolerance_m && error.orientation <= options.orientation_tolerance_rad)
        return q;
      if (iteration == options.max_iterations) break;
      const Jacobian j = jacobian(q, tool_point);
      bool improved = false;
      for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
        std::vector<double> dq = damped_least_squares(j, error.e, lambda);
        double largest = 0;
        for (double v : dq) largest = std::max(largest, std::abs(v));
        const double scale = largest > kMaxIkStep ? kMaxIkStep / largest : 1.0;
        std::vector<double> next = q;
        for (std::size_t i = 0; i < n; ++i) next[i] += scale * dq[i];
        next = within_limits(std::move(next));
        const PoseError next_error = pose_error(tool_pose(next, tool_point), target);
        if (next_error.cost() < error.cost()) {
          q = std::move(next);
          error = next_error;
          lambda = std::max(lambda / 3, kMinDamping);
          improved = true;
        } else {
          lambda *= 4;
        }
      }
      if (!improved) break;  // a local minimum (or a limit) this start cannot leave
    }
    if (error.cost() < best_position * best_position + best_orientation * best_orientation) {
      best_position = error.position;
      best_orientation = error.orientation;
    }
  }
  std::ostringstream why;
  why << "no joint positions within the limits reach it (closest: " << best_position << " m, " << best_orientation
      << " rad away)";
  return unexpected(make_error(ErrorCode::out_of_range, why.str()));
}

JointRates ArmKinematics::joint_rates(const std::vector<double>& q, const Vec3& tool_point, const Vec3& linear,
                                      const Vec3& angular) const {
  const Jacobian j = jacobian(q, tool_point);
  const std::array<double, 6> twist{linear.x, linear.y, linear.z, angular.x, angular.y, angular.z};
  JointRates out;
  out.rates = damped_least_squares(j, twist, kRateDamping);
  std::array<double, 6> achieved{};
  for (std::size_t i = 0; i < j.size(); ++i)
    for (int k = 0; k < 6; ++k) achieved[k] += j[i][k] * out.rates[i];
  double lin = 0, ang = 0;
  for (int k = 0; k < 3; ++k) lin += (achieved[k] - twist[k]) * (achieved[k] - twist[k]);
  for (int k = 3; k < 6; ++k) ang += (achieved[k] - twist[k]) * (achieved[k] - twist[k]);
  out.residual = std::sqrt(lin) + std::sqrt(ang);
  return out;
}

}  // namespace jaus::components::kinematics
