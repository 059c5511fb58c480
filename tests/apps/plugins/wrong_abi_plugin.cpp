// A plugin of a future ABI: only its first field may be read.
#include "broken_plugins.hpp"

extern "C" __attribute__((visibility("default"))) const jaus::rt::ComponentPluginInfo* jaus_component_plugin() {
  static const jaus::rt::ComponentPluginInfo info{jaus::rt::kComponentPluginAbi + 1, nullptr, nullptr, 0, nullptr,
                                                  nullptr};
  return &info;
}
