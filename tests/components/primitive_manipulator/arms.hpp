// Arms the manipulator tests share, with hand-computable geometry.
#pragma once

#include <numbers>

#include "jaus/components/arm_config.hpp"

namespace jaus::test {

inline constexpr double kPi = std::numbers::pi;

inline components::JointConfig revolute(const char* name, double a, double alpha, double d) {
  components::JointConfig j;
  j.name = name;
  j.link_length_m = a;
  j.twist_angle_rad = alpha;
  j.offset = d;
  return j;
}

// Two parallel revolute joints: a 1 m link, then the last joint (tool point 0.5 m along its x).
inline components::ArmConfig planar_arm() {
  components::ArmConfig c;
  c.joints = {revolute("shoulder", 1.0, 0, 0), revolute("elbow", 0, 0, 0)};
  return c;
}

// SCARA (RRP): shoulder 0.4 m up, 0.5 m and 0.3 m links, the second flips z
// down; a prismatic quill of 0 .. 0.3 m at 0.2 m/s.
inline components::ArmConfig scara_arm() {
  components::ArmConfig c;
  c.joints = {revolute("shoulder", 0.5, 0, 0.4), revolute("elbow", 0.3, kPi, 0), revolute("quill", 0, 0, 0)};
  c.joints[0].min_position = -2.5;
  c.joints[0].max_position = 2.5;
  c.joints[1].min_position = -2.5;
  c.joints[1].max_position = 2.5;
  c.joints[1].max_velocity = 0.5;
  c.joints[2].prismatic = true;
  c.joints[2].min_position = 0;
  c.joints[2].max_position = 0.3;
  c.joints[2].max_velocity = 0.2;
  c.joints[2].max_effort = 100;  // N
  c.joints[2].initial_position = 0.1;
  return c;
}

// The PUMA 560 in standard DH (Corke's p560), joints within +-pi.
inline components::ArmConfig puma_arm() {
  components::ArmConfig c;
  c.joints = {revolute("waist", 0, kPi / 2, 0),        revolute("shoulder", 0.4318, 0, 0),
              revolute("elbow", 0.0203, -kPi / 2, 0.15005), revolute("wrist roll", 0, kPi / 2, 0.4318),
              revolute("wrist pitch", 0, -kPi / 2, 0), revolute("wrist yaw", 0, 0, 0)};
  for (auto& j : c.joints) {
    j.max_velocity = 1.0;
    j.max_effort = 50;
  }
  return c;
}

}  // namespace jaus::test
