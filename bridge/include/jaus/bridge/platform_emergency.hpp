// Safety, both ways between JAUS and a Clearpath platform's own stops,
// through emergency latches only (a component may be shut down and destroyed
// at any time; the latches belong to whoever hosts the components and
// outlive them and this mirror):
//   - the platform's e-stop or pause (or its emergency flag not yet reported
//     clear after jausd cleared it) is a local hold on every latch of a
//     component on the platform, until the platform reports it clear;
//   - the platform's emergency flag (ClearpathVehicleConfig::emergency_flags)
//     is set while Set Emergency holds the driver's latch, whatever state any
//     component is in: a Shutdown never clears it.
// The flag follows the latch as one of its observers, which run before the
// latch's members follow it: when a clear must first be confirmed by the
// platform, the hold is in place before any component could leave Emergency.
#pragma once

#include <string_view>
#include <vector>

#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/runtime/emergency_latch.hpp"

namespace jaus::bridge {

class PlatformEmergencyMirror {
 public:
  // The name of the local hold the platform's own stop puts on the latches.
  static constexpr std::string_view kPlatformStop = "the Clearpath platform's own stop";

  // `flag_follows` may be null (no driver on the platform). Every latch must
  // outlive this mirror; the vehicle too.
  PlatformEmergencyMirror(ClearpathVehicle& vehicle, std::vector<rt::EmergencyLatch*> held_by_platform,
                          rt::EmergencyLatch* flag_follows);
  ~PlatformEmergencyMirror();
  PlatformEmergencyMirror(const PlatformEmergencyMirror&) = delete;
  PlatformEmergencyMirror& operator=(const PlatformEmergencyMirror&) = delete;

 private:
  ClearpathVehicle& vehicle_;
  std::vector<rt::EmergencyLatch*> held_by_platform_;
};

}  // namespace jaus::bridge
