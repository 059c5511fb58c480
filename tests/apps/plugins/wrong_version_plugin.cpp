// A plugin built against another jaus version.
#include "broken_plugins.hpp"

extern "C" __attribute__((visibility("default"))) const jaus::rt::ComponentPluginInfo* jaus_component_plugin() {
  static const jaus::rt::ComponentPluginInfo info{jaus::rt::kComponentPluginAbi, "0.0.1", jaus::rt::kComponentPluginToolchain,
                                                  sizeof(jaus::rt::ComponentKind), "old_version", &broken::one_kind};
  return &info;
}
