// A platform plugin of a future ABI: only its first field may be read.
#include "jaus/host/platform_plugin.hpp"

extern "C" __attribute__((visibility("default"))) const jaus::host::PlatformPluginInfo* jaus_platform_plugin() {
  static const jaus::host::PlatformPluginInfo info{jaus::host::kPlatformPluginAbi + 1, nullptr, nullptr, 0, nullptr,
                                                   nullptr};
  return &info;
}
