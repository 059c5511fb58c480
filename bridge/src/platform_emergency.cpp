#include "jaus/bridge/platform_emergency.hpp"

namespace jaus::bridge {

PlatformEmergencyMirror::PlatformEmergencyMirror(ClearpathVehicle& vehicle,
                                                 std::vector<rt::EmergencyLatch*> held_by_platform,
                                                 rt::EmergencyLatch* flag_follows)
    : vehicle_(vehicle), held_by_platform_(std::move(held_by_platform)) {
  vehicle_.on_platform_emergency([this](const std::optional<std::string>& why) {
    for (auto* latch : held_by_platform_) {
      if (why) latch->hold_local(kPlatformStop);
      else latch->release_local(kPlatformStop);
    }
  });
  if (flag_follows == nullptr) return;
  flag_follows->observe([vehicle = &vehicle_](const rt::EmergencyLatch& latch) {
    vehicle->command_emergency(latch.held_by_jaus());
  });
  vehicle_.command_emergency(flag_follows->held_by_jaus());  // a hold restored at start
}

PlatformEmergencyMirror::~PlatformEmergencyMirror() { vehicle_.on_platform_emergency({}); }

}  // namespace jaus::bridge
