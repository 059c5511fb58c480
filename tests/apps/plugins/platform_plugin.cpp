// A working platform plugin: platform kind `plugin_rig` (written
// `plugin_rig`, option plugin_wheels 2..8) carries the components on their
// own simulations, as `model` does, and says in the host's log when it is
// made and when it stops. `plugin_wheels: explode` throws from its check.
#include <charconv>
#include <memory>
#include <stdexcept>
#include <string>

#include "jaus/host/model_platform.hpp"
#include "jaus/host/platform_plugin.hpp"

namespace {

class PluginRig final : public jaus::host::Platform {
 public:
  PluginRig(jaus::host::SimulationSettings simulation, jaus::host::PlatformEnvironment environment)
      : log_(environment.log), model_(std::move(simulation), std::move(environment)) {}
  jaus::Expected<void> provide(std::string_view interface, jaus::rt::Backends& backends) override {
    return model_.provide(interface, backends);
  }
  void stop() override {
    model_.stop();
    log_(jaus::rt::LogLevel::info, "plugin rig: stopped");
  }

 private:
  jaus::rt::LogFn log_;
  jaus::host::ModelPlatform model_;
};

jaus::Expected<int> wheels(const jaus::host::PlatformSettings& settings) {
  const auto it = settings.options.find("plugin_wheels");
  if (it == settings.options.end()) return 4;
  const std::string& text = it->second;
  if (text == "explode") throw std::runtime_error("wheels exploded");  // the loader's guard turns it into an error
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || value < 2 || value > 8) {
    jaus::Error e = jaus::make_error(jaus::ErrorCode::invalid_argument,
                                     "'plugin_wheels' must be an integer 2..8, got '" + text + "'");
    e.field = "plugin_wheels";
    return jaus::unexpected(e);
  }
  return value;
}

std::vector<jaus::host::PlatformKind> platform_kinds() {
  return {jaus::host::PlatformKind{
      .name = "plugin_rig",
      .written = "plugin_rig",
      .options = {"plugin_wheels"},
      .check = [](const jaus::host::PlatformSettings& settings,
                  const jaus::host::SimulationSettings&) -> jaus::Expected<void> {
        if (auto w = wheels(settings); !w) return jaus::unexpected(w.error());
        return {};
      },
      .make = [](const jaus::host::PlatformSettings& settings, const jaus::host::SimulationSettings& simulation,
                 jaus::host::PlatformEnvironment environment)
          -> jaus::Expected<std::unique_ptr<jaus::host::Platform>> {
        environment.log(jaus::rt::LogLevel::info, "plugin rig: " + std::to_string(*wheels(settings)) + " wheels");
        return std::unique_ptr<jaus::host::Platform>(std::make_unique<PluginRig>(simulation, std::move(environment)));
      }}};
}

}  // namespace

JAUS_PLATFORM_PLUGIN("test_rig_platform", platform_kinds)
