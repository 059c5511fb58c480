// The Clearpath backend of the mobility components: the primitive driver's
// Drive and the pose and velocity sensors' PoseSource, over one Clearpath
// platform (PlatformConnection). docs/bridge.md has the tables; in short:
//
// Drive (JAUS percent, rotational z positive turning right) -> platform:
//   differential_output  0x0202  L = X + Z, R = X - Z (each clamped to
//                                 +-100 %): a positive (right) Z speeds the
//                                 left wheel up, so the platform turns right;
//                                 a brake (resistive X) scales both down by
//                                 1 - brake/100, or is ignored (BrakeMode).
//   differential_speeds  0x0200  v = X% of max_speed, w = Z% of max_yaw_rate,
//                                 left = v + w t/2, right = v - w t/2.
//   velocity             0x0204  v as above, rotational = -w (Clearpath's
//                                 rotation is positive turning left).
//   ackermann            0x0203  steering = -Z (positive left), throttle = X,
//                                 brake = resistive X.
//   Closed-loop speeds never exceed the platform's own limits (0x8210).
//   Gear 0x0212: park -> -1, 1..127 forward -> 1..127, neutral 128 -> 0,
//   129..255 reverse -> -2..-128. Parking brake, horn and main power: bits
//   of the safety flags (0x0010) or GPIO outputs (0x0302), by configuration.
//
// PoseSource <- platform: odometry from the encoders (0x8800, travel and
// speed of the left and right side) dead-reckoned from the configured datum
// into the local frame and WGS 84 (LocalFrame); heading from orientation
// (0x8600, whose yaw is left-handed: it grows turning right, like a heading,
// from the platform's own reference) plus the datum's heading, or from the
// encoders when configured so; rates from 0x8601 (left-handed yaw rate:
// positive turning right, JAUS's sense). Position RMS grows with the distance
// travelled.
//
// Safety (Drive contract): every motion command is a setpoint the client
// resends only while younger than setpoint_max_age, so it lives exactly as
// long as the driver keeps renewing it; stop() replaces it with one zero
// setpoint and the stream ends. While the platform is not alive (link down,
// or no data since it came up) the drive reports a fault and moves nothing;
// when it is back, nothing moves until a new command.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "jaus/base/time.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/components/drive.hpp"
#include "jaus/components/pose_source.hpp"

namespace jaus::bridge {

// Which Clearpath command a wrench effort becomes.
enum class DriveMode { differential_output, differential_speeds, velocity, ackermann };
// Differential drives: what the resistive linear effort (brake) does.
enum class BrakeMode { scale, ignore };

// Where a discrete device is on the platform.
struct DeviceOutput {
  enum class Kind { none, safety_flag, gpio } kind = Kind::none;
  std::uint32_t bits = 0;   // safety flag bits (0x0010) or GPIO pins (0x0302)
  bool active_high = true;  // the bits are 1 when the device is on / set / sounding
};

struct ClearpathVehicleConfig {
  DriveMode drive = DriveMode::differential_output;
  BrakeMode brake = BrakeMode::scale;
  double max_speed_mps = 1.0;          // closed loop: at 100 % propulsive linear x
  double max_yaw_rate_rps = 1.0;       // closed loop: at 100 % propulsive rotational z
  double max_acceleration_mps2 = 1.0;  // closed loop: the commands' acceleration
  double track_width_m = 0.55;         // wheel speeds from a yaw rate; heading from the encoders
  // Ackermann: the wheel base and the front wheels' angle at 100 % propulsive
  // rotational z, for Report Platform Specifications' turning radius (what
  // the drivers above the primitive driver steer by).
  double wheel_base_m = 0.5;
  double max_steering_rad = 0.5;
  bool gear = false;                   // the platform has Change Gear (0x0212)
  DeviceOutput main_power, parking_brake, horn;
  // As the client's ClientConfig::setpoint_max_age: how long the platform
  // acts on one command; Report Wrench Effort says zero after that.
  rt::Duration setpoint_max_age = std::chrono::milliseconds(500);
  // Report Platform Specifications; an empty name is the platform's (0x8002).
  components::PlatformSpecifications specifications;

  components::GeoPosition datum{45.0, -73.0, 50.0};  // where the platform starts (WGS 84)
  double datum_heading_rad = 0;                      // its heading there, from north, clockwise
  bool heading_from_orientation = true;              // 0x8600; false: integrate the encoders
  bool local_frame = true;                           // report Local Pose (origin: the datum)
  double position_rms_m = 0.5, position_rms_per_m = 0.02;
  double attitude_rms_rad = 0.02, velocity_rms_mps = 0.05, rate_rms_rps = 0.02;
  std::uint16_t data_rate_hz = 20;   // encoders, orientation and rates subscriptions
  double max_encoder_step_m = 2.0;   // a larger jump between readings is a reset: start again from it
  double nominal_battery_v = 24.0;   // Platform Operational Data's battery voltage percent

  // Hardware e-stop, both ways (Husky flags: 0x08 emergency stop, 0x10 pause).
  // JAUS Emergency (held by Set Emergency) also sets these bits of the safety
  // flags (0x0010); 0: it does not. jausd owns only these and the devices'
  // safety bits; bridge/src/safety_word.hpp has the rule for the rest.
  std::uint16_t emergency_flags = 0;
  // These bits seen in the platform's safety status (0x8010), other than the
  // ones we set ourselves, mean its own e-stop or pause is on; 0: not watched.
  std::uint16_t platform_stop_flags = 0x08 | 0x10;
  // Bits of 0x8010 the platform reports about itself (Husky: 0x01 timeout,
  // 0x20 no battery, 0x40 current limit): never written back.
  std::uint16_t platform_status_flags = 0x01 | 0x20 | 0x40;
  // 0x8010 subscription: how soon a platform stop is seen, and which stops
  // are: a pause or e-stop that lasts one period (20 ms) falls on a sample
  // whenever it starts; a shorter one may fall between two and is missed.
  // 50 Hz keeps a 50 ms pause seen with 30 ms to spare for the platform's
  // jitter; the cost is 16-byte frames at 50 Hz, 800 bytes/s (7 % of a
  // 115200-baud serial line; 160 bytes/s at 10 Hz). docs/bridge.md.
  std::uint16_t safety_status_rate_hz = 50;
};

struct ClearpathVehicleCounters {
  std::uint64_t setpoints = 0, stops = 0, refused_offline = 0;
  std::uint64_t encoder_readings = 0, encoder_resets = 0, command_failures = 0;
};

class ClearpathVehicle final : public components::Drive, public components::PoseSource {
 public:
  // Subscribes to what it needs at once (the client keeps subscriptions across reconnects).
  ClearpathVehicle(PlatformConnection& platform, ClearpathVehicleConfig config);
  ~ClearpathVehicle() override;
  ClearpathVehicle(const ClearpathVehicle&) = delete;
  ClearpathVehicle& operator=(const ClearpathVehicle&) = delete;

  // Drive.
  void on_fault(FaultListener listener) override;
  std::uint16_t effort_fields() const override;
  components::DeviceSet devices() const override;
  components::PlatformSpecifications specifications() const override;
  components::WrenchEffort apply_effort(const components::WrenchEffort& effort) override;
  components::DiscreteDevices set_devices(const components::DiscreteDevices& devices) override;
  void stop(double brake_percent) override;
  components::WrenchEffort applied_effort() const override;
  components::DiscreteDevices device_state() const override;
  components::OperationalData operational_data() override;

  // PoseSource.
  std::optional<components::PoseSample> sample() override;
  double update_rate_hz() const override;

  // The platform's own e-stop or pause (platform_stop_flags bits jausd did
  // not set), or jausd's emergency flag written clear but not yet reported
  // clear: `why` when it appears, nullopt when the platform reports it clear.
  // The host holds the components in Emergency meanwhile. Called at once,
  // from command_emergency(false) too, so the hold is in place before the
  // components could leave Emergency.
  using EmergencyListener = std::function<void(const std::optional<std::string>& why)>;
  void on_platform_emergency(EmergencyListener listener);
  // Set Emergency holds the vehicle (true) or no longer does: sets or clears
  // emergency_flags on the platform. Does nothing when emergency_flags is 0.
  void command_emergency(bool active);
  // The local command for holds whose holder is gone (jausd's SIGUSR1): the
  // owned safety bits the platform shows are taken as jausd's own, and those
  // not wanted are cleared (safety_word.hpp). Never undoes a hardware stop.
  void reclaim_safety_bits();

  const ClearpathVehicleConfig& config() const;
  const ClearpathVehicleCounters& counters() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Gear codes: Part 3's (0 park, 1..127 forward, 128 neutral, 129..255
// reverse) <-> Clearpath's (-1 park, 0 neutral, > 0 forward, < -1 reverse).
std::int8_t clearpath_gear(std::uint8_t jaus_gear);
std::uint8_t jaus_gear(std::int8_t clearpath_gear);

}  // namespace jaus::bridge
