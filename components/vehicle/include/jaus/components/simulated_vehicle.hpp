// The default backend of the mobility components: one simulated vehicle that
// the primitive driver drives (Drive) and the pose and velocity sensors read
// (PoseSource). A wrench effort sets target speeds; the vehicle reaches them
// within its acceleration limits, turns (differential: yaw rate; Ackermann:
// steering angle), and its local motion becomes WGS 84 latitude, longitude
// and altitude through GeographicLib's local Cartesian frame at the start pose.
//
// Time: the vehicle reads the injected clock and integrates lazily, in fixed
// steps of 1 / update_rate_hz up to now, whenever it is asked or told
// anything; so under VirtualTime it is deterministic, and it needs no timer.
// A command takes effect from the step in which it arrives.
//
// Motion rules:
// - Effort fields: propulsive linear x (speed, either way), propulsive
//   rotational z (differential: yaw rate; Ackermann: steering angle),
//   resistive linear x (brake: it scales the target speed by
//   1 - brake / 100 and raises the deceleration from max_acceleration
//   towards max_deceleration). Out-of-range values are clamped, NaN and
//   infinities count as 0.
// - Devices: main power (starts on), parking brake (starts off), horn, gear
//   (starts 1, forward). The sign of the linear effort is the direction in
//   every drive gear: a forward gear (1..127) and a reverse gear (129..255)
//   both engage the drive, and a negative effort reverses in either (JAUS's
//   effort already says which way; the gear number is reported, not
//   re-interpreted). Neutral (128) and main power off disengage it: the
//   vehicle coasts down (brake still works). Park (0) and the parking brake
//   hold it: it stops at max_deceleration. While disengaged or held, neither
//   speed nor (differential) yaw rate is driven.
// - Pose: heading and position integrate in a local frame at `start`
//   (flat, tangent to the ellipsoid there); roll and pitch are 0; altitude
//   follows the tangent plane.
#pragma once

#include <memory>
#include <optional>

#include "jaus/base/time.hpp"
#include "jaus/components/drive.hpp"
#include "jaus/components/pose_source.hpp"

namespace jaus::components {

enum class Steering { differential, ackermann };

struct SimulatedVehicleConfig {
  PlatformSpecifications specifications{"jaus-sim", 0.5, 0.5, 0.35, 0.35, 0.0, 0.4, 0.5, 0.55, std::nullopt,
                                        std::nullopt, std::nullopt};
  Steering steering = Steering::differential;
  double max_speed_mps = 1.0;             // at 100 % propulsive linear x (either way)
  double max_yaw_rate_rps = 1.0;          // differential: at 100 % propulsive rotational z
  double max_steering_rad = 0.5;          // Ackermann: at 100 % propulsive rotational z
  double wheel_base_m = 0.5;              // Ackermann turning geometry
  double max_acceleration_mps2 = 1.0;     // speeding up, and coasting down
  double max_deceleration_mps2 = 3.0;     // with 100 % resistive linear x (brake)
  double max_yaw_acceleration_rps2 = 3.0;

  GeoPosition start{45.0, -73.0, 50.0};  // WGS 84 datum of the local frame too
  double start_heading_rad = 0;           // from north, clockwise
  bool local_frame = true;                // report Local Pose (origin: start, x north, y east, z down)

  double update_rate_hz = 50;             // integration step and sample rate (clamped to 0.1..10000)
  double position_rms_m = 0.5;            // at the start...
  double position_rms_per_m = 0.01;       // ...growing with the distance travelled (dead reckoning)
  double attitude_rms_rad = 0.01;
  double velocity_rms_mps = 0.02;
  double rate_rms_rps = 0.01;
  double battery_percent = 100;           // at start
  double battery_drain_percent_per_hour = 5;  // while main power is on
};

class SimulatedVehicle final : public Drive, public PoseSource {
 public:
  SimulatedVehicle(SimulatedVehicleConfig config, const rt::Clock& clock);
  ~SimulatedVehicle() override;
  SimulatedVehicle(const SimulatedVehicle&) = delete;
  SimulatedVehicle& operator=(const SimulatedVehicle&) = delete;

  // Drive.
  std::uint16_t effort_fields() const override;
  DeviceSet devices() const override;
  PlatformSpecifications specifications() const override;
  WrenchEffort apply_effort(const WrenchEffort& effort) override;
  DiscreteDevices set_devices(const DiscreteDevices& devices) override;
  void stop(double brake_percent) override;
  WrenchEffort applied_effort() const override;
  DiscreteDevices device_state() const override;
  OperationalData operational_data() override;

  // PoseSource.
  std::optional<PoseSample> sample() override;
  double update_rate_hz() const override;

  void on_fault(FaultListener listener) override;
  // Tests and faults: a drive fault as a real platform would raise one (a
  // lost link, a tripped motor controller), or its end (nullopt).
  void inject_drive_fault(std::optional<std::string> fault);
  // A frozen source keeps returning its last sample (a
  // navigation receiver that stopped updating); the vehicle still moves.
  void freeze_samples(bool frozen);

  // The true state, for tests.
  double speed_mps();          // forward, negative when reversing
  double yaw_rate_rps();       // positive turning right
  double heading_rad();        // from north, clockwise
  double distance_travelled_m();

  const SimulatedVehicleConfig& config() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace jaus::components
