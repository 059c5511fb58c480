#include "jaus/console/panels/arm_panel.hpp"

#include <cmath>
#include <numbers>

#include "jaus/messages/all.hpp"

namespace jaus::console {

namespace {

struct JointLimit {
  bool revolute = true;
  double min = 0, max = 0;  // rad or m
};

// Part 3 carries revolute angles as 0 .. 2 pi: back into (-pi, pi], with
// the 0.001 rad of the wire's rounding allowed above pi.
double signed_angle(double rad) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  return rad > std::numbers::pi + 0.002 ? rad - kTwoPi : rad;
}

JointLimit joint_limit(std::uint8_t type, double min, double max) {
  if (type == static_cast<std::uint8_t>(jaus::msg::JointType::prismatic)) return {false, min, max};
  JointLimit limit{true, signed_angle(min), signed_angle(max)};
  // -pi and pi are one angle on the wire: a minimum that came back as +pi.
  if (limit.min >= limit.max) limit.min -= 2 * std::numbers::pi;
  return limit;
}

// Joints 1 .. n-1 with their links, then the last joint (Part 3's order).
std::vector<JointLimit> joint_limits(const jaus::msg::ManipulatorSpecificationsBody& s) {
  std::vector<JointLimit> limits;
  for (const auto& j : s.joints) limits.push_back(joint_limit(j.type, j.min_rad_or_m, j.max_rad_or_m));
  limits.push_back(joint_limit(s.last_joint_type, s.last_joint_min_rad_or_m, s.last_joint_max_rad_or_m));
  return limits;
}

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }
double radians(double deg) { return deg * std::numbers::pi / 180.0; }

}  // namespace

void ArmPanel::follow(const jaus::Address& a, std::string_view /*view*/) {
  session().send(a, jaus::msg::QueryManipulatorSpecifications{});
  const auto on_joints = [this, a](const jaus::Header&, const jaus::msg::ReportJointPositions& j) {
    arms_[a].positions_rad_or_m = j.positions_rad;
    publish(a);
  };
  subscribe<jaus::msg::ReportJointPositions>(a, 0, on_joints);
}

void ArmPanel::received(const jaus::ocu::Received& r) {
  if (r.header.command_code != jaus::msg::ReportManipulatorSpecifications::code) return;
  if (auto m = decode_report<jaus::msg::ReportManipulatorSpecifications>(r.payload)) {
    arms_[r.header.source].specifications = *m;
    publish(r.header.source);
  }
}

void ArmPanel::on_frame(PageId page, const ArmFrame& frame) {
  auto it = arms_.find(frame.target);
  if (it == arms_.end() || !it->second.specifications) {
    session().send(frame.target, jaus::msg::QueryManipulatorSpecifications{});
    pages().refuse(page, "arm: no Report Manipulator Specifications from " + frame.target.to_string() + " yet");
    return;
  }
  const auto limits = joint_limits(*it->second.specifications);
  if (frame.joints.size() != limits.size()) {
    pages().refuse(page, "arm: " + frame.target.to_string() + " has " + std::to_string(limits.size()) +
                             " joints, not " + std::to_string(frame.joints.size()));
    return;
  }
  jaus::msg::SetJointPositions set{};
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const double value = limits[i].revolute ? radians(frame.joints[i]) : frame.joints[i];
    // The specifications carry limits to 0.001 (rad or m), rounded either
    // way: one step inside them is within the arm's real limits.
    constexpr double kStep = 0.001;
    const double low = std::min(limits[i].min, limits[i].max) + kStep;
    const double high = std::max(limits[i].min, limits[i].max) - kStep;
    set.positions_rad.push_back(low < high ? within(value, low, high) : within(value, limits[i].min, limits[i].max));
  }
  control_.as_controller(page, frame.target, [this, target = frame.target, set] { session().send(target, set); });
}

void ArmPanel::publish(const jaus::Address& source) {
  const auto it = arms_.find(source);
  if (it == arms_.end() || !it->second.specifications) return;
  const auto limits = joint_limits(*it->second.specifications);
  ArmStateFrame frame{source, {}};
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const auto& l = limits[i];
    const double position = i < it->second.positions_rad_or_m.size() ? it->second.positions_rad_or_m[i] : 0.0;
    frame.joints.push_back(l.revolute ? ArmJoint{degrees(l.min), degrees(l.max), degrees(signed_angle(position)), "deg"}
                                      : ArmJoint{l.min, l.max, position, "m"});
  }
  pages().to_all(frame);
}

}  // namespace jaus::console
