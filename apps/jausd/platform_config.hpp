// The `platform:` and `clearpath:` sections of jausd.yaml: what carries the
// vehicle (the components' own simulation, a simulated Clearpath platform in
// process, or a real one on a serial port, UDP or TCP) and how the bridge maps
// JAUS onto the Clearpath protocol. The vehicle's own figures (speeds, track,
// start pose, accuracy) stay in `vehicle:`; to_host_config() hands both to the
// host. docs/configuration.md and docs/bridge.md are the reference.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config_reader.hpp"
#include "jaus/bridge/clearpath_arm.hpp"
#include "jaus/bridge/clearpath_cameras.hpp"
#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/components/arm_config.hpp"
#include "jaus/components/camera_config.hpp"
#include "jaus/components/simulated_vehicle.hpp"

namespace jausd {

// platform: NAME | {OPTION: VALUE, ...}: a platform kind of the host
// (jaus/host/platform_kinds.hpp), named alone as it is written (sim, model)
// or by the options it takes (serial and baud, udp or tcp: a Clearpath
// platform at that endpoint). The reader knows no kind: it asks the list;
// the kind checks its options (validate()).
struct PlatformChoice {
  std::string kind = "clearpath_sim";  // a kind's name (not as written)
  std::map<std::string, std::string> options;
  std::map<std::string, int> option_lines;  // where each option's value is
};

// clearpath: the mapping options (the rest of ClearpathVehicleConfig comes from `vehicle:`).
struct ClearpathOptions {
  // Unset: ackermann for an Ackermann vehicle (vehicle.steering), else differential_output.
  std::optional<jaus::bridge::DriveMode> drive;
  jaus::bridge::BrakeMode brake = jaus::bridge::BrakeMode::scale;
  bool gear = false;
  jaus::bridge::DeviceOutput main_power, parking_brake, horn;
  bool heading_from_orientation = true;
  std::uint16_t data_rate_hz = 20;
  double setpoint_max_age_s = 0.5;
  double nominal_battery_v = 24.0;
  double max_encoder_step_m = 2.0;
  std::uint16_t emergency_flags = 0;             // JAUS Emergency also sets these safety flags
  std::uint16_t platform_stop_flags = 0x08 | 0x10;  // the platform's own e-stop / pause bits
  std::uint16_t platform_status_flags = 0x01 | 0x20 | 0x40;  // 0x8010 bits about itself, never written
  // Unset: every camera with a movable pan or tilt on the next mount (0, 1, ...).
  std::optional<std::vector<jaus::bridge::ClearpathMountConfig>> mounts;
  // Unset: manipulator joint n on Clearpath joint n - 1, same sign, no offset
  // (an arm with a prismatic joint: none, it stays simulated).
  std::optional<std::vector<jaus::bridge::ClearpathJointMapping>> arm_joints;
};

// The drive mode in use: the configured one, or the vehicle's steering's.
jaus::bridge::DriveMode drive_mode(const ClearpathOptions& options, jaus::components::Steering steering);

// The mounts and arm joints in use: the configured ones, or the defaults above.
std::vector<jaus::bridge::ClearpathMountConfig> camera_mounts(const ClearpathOptions& options,
                                                              const jaus::components::VisualSensorConfig& cameras);
std::vector<jaus::bridge::ClearpathJointMapping> arm_joints(const ClearpathOptions& options,
                                                            const jaus::components::ArmConfig& arm);

void read_platform(const yaml_reader::Entry& entry, PlatformChoice& platform);
void read_clearpath(const yaml_reader::Entry& section, ClearpathOptions& options);

}  // namespace jausd
