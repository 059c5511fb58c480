#include "jaus/host/clearpath_platform.hpp"

#include <algorithm>
#include <charconv>

#include "jaus/base/quoted.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace jaus::host {

ClearpathPlatform::ClearpathPlatform(std::optional<clearpath::PlatformEndpoint> endpoint, ClearpathSettings settings,
                                     SimulationSettings simulation, PlatformEnvironment environment)
    : endpoint_(std::move(endpoint)),
      settings_(std::move(settings)),
      simulation_(simulation),
      environment_(environment),
      simulated_(std::move(simulation), std::move(environment)) {}

ClearpathPlatform::~ClearpathPlatform() = default;

// A link that reopens with backoff and never fails the node (a missing port
// is a link down, which the components report as Failure), or the simulated
// platform in this process.
bridge::PlatformConnection& ClearpathPlatform::connect() {
  if (connection_) return *connection_;
  if (!endpoint_) {
    clearpath::sim::LoopbackConfig loopback;
    loopback.platform = settings_.sim;
    loopback.client = settings_.client;
    loopback.period = std::chrono::milliseconds(5);
    client_ = std::make_unique<clearpath::sim::LoopbackClient>(environment_.clock, environment_.scheduler, loopback);
    environment_.log(rt::LogLevel::info, "Clearpath platform: simulated in process");
  } else {
    // The kind `clearpath` makes a real platform only in an environment with an io_context.
    auto link = std::make_unique<clearpath::ClearpathLink>(*environment_.io, environment_.clock, environment_.scheduler,
                                                           *endpoint_, settings_.client);
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
      // Checked before the connection opens: a mapping the cameras refuse opens nothing.
      if (auto ok = bridge::check_clearpath_cameras_config(simulated_.cameras()->configs(), mounts); !ok)
        return unexpected(ok.error());
      auto made = bridge::ClearpathCameras::make(connect(), environment_.scheduler, *simulated_.cameras(), mounts);
      if (!made) return unexpected(made.error());
      cameras_ = std::move(*made);
    }
    backends.offer<components::Cameras>(cameras_.get());
    on_platform(components::Cameras::kInterface);
  } else if (interface == components::ManipulatorArm::kInterface) {
    const auto& joints = settings_.arm;
    if (joints.joints.empty()) return simulated_.provide(interface, backends);
    if (!arm_) {
      // Checked before the connection opens: a mapping the arm refuses opens nothing.
      if (auto ok = bridge::check_clearpath_arm_config(simulation_.arm, joints); !ok) return unexpected(ok.error());
      auto made = bridge::ClearpathArm::make(connect(), environment_.scheduler, simulation_.arm, joints);
      if (!made) return unexpected(made.error());
      arm_ = std::move(*made);
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

// ---- the kinds

namespace {

Error platform_error(std::string what, std::string field = {}) {
  Error e = make_error(ErrorCode::invalid_argument, std::move(what));
  e.field = std::move(field);
  return e;
}

const std::string* option(const PlatformSettings& settings, const char* key) {
  const auto it = settings.options.find(key);
  return it == settings.options.end() ? nullptr : &it->second;
}

ClearpathSettings section_of(const PlatformSettings& settings) {
  const ClearpathSettings* section = settings.sections.find<ClearpathSettings>();
  return section ? *section : ClearpathSettings{};
}

// What both kinds check: the camera mounts and arm joints mapped onto the
// platform fit the simulated cameras and arm (the problem is the mapping's:
// the `clearpath` section first, else the cameras' or the arm's own).
Expected<void> check_mapping(const ClearpathSettings& settings, const SimulationSettings& simulation) {
  if (!settings.cameras.mounts.empty())
    if (auto ok = bridge::check_clearpath_cameras_config(simulation.cameras.cameras, settings.cameras); !ok)
      return unexpected(platform_error(ok.error().message(), "clearpath|cameras"));
  if (!settings.arm.joints.empty())
    if (auto ok = bridge::check_clearpath_arm_config(simulation.arm, settings.arm); !ok)
      return unexpected(platform_error(ok.error().message(), "clearpath|manipulator"));
  return {};
}

}  // namespace

Expected<clearpath::PlatformEndpoint> clearpath_endpoint(const PlatformSettings& settings) {
  const std::string* serial = option(settings, "serial");
  const std::string* baud = option(settings, "baud");
  const std::string* udp = option(settings, "udp");
  const std::string* tcp = option(settings, "tcp");
  if ((serial != nullptr) + (udp != nullptr) + (tcp != nullptr) != 1)
    return unexpected(platform_error("'platform' needs exactly one of serial, udp or tcp"));
  if (baud && !serial) return unexpected(platform_error("'platform': baud applies to a serial port only"));
  clearpath::PlatformEndpoint endpoint;
  if (serial) {
    if (serial->empty())
      return unexpected(
          platform_error("'serial' must be a device path such as /dev/ttyUSB0, got " + jaus::quoted(*serial), "serial"));
    endpoint.kind = clearpath::PlatformEndpoint::Kind::serial;
    endpoint.device = *serial;
    if (baud) {
      unsigned value = 0;
      const std::string_view text = std::string_view(*baud).substr(!baud->empty() && baud->front() == '+');
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || value < 1200 || value > 4000000)
        return unexpected(
            platform_error("'baud' must be an integer 1200..4000000, got " + jaus::quoted(*baud), "baud"));
      endpoint.baud = value;
    }
    return endpoint;
  }
  const char* scheme = udp ? "udp" : "tcp";
  const std::string& text = udp ? *udp : *tcp;
  auto parsed = clearpath::parse_platform_endpoint(std::string(scheme) + ":" + text);
  if (!parsed)
    return unexpected(platform_error("'" + std::string(scheme) + "' must be HOST:PORT, got " + jaus::quoted(text), scheme));
  return *parsed;
}

PlatformSettings clearpath_sim_platform_settings(ClearpathSettings settings) {
  PlatformSettings p;
  p.kind = "clearpath_sim";
  p.sections.set(std::move(settings));
  return p;
}

PlatformSettings clearpath_platform_settings(const clearpath::PlatformEndpoint& endpoint, ClearpathSettings settings) {
  PlatformSettings p;
  p.kind = "clearpath";
  switch (endpoint.kind) {
    case clearpath::PlatformEndpoint::Kind::serial:
      p.options = {{"serial", endpoint.device}, {"baud", std::to_string(endpoint.baud)}};
      break;
    case clearpath::PlatformEndpoint::Kind::udp:
      p.options = {{"udp", endpoint.host + ":" + std::to_string(endpoint.port)}};
      break;
    case clearpath::PlatformEndpoint::Kind::tcp:
      p.options = {{"tcp", endpoint.host + ":" + std::to_string(endpoint.port)}};
      break;
  }
  p.sections.set(std::move(settings));
  return p;
}

const PlatformKind& clearpath_sim_platform_kind() {
  static const PlatformKind kind{
      .name = "clearpath_sim",
      .written = "sim",
      .options = {},
      // The simulated platform steers as the vehicle is configured, and
      // refuses the other kind's commands: the two must agree.
      .check = [](const PlatformSettings& settings, const SimulationSettings& simulation) -> Expected<void> {
        const ClearpathSettings section = section_of(settings);
        const bool ackermann_drive = section.vehicle.drive == bridge::DriveMode::ackermann;
        const bool ackermann_vehicle = simulation.vehicle.steering == components::Steering::ackermann;
        if (ackermann_drive != ackermann_vehicle)
          return unexpected(platform_error(
              ackermann_drive ? "'clearpath.drive' ackermann needs vehicle.steering ackermann on the simulated platform"
                              : "'clearpath.drive' commands a differential platform: vehicle.steering must be "
                                "differential on the simulated platform",
              "clearpath"));
        return check_mapping(section, simulation);
      },
      .make = [](const PlatformSettings& settings, const SimulationSettings& simulation,
                 PlatformEnvironment environment) -> Expected<std::unique_ptr<Platform>> {
        return std::unique_ptr<Platform>(
            std::make_unique<ClearpathPlatform>(std::nullopt, section_of(settings), simulation, std::move(environment)));
      }};
  return kind;
}

const PlatformKind& clearpath_platform_kind() {
  static const PlatformKind kind{
      .name = "clearpath",
      .written = {},
      .options = {"serial", "baud", "udp", "tcp"},
      .check = [](const PlatformSettings& settings, const SimulationSettings& simulation) -> Expected<void> {
        if (auto endpoint = clearpath_endpoint(settings); !endpoint) return unexpected(endpoint.error());
        return check_mapping(section_of(settings), simulation);
      },
      .make = [](const PlatformSettings& settings, const SimulationSettings& simulation,
                 PlatformEnvironment environment) -> Expected<std::unique_ptr<Platform>> {
        if (environment.io == nullptr)
          return unexpected(platform_error(
              "a Clearpath platform at an endpoint needs an opened host (NodeHost::open, on an io_context); an "
              "attached host takes model or clearpath_sim"));
        auto endpoint = clearpath_endpoint(settings);
        if (!endpoint) return unexpected(endpoint.error());
        return std::unique_ptr<Platform>(std::make_unique<ClearpathPlatform>(*endpoint, section_of(settings),
                                                                             simulation, std::move(environment)));
      }};
  return kind;
}

}  // namespace jaus::host
