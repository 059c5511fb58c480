// Kinematics of a serial arm described as Part 3's Report Manipulator
// Specifications describes it (ArmConfig): forward kinematics, the Jacobian,
// numerical inverse kinematics, and joint rates for an end-effector twist.
//
// Convention (standard, "distal" Denavit-Hartenberg, in Part 3's terms of
// joint axes S_i and link vectors a_i(i+1)):
//   - The manipulator (base) frame is ArmConfig's base pose in the vehicle
//     frame; its z axis is the axis of joint 1, its x axis the direction
//     from which joint 1's angle is measured.
//   - Joint i turns about (revolute) or slides along (prismatic) the z axis
//     of frame i-1: Rz(theta_i) Tz(d_i), where theta_i is the joint's
//     position and d_i its fixed offset (revolute), or theta_i the fixed
//     joint angle and d_i the position (prismatic).
//   - The link after joint i follows: Tx(a_i(i+1)) Rx(alpha_i(i+1)), giving
//     frame i (z along the axis of joint i+1).
//   - The end-effector frame (Part 3, Set Tool Point) has its origin where
//     the last joint's axis S_n meets a_n(n+1), z along S_n and x along
//     a_n(n+1): it is the frame after the last joint's Rz Tz. The last
//     joint's link length and twist (which Part 3 does not report) are not
//     used; a tool offset is the tool point, given in this frame.
//   - The end-effector pose (Set End-Effector Pose) is the tool point's
//     position and the end-effector frame's orientation, in the vehicle frame.
// Everything an OCU needs to reproduce it is in Report Manipulator
// Specifications, Report Tool Point and Report Joint Positions.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/arm_config.hpp"

namespace jaus::components::kinematics {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  bool operator==(const Vec3&) const = default;
};
Vec3 operator+(const Vec3& a, const Vec3& b);
Vec3 operator-(const Vec3& a, const Vec3& b);
Vec3 operator*(double k, const Vec3& v);
double dot(const Vec3& a, const Vec3& b);
Vec3 cross(const Vec3& a, const Vec3& b);
double norm(const Vec3& v);

// A rotation matrix, row-major: v_parent = m * v_child.
struct Rotation {
  std::array<double, 9> m{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 operator*(const Vec3& v) const;
  Rotation operator*(const Rotation& o) const;
  Rotation transposed() const;
  Vec3 column(int c) const { return {m[c], m[3 + c], m[6 + c]}; }
};
Rotation rot_x(double angle);
Rotation rot_z(double angle);

// A unit quaternion (d; a, b, c) = (w; x, y, z), as Part 3 writes them.
struct Quaternion {
  double d = 1, a = 0, b = 0, c = 0;
  bool operator==(const Quaternion&) const = default;
};
// Normalised (zero or non-finite: identity).
Rotation to_rotation(const Quaternion& q);
// The quaternion of `r`, with d >= 0.
Quaternion to_quaternion(const Rotation& r);
// The rotation vector (axis x angle, angle in [0, pi]) taking `from` to `to`, in the parent frame.
Vec3 rotation_error(const Rotation& from, const Rotation& to);

// A frame's pose in its parent: v_parent = rotation * v_frame + origin.
struct Transform {
  Rotation rotation;
  Vec3 origin;
  Vec3 operator*(const Vec3& v) const { return rotation * v + origin; }
  Transform operator*(const Transform& o) const { return {rotation * o.rotation, rotation * o.origin + origin}; }
};

// The tool point in the vehicle frame and the end-effector frame's orientation.
struct Pose {
  Vec3 position;
  Rotation orientation;
};

// A 6 x n Jacobian, one column per joint: rows linear velocity of the tool
// point (x, y, z), then angular velocity (x, y, z), all in the vehicle frame.
using Jacobian = std::vector<std::array<double, 6>>;

struct IkOptions {
  double position_tolerance_m = 1e-3;
  double orientation_tolerance_rad = 1e-3;
  int max_iterations = 200;  // per start
  int starts = 12;           // the seed, then deterministic spread starts within the limits
};

// Joint rates for a twist, and how far they miss it (|J q' - twist|, the
// linear and angular parts added).
struct JointRates {
  std::vector<double> rates;
  double residual = 0;
};

class ArmKinematics {
 public:
  explicit ArmKinematics(const ArmConfig& config);

  std::size_t joint_count() const { return config_.joints.size(); }
  const ArmConfig& config() const { return config_; }
  // The manipulator (base) frame in the vehicle frame.
  const Transform& base() const { return base_; }

  // The end-effector frame in the vehicle frame; `q` has one value per joint.
  Transform end_effector_frame(const std::vector<double>& q) const;
  // The tool point (in the end-effector frame) and end-effector orientation, in the vehicle frame.
  Pose tool_pose(const std::vector<double>& q, const Vec3& tool_point) const;
  Jacobian jacobian(const std::vector<double>& q, const Vec3& tool_point) const;

  // Joint positions within the limits that put the tool point at `target`
  // (damped least squares from `seed`, then from spread starts); an error
  // when none converges within the tolerances.
  Expected<std::vector<double>> inverse(const Pose& target, const Vec3& tool_point, const std::vector<double>& seed,
                                        const IkOptions& options = {}) const;
  // Joint rates (damped least squares) giving the tool point `linear` and the
  // end effector `angular` velocity, vehicle frame.
  JointRates joint_rates(const std::vector<double>& q, const Vec3& tool_point, const Vec3& linear,
                         const Vec3& angular) const;

 private:
  // Frames 0 .. n-1 (z along the axis of joint i+1) and the end-effector frame last.
  std::vector<Transform> frames(const std::vector<double>& q) const;
  std::vector<double> within_limits(std::vector<double> q) const;

  ArmConfig config_;
  Transform base_;
};

}  // namespace jaus::components::kinematics
