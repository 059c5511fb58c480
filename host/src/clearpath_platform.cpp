#include "jaus/host/clearpath_platform.hpp"

#include <algorithm>

#include "jaus/clearpath/sim/loopback_client.hpp"

namespace jaus::host {

ClearpathPlatform::ClearpathPlatform(PlatformSettings settings, SimulationSettings simulation,
                                     PlatformEnvironment environment)
    : settings_(std::move(settings)),
      simulation_(simulation),
      environment_(environment),
      simulated_(std::move(simulation), std::move(environment)) {}

ClearpathPlatform::~ClearpathPlatform() = default;

// A link that reopens with backoff and never fails the node (a missing port
// is a link down, which the components report as Failure), or the simulated
// platform in this process.
bridge::PlatformConnection& ClearpathPlatform::connect() {
  if (connection_) return *connection_;
  if (settings_.kind == PlatformSettings::Kind::clearpath_sim) {
    clearpath::sim::LoopbackConfig loopback;
    loopback.platform = settings_.sim;
    loopback.client = settings_.client;
    loopback.period = std::chrono::milliseconds(5);
    client_ = std::make_unique<clearpath::sim::LoopbackClient>(environment_.clock, environment_.scheduler, loopback);
    environment_.log(rt::LogLevel::info, "Clearpath platform: simulated in process");
  } else {
    // make_platform gives a real platform only an environment with an io_context.
    auto link = std::make_unique<clearpath::ClearpathLink>(*environment_.io, environment_.clock, environment_.scheduler,
                                                           settings_.endpoint, settings_.client);
    link->start();
    link_ = link.get();
    client_ = std::move(link);
  }
  connection_ = std::make_unique<bridge::PlatformConnection>(*client_, environment_.clock, environment_.log);
  return *connection_;
}

// The images are always the simulated cameras'; their mounts may be the
// platform's. A camera mount or an arm joint not mapped stays simulated.
Expected<void> ClearpathPlatform::provide(std::string_view interface, rt::Backends& backends) {
  const auto on_platform = [&](std::string_view name) {
    if (std::find(on_estop_.begin(), on_estop_.end(), name) == on_estop_.end()) on_estop_.push_back(name);
  };
  if (interface == components::Drive::kInterface || interface == components::PoseSource::kInterface) {
    if (!vehicle_) vehicle_ = std::make_unique<bridge::ClearpathVehicle>(connect(), settings_.vehicle);
    backends.offer<components::Drive>(vehicle_.get());
    backends.offer<components::PoseSource>(vehicle_.get());
    on_platform(components::Drive::kInterface);
    on_platform(components::PoseSource::kInterface);
  } else if (interface == components::Cameras::kInterface) {
    if (auto images = simulated_.provide(interface, backends); !images) return images;
    const auto& mounts = settings_.cameras;
    if (mounts.mounts.empty()) return {};
    if (!cameras_) {
      if (auto ok = bridge::check_clearpath_cameras_config(simulation_.cameras.cameras, mounts); !ok)
        return unexpected(ok.error());
      cameras_ = std::make_unique<bridge::ClearpathCameras>(connect(), environment_.scheduler,
                                                            *simulated_.cameras(), mounts);
    }
    backends.offer<components::Cameras>(cameras_.get());
    on_platform(components::Cameras::kInterface);
  } else if (interface == components::ManipulatorArm::kInterface) {
    const auto& joints = settings_.arm;
    if (joints.joints.empty()) return simulated_.provide(interface, backends);
    if (!arm_) {
      if (auto ok = bridge::check_clearpath_arm_config(simulation_.arm, joints); !ok) return unexpected(ok.error());
      arm_ = std::make_unique<bridge::ClearpathArm>(connect(), environment_.scheduler, simulation_.arm, joints);
    }
    backends.offer<components::ManipulatorArm>(arm_.get());
    on_platform(components::ManipulatorArm::kInterface);
  } else {
    return simulated_.provide(interface, backends);
  }
  return {};
}

bool ClearpathPlatform::on_estop(std::string_view interface) const {
  return std::find(on_estop_.begin(), on_estop_.end(), interface) != on_estop_.end();
}

void ClearpathPlatform::follow_emergencies(std::vector<rt::EmergencyLatch*> on_estop, rt::EmergencyLatch* driver) {
  if (vehicle_) emergency_mirror_ = std::make_unique<bridge::PlatformEmergencyMirror>(*vehicle_, std::move(on_estop), driver);
}

void ClearpathPlatform::reclaim_stops() {
  if (vehicle_) vehicle_->reclaim_safety_bits();
}

void ClearpathPlatform::stop() {
  simulated_.stop();
  if (link_ != nullptr) link_->flush();
}

}  // namespace jaus::host
