// The hardware interface of the primitive driver: what the component asks of
// a platform's drive, in JAUS's own terms (wrench effort in percent, body
// frame x forward, y right, z down; discrete devices as Part 3 codes them).
// Backends: the simulated vehicle (simulated_vehicle.hpp) and the Clearpath
// platform (bridge/). The component decides who may drive and when; a backend
// only drives, and says what it actually applied.
#pragma once

#include <string_view>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace jaus::components {

// Per-axis values; linear x/y/z and rotational about x/y/z.
struct Axes {
  double x = 0, y = 0, z = 0;
  bool operator==(const Axes&) const = default;
};

// Set Wrench Effort in percent: propulsive -100..100 (rotational z positive
// turns right), resistive (brakes) 0..100.
struct WrenchEffort {
  Axes propulsive_linear;
  Axes propulsive_rotational;
  Axes resistive_linear;
  Axes resistive_rotational;
  bool operator==(const WrenchEffort&) const = default;
};

// Which of the twelve wrench effort fields a drive acts on, as bits of the
// Report Wrench Effort presence vector (bit 0 propulsive linear x ... bit 11
// resistive rotational z). Fields outside it are ignored and never reported.
namespace effort_field {
inline constexpr std::uint16_t kPropulsiveLinearX = 1u << 0;
inline constexpr std::uint16_t kPropulsiveLinearY = 1u << 1;
inline constexpr std::uint16_t kPropulsiveLinearZ = 1u << 2;
inline constexpr std::uint16_t kPropulsiveRotationalX = 1u << 3;
inline constexpr std::uint16_t kPropulsiveRotationalY = 1u << 4;
inline constexpr std::uint16_t kPropulsiveRotationalZ = 1u << 5;
inline constexpr std::uint16_t kResistiveLinearX = 1u << 6;
inline constexpr std::uint16_t kResistiveLinearY = 1u << 7;
inline constexpr std::uint16_t kResistiveLinearZ = 1u << 8;
inline constexpr std::uint16_t kResistiveRotationalX = 1u << 9;
inline constexpr std::uint16_t kResistiveRotationalY = 1u << 10;
inline constexpr std::uint16_t kResistiveRotationalZ = 1u << 11;
}  // namespace effort_field

// Discrete devices, each present only when the platform has it. Gear as Part
// 3 codes it: 0 park, 1..127 forward, 128 neutral, 129..255 reverse.
struct DiscreteDevices {
  std::optional<bool> main_power;      // main propulsion on
  std::optional<bool> parking_brake;   // set
  std::optional<bool> horn;            // sounding
  std::optional<std::uint8_t> gear;
  bool operator==(const DiscreteDevices&) const = default;
};

// Which devices a platform has (a field is true when it has it).
struct DeviceSet {
  bool main_power = false, parking_brake = false, horn = false, gear = false;
};

// Platform Specifications: what the vehicle is (SI units; absent = unknown).
struct PlatformSpecifications {
  std::string name;  // up to 15 characters on the wire
  std::optional<double> front_m, back_m, right_m, left_m, bottom_m, top_m;
  std::optional<double> wheel_base_m, track_width_m, turning_radius_m;
  std::optional<double> max_velocity_x_mps, max_yaw_rate_rps;
};

// Platform Operational Data: what the platform measures of itself, where it has it.
struct OperationalData {
  std::optional<double> engine_temperature_c;
  std::optional<double> odometer_m;
  std::optional<double> battery_voltage_percent;  // of nominal
  std::optional<double> fuel_level_percent;
  bool operator==(const OperationalData&) const = default;
};

class Drive {
 public:
  // Its name among the hardware a host offers a component kind (rt::Backends).
  static constexpr std::string_view kInterface = "drive";
  static constexpr std::string_view kDescription = "a vehicle drive";

  // Hears a fault of the drive when it appears (what is wrong: "link to the
  // platform lost") and when it clears (nullopt). Called on the runtime's
  // thread.
  using FaultListener = std::function<void(const std::optional<std::string>& fault)>;

  virtual ~Drive() = default;

  // A drive that can fail (a lost link, a motor controller fault) tells the
  // listener; the driver then goes to Failure and stops the drive. The
  // default never faults.
  virtual void on_fault(FaultListener listener) { (void)listener; }

  // The wrench effort fields this drive acts on (effort_field bits).
  virtual std::uint16_t effort_fields() const = 0;
  virtual DeviceSet devices() const = 0;
  virtual PlatformSpecifications specifications() const = 0;

  // Applies an effort (fields outside effort_fields() are ignored); returns
  // what the drive was actually told, after its own limits (clamping).
  virtual WrenchEffort apply_effort(const WrenchEffort& effort) = 0;
  // Sets the devices given (absent ones unchanged); returns their state.
  virtual DiscreteDevices set_devices(const DiscreteDevices& devices) = 0;
  // Safety: zero propulsive effort at once, with `brake_percent` of
  // resistive linear effort (0: coast). Called on every stop of the driver;
  // never fails, idempotent. The drive stays stopped until the next
  // apply_effort(): it never resumes an earlier effort by itself.
  virtual void stop(double brake_percent) = 0;

  // What the drive is applying now (zero after stop()).
  virtual WrenchEffort applied_effort() const = 0;
  virtual DiscreteDevices device_state() const = 0;
  virtual OperationalData operational_data() = 0;
};

}  // namespace jaus::components
