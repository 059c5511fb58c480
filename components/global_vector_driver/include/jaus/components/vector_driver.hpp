// What the global and the local vector driver share (components 34 and 44,
// issue 30): a commanded vector (a speed and a heading) followed with the
// guidance's heading and speed loops, each step one Set Wrench Effort to the
// primitive driver (MobilityDriver). The two differ only in their messages.
//
// The rules (docs/components.md, vector drivers):
//   - a Set of the controller in Ready replaces the fields it carries; the
//     others keep their commanded value. Before any Set the commanded speed
//     is 0 and the commanded heading is the vehicle's heading when the first
//     Set arrives. Every Set engages (drives until told otherwise);
//   - a commanded speed of 0 with the heading within heading_tolerance_rad
//     (and the vehicle no longer turning) ends the motion as an arrival
//     (zero below, control of the primitive driver released); an Ackermann
//     vehicle cannot turn at rest, so speed 0 arrives at once;
//   - every other end of a motion (Standby, Emergency, Reset, the primitive
//     driver lost, a stale pose) sets the commanded speed to 0: nothing
//     restarts the vehicle but a new Set; Reset forgets the command whole.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "jaus/components/guidance/loops.hpp"
#include "jaus/components/mobility_driver.hpp"

namespace jaus::components {

struct VectorDriverOptions {
  MobilityDriverOptions mobility;
  // Speed 0: the motion ends once the heading is this close.
  double heading_tolerance_rad = 0.05;
  // Heading: yaw rate (rad/s) per rad of heading error. The vehicle
  // integrates a yaw rate into its heading, so P reaches the heading with no
  // offset and no integral (which would only overshoot) unless the drive
  // pulls to one side; D damps a drive that turns faster per percent than
  // its specifications say (a Clearpath differential output drive). Tuned
  // on both platforms and drivetrains: no overshoot of a 90 degree turn.
  guidance::PidGains heading_gains{.kp = 1.5, .ki = 0, .kd = 0.1};
  // Speed: percent of full effort per m/s of speed error, on top of the
  // feedforward (which alone gives the speed on an ideal drive); a small
  // integral makes up a drive that under-delivers without winding up while
  // the vehicle accelerates.
  guidance::PidGains speed_gains{.kp = 20, .ki = 2, .kd = 0};
};

// The option keys of both vector driver kinds: the mobility driver's, then
// heading_tolerance_rad, heading_kp/ki/kd and speed_kp/ki/kd.
std::vector<std::string_view> vector_driver_option_keys();
Expected<VectorDriverOptions> vector_driver_options(const rt::KindOptions& options);

class VectorDriver : public MobilityDriver {
 public:
  VectorDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose, VectorDriverOptions options);

  // What the driver follows now (what Report ... Vector gives).
  double commanded_speed_mps() const { return speed_mps_; }
  // None before the first Set (or after a Reset).
  const std::optional<double>& commanded_heading_rad() const { return heading_rad_; }
  // Set ... Vector messages acted on.
  std::uint64_t commands() const { return commands_; }

 protected:
  // A Set ... Vector of the controller in Ready: the fields given replace
  // the commanded ones, then the vehicle drives (engage(why)).
  void command(std::optional<double> speed_mps, std::optional<double> heading_rad, std::string_view why);
  // The vehicle's heading now, if the pose source has one.
  std::optional<double> vehicle_heading_rad();

  Step step(const PoseSample& pose, double dt_s) override;
  void motion_started() override;
  void motion_halted(std::string_view why) override;
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override;
  // Reset: the command is forgotten (a derived driver forgets its own fields too).
  virtual void forget_command();

 private:
  VectorDriverOptions options_;
  double speed_mps_ = 0;
  std::optional<double> heading_rad_;
  std::uint64_t commands_ = 0;
  // Made when a motion starts: they need the primitive driver's limits.
  std::optional<guidance::HeadingLoop> heading_loop_;
  std::optional<guidance::SpeedLoop> speed_loop_;
};

}  // namespace jaus::components
