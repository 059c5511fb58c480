// The hardware a host's components run on, one class per platform: it hands
// out the backends it has, by interface name (rt::Backends), says which of
// them its e-stop holds, and does what that platform needs on an emergency,
// on the local clear and on a stop. NodeHost knows no platform by name: a
// platform kind (platform_kinds.hpp) makes it from PlatformSettings.
//
//   ModelPlatform (model_platform.hpp, kind `model`): the components' own
//     simulations.
//   ClearpathPlatform (clearpath_platform.hpp, kinds `clearpath_sim` and
//     `clearpath`): the bridge's backends on a Clearpath platform, simulated
//     in process or real (only the client differs); what the platform lacks
//     (images, unmapped joints) stays simulated.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <memory>
#include <string_view>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/components/arm_config.hpp"
#include "jaus/components/camera_config.hpp"
#include "jaus/components/simulated_vehicle.hpp"
#include "jaus/runtime/component_kind.hpp"
#include "jaus/runtime/emergency_latch.hpp"
#include "jaus/base/log.hpp"

namespace jaus::host {

// What the simulated hardware is like, on any platform (a Clearpath platform
// keeps the simulated cameras' images, and the simulated arm when no joint is
// mapped to it).
struct SimulationSettings {
  components::SimulatedVehicleConfig vehicle;
  components::VisualSensorConfig cameras;
  components::ArmConfig arm;
};

// Where a platform runs: the host's clock and scheduler, and an opened host's
// io_context (nullptr for an attached host: no thread posts back, no socket).
struct PlatformEnvironment {
  rt::Clock& clock;
  rt::Scheduler& scheduler;
  boost::asio::io_context* io = nullptr;
  rt::LogFn log;
};

class Platform {
 public:
  virtual ~Platform() = default;

  // Makes the backend of `interface` once (a second call finds it made) and
  // offers it in `backends`; an interface this platform lacks is left out
  // (the kind that needs it says so). An error: a configuration the platform
  // cannot take (a camera mount or joint mapped wrongly).
  virtual Expected<void> provide(std::string_view interface, rt::Backends& backends) = 0;
  // Whether the platform's own e-stop holds the backend of `interface` (every
  // component needing one is then held by it too). Asked once everything is
  // provided.
  virtual bool on_estop(std::string_view /*interface*/) const { return false; }
  // Once every component has its latch: `on_estop` are the latches of the
  // components held by the platform's e-stop, `driver` the latch of what
  // drives the vehicle (nullptr: none). Every latch outlives the platform.
  virtual void follow_emergencies(std::vector<rt::EmergencyLatch*> /*on_estop*/, rt::EmergencyLatch* /*driver*/) {}
  // The local clear of emergency holds: the platform's stops an earlier run
  // left behind are cleared too; its hardware stops stay.
  virtual void reclaim_stops() {}
  // After every component's stop path has run (NodeHost::stop): no frame is
  // wanted any more, and the stop's zero setpoint goes out now, before a
  // process exits without running its loop again. Idempotent.
  virtual void stop() {}
};

}  // namespace jaus::host
