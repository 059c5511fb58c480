// A Clearpath platform through the bridge: the mobility components drive and
// read it (ClearpathVehicle), the camera mounts and arm joints the
// configuration maps to it move on it, all on one PlatformConnection. Its
// e-stop holds every component on it, and the driver's JAUS Emergency sets
// its emergency flag (bridge::PlatformEmergencyMirror). What it lacks stays
// simulated (a ModelPlatform): the images, the arm when no joint is mapped.
// Simulated in process (sim::LoopbackClient, on the host's clock and
// scheduler) or real (ClearpathLink, on the host's io_context): only the
// client differs. The client is opened when a component first needs the
// platform: a configuration that puts nothing on it opens nothing.
//
// Its own library (jaus_clearpath_platform), which registers the kinds
// `clearpath_sim` (written `sim`) and `clearpath` (options serial and baud,
// udp or tcp: where the platform is) with the host (platform_kinds.hpp);
// both read the section ClearpathSettings.
#pragma once

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "jaus/bridge/clearpath_arm.hpp"
#include "jaus/bridge/clearpath_cameras.hpp"
#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/bridge/platform_emergency.hpp"
#include "jaus/clearpath/client.hpp"
#include "jaus/clearpath/link.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/platform.hpp"
#include "jaus/host/platform_kinds.hpp"

namespace jaus::host {

// A Clearpath platform's settings beyond where it is (PlatformSettings'
// section "clearpath"; absent: all defaults).
struct ClearpathSettings {
  static constexpr std::string_view kSection = "clearpath";
  clearpath::sim::PlatformConfig sim;      // clearpath_sim: the simulated platform
  clearpath::ClientConfig client;          // retries, silence, setpoint period and maximum age
  bridge::ClearpathVehicleConfig vehicle;  // the mobility components' mapping
  // The visual sensor's camera mounts on the platform (images still come from
  // the simulated cameras); cameras not listed keep their simulated mount.
  bridge::ClearpathCamerasConfig cameras;
  // The manipulator's joints on the platform; none: the arm stays simulated.
  bridge::ClearpathArmConfig arm;
};

// The kinds this library registers.
const PlatformKind& clearpath_sim_platform_kind();  // `clearpath_sim`: simulated in this process
const PlatformKind& clearpath_platform_kind();      // `clearpath`: at an endpoint, on an opened host

// Platform settings naming a simulated Clearpath platform, or a real one at
// `endpoint` (its options written from it), with `settings`.
PlatformSettings clearpath_sim_platform_settings(ClearpathSettings settings = {});
PlatformSettings clearpath_platform_settings(const clearpath::PlatformEndpoint& endpoint,
                                             ClearpathSettings settings = {});
// Where a `clearpath` platform is, read from its options (serial and baud,
// udp or tcp); the error's field is the option at fault (empty: the platform).
Expected<clearpath::PlatformEndpoint> clearpath_endpoint(const PlatformSettings& settings);

class ClearpathPlatform final : public Platform {
 public:
  // In this process (no endpoint), or at `endpoint` with environment.io set.
  ClearpathPlatform(std::optional<clearpath::PlatformEndpoint> endpoint, ClearpathSettings settings,
                    SimulationSettings simulation, PlatformEnvironment environment);
  ~ClearpathPlatform() override;
  ClearpathPlatform(const ClearpathPlatform&) = delete;
  ClearpathPlatform& operator=(const ClearpathPlatform&) = delete;

  Expected<void> provide(std::string_view interface, rt::Backends& backends) override;
  bool on_estop(std::string_view interface) const override;
  void follow_emergencies(std::vector<rt::EmergencyLatch*> on_estop, rt::EmergencyLatch* driver) override;
  void reclaim_stops() override;
  void stop() override;

  // Once opened (nullptr before): the client, a ClearpathLink or a
  // sim::LoopbackClient, and the bridge's connection on it.
  clearpath::Client* client() { return client_.get(); }
  clearpath::ClearpathLink* link() { return link_; }  // a real link (not clearpath_sim)
  bridge::PlatformConnection* connection() { return connection_.get(); }
  // The bridge's backends, once a component needs them (nullptr until then,
  // and for a mount or arm the configuration maps nothing to).
  bridge::ClearpathVehicle* vehicle() { return vehicle_.get(); }
  bridge::ClearpathCameras* cameras() { return cameras_.get(); }
  bridge::ClearpathArm* arm() { return arm_.get(); }
  // What stays simulated: the cameras' images, an arm not on the platform.
  ModelPlatform& simulated() { return simulated_; }

 private:
  bridge::PlatformConnection& connect();  // opens the client and the connection, once

  std::optional<clearpath::PlatformEndpoint> endpoint_;  // none: simulated in this process
  ClearpathSettings settings_;
  SimulationSettings simulation_;
  PlatformEnvironment environment_;
  ModelPlatform simulated_;
  std::unique_ptr<clearpath::Client> client_;
  clearpath::ClearpathLink* link_ = nullptr;  // client_, when it is a real link
  std::unique_ptr<bridge::PlatformConnection> connection_;
  std::unique_ptr<bridge::ClearpathVehicle> vehicle_;
  std::unique_ptr<bridge::ClearpathCameras> cameras_;
  std::unique_ptr<bridge::ClearpathArm> arm_;
  std::unique_ptr<bridge::PlatformEmergencyMirror> emergency_mirror_;  // the platform's stops <-> the latches
  std::vector<std::string_view> on_estop_;  // the interfaces provided on the platform
};

}  // namespace jaus::host
