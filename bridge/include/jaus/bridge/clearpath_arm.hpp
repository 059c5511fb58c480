// The Clearpath backend of the primitive manipulator's arm: the JAUS joints
// of an ArmConfig, each mapped to a (revolute) Clearpath joint.
//
// Units. JAUS side (manipulator_arm.hpp): joint positions in rad, velocities
// in rad/s, force/torques in N m, in the senses of the arm's DH table.
// Clearpath side: joint angles in rad, [-pi, pi], torques in N m, in the
// manipulator hardware's own senses; a joint is named by its ID in commands
// (0x1010, 0x1013) and by its index in data (0x9010, 0x9014: index = ID).
// For JAUS joint i and its mapping:
//   Clearpath angle  = offset_rad + sign * JAUS position
//   JAUS position    = sign * (Clearpath angle - offset_rad)
//   JAUS torque      = sign * Clearpath torque
//
// What the platform reports: 0x9010 is the "absolute joint position
// SETPOINT data" (the protocol document): Clearpath reports no measured
// joint angle. sample().positions are the latest 0x9010 setpoints mapped back,
// the arm's position as far as the platform says; force_torques the latest
// 0x9014 torques; no velocities or efforts (empty). Both are subscribed at
// data_rate_hz (0x5010, 0x5014); sample() is none before the first 0x9010.
//
// Commands, each checked whole first (nothing is sent when any joint fails;
// the error names the joint, like the simulated arm's):
// - move_to_positions: one position per joint within its limits and, mapped,
//   within Clearpath's +-pi. The motion is ramped: Clearpath's Set Absolute
//   Joints (0x1010) has no speed and the platform reports only its
//   setpoint, so the bridge moves the setpoint itself, from where the
//   platform's setpoint is toward the target at each joint's max_velocity,
//   sending the next 0x1010 every 1 / control_rate_hz until every joint is
//   there. So the joints move at the configured speed limit (when the
//   platform's joints can keep up) and the setpoint stays with the arm,
//   which is what makes hold() stop it within a step.
// - move_at_velocities is integrated: Clearpath has no joint velocity
//   command, so each velocity (within max_velocity) is integrated on the
//   runtime's scheduler into successive 0x1010 targets, every
//   1 / control_rate_hz, until the joint's position limit (or Clearpath's
//   +-pi, whichever is nearer), where that joint stops, or a new command.
// - apply_efforts: refused (ErrorCode::refused): Clearpath has no joint
//   effort command, and a fake one would not be an effort.
// - hold(): the ramp stops where it is: 0x1010 re-sends the setpoints the
//   bridge's own targets have reached (the reported ones are a little older,
//   and going back to them would reverse the joints), or, after homing, a
//   failed command or a lost link, the latest 0x9010 setpoints: the arm stays
//   where the platform says it is. It cannot stop a homing sequence (the
//   platform's setpoint is then home itself).
// - home(): Home Joint (0x1013) for every mapped joint, in joint order; the
//   platform runs its homing sequence. The component calls it on Reset.
// - Set End-Effector Pose: the component solves the inverse kinematics with
//   its DH table and calls move_to_positions; Clearpath's own pose command
//   (0x1021) is not used.
// Commands are refused (ErrorCode::io) while the platform is not alive or
// before its first 0x9010 since it came up; losing the platform ends any ramp
// (the platform keeps its last setpoint), and sample() keeps the last data,
// with the time it arrived. 0x1010 and 0x1013 go out one at a time with ACK
// (Client::send), in order; a waiting 0x1010 is replaced by a newer one, so
// a retried old target never overtakes a new one. A refused or failed
// command is logged (one line, with the reason) and ends the ramp.
//
// Time: every timer is on the injected rt::Scheduler and clock
// (PlatformConnection::clock()). Nothing throws.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/components/manipulator_arm.hpp"

namespace jaus::bridge {

// Where one JAUS joint is on the Clearpath manipulator.
struct ClearpathJointMapping {
  std::uint8_t clearpath_joint = 0;  // ID in 0x1010/0x1013, index in 0x9010/0x9014
  double sign = 1;                   // +1: the Clearpath angle grows with the JAUS position; -1: the other way
  double offset_rad = 0;             // the Clearpath angle at JAUS position 0
};

struct ClearpathArmConfig {
  std::vector<ClearpathJointMapping> joints;  // one per JAUS joint, in ArmConfig order
  std::uint16_t data_rate_hz = 20;            // 0x5010 and 0x5014 subscriptions, 1..100 Hz
  double control_rate_hz = 20;                // ramp and velocity integration: 0x1010 per second, (0, 1000]
};

// Whether `config` can drive an arm of `arm`'s joints: a valid ArmConfig
// (check_arm_config), one mapping per joint, no prismatic joint (Clearpath
// joints are angles), no Clearpath joint twice, signs +-1, finite offsets,
// and each joint's limits reachable within +-pi after mapping, the rates in
// range. The error names the first offending joint.
Expected<void> check_clearpath_arm_config(const components::ArmConfig& arm, const ClearpathArmConfig& config);

struct ClearpathArmCounters {
  std::uint64_t commands_sent = 0;    // 0x1010 and 0x1013 handed to the client
  std::uint64_t commands_failed = 0;  // refused by the platform, unanswered, or link down
  std::uint64_t refused = 0;          // move_* / apply_efforts refused here
  std::uint64_t homings = 0;          // home() calls that sent 0x1013
  std::uint64_t samples = 0;          // 0x9010 received and mapped
};

class ClearpathArm final : public components::ManipulatorArm {
 public:
  // The arm `config` maps onto the platform, subscribed at once (the client
  // keeps subscriptions across reconnects); or the configuration's problem
  // (check_clearpath_arm_config), and no arm: none exists in an invalid state.
  static Expected<std::unique_ptr<ClearpathArm>> make(PlatformConnection& platform, rt::Scheduler& scheduler,
                                                      components::ArmConfig geometry, ClearpathArmConfig config);
  ~ClearpathArm() override;
  ClearpathArm(const ClearpathArm&) = delete;
  ClearpathArm& operator=(const ClearpathArm&) = delete;

  const components::ArmConfig& geometry() const override;
  Expected<void> move_to_positions(const std::vector<double>& positions) override;
  Expected<void> move_at_velocities(const std::vector<double>& velocities) override;
  Expected<void> apply_efforts(const std::vector<double>& efforts_percent) override;
  void hold() override;
  std::optional<components::JointSample> sample() const override;
  // Home Joint (0x1013) for every mapped joint; ends any ramp. Logged and
  // skipped while the platform is not alive.
  void home() override;

  // What the bridge is doing with the arm by the last command.
  enum class Motion { holding, positions, velocities, homing };
  Motion motion() const;
  // Whether a ramp or an integrated velocity is still sending targets.
  bool ramping() const;
  const ClearpathArmConfig& config() const;
  const ClearpathArmCounters& counters() const;

 private:
  struct State;
  // `config` checked (make).
  ClearpathArm(PlatformConnection& platform, rt::Scheduler& scheduler, components::ArmConfig geometry,
               ClearpathArmConfig config);
  std::shared_ptr<State> state_;  // shared with the client's callbacks, which hold it weakly
};

}  // namespace jaus::bridge
