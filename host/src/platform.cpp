#include "jaus/host/platform.hpp"

#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/model_platform.hpp"

namespace jaus::host {

Expected<std::unique_ptr<Platform>> make_platform(const PlatformSettings& settings, const SimulationSettings& simulation,
                                                  PlatformEnvironment environment) {
  if (!environment.log) environment.log = rt::silent_log();
  switch (settings.kind) {
    case PlatformSettings::Kind::model:
      return std::unique_ptr<Platform>(std::make_unique<ModelPlatform>(simulation, std::move(environment)));
    case PlatformSettings::Kind::clearpath:
      if (environment.io == nullptr)
        return unexpected(make_error(ErrorCode::invalid_argument,
                                     "a Clearpath platform at an endpoint needs an opened host (NodeHost::open, on an "
                                     "io_context); an attached host takes model or clearpath_sim"));
      [[fallthrough]];
    case PlatformSettings::Kind::clearpath_sim:
      return std::unique_ptr<Platform>(std::make_unique<ClearpathPlatform>(settings, simulation, std::move(environment)));
  }
  return unexpected(make_error(ErrorCode::invalid_argument, "unknown platform kind"));
}

}  // namespace jaus::host
