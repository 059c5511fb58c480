// A platform plugin: a shared library that brings platform kinds
// (host::PlatformKind, platform_kinds.hpp) to a jausd that lists it under
// `plugins:`, as a component plugin brings component kinds
// (jaus/runtime/component_plugin.hpp), with the same checks: the library
// exports one C symbol, jaus_platform_plugin, written by
// JAUS_PLATFORM_PLUGIN; it returns a PlatformPluginInfo whose first field is
// the plugin ABI number, read before anything else, then the jaus version it
// was built against, its standard library and sanitizers, and the size of
// host::PlatformKind. One library may write both entry points.
//
//   std::vector<jaus::host::PlatformKind> my_platforms() { return {my_platform_kind()}; }
//   JAUS_PLATFORM_PLUGIN("my_platforms", my_platforms)
//
// docs/plugins.md describes the design and a complete plugin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "jaus/base/version.hpp"
#include "jaus/host/platform_kinds.hpp"
#include "jaus/runtime/component_plugin.hpp"  // kComponentPluginToolchain: the same toolchain tag

namespace jaus::host {

// Bumped when PlatformPluginInfo changes: a loader reads only `abi` of a
// plugin whose number differs.
inline constexpr std::uint32_t kPlatformPluginAbi = 1;

// The kinds a plugin brings; may fail (an exception is caught by the loader).
using PlatformPluginKinds = std::vector<PlatformKind> (*)();

extern "C" {
// C layout, so that `abi` is at offset 0 whatever else changes.
struct PlatformPluginInfo {
  std::uint32_t abi;               // kPlatformPluginAbi of the plugin's build
  const char* jaus_version;        // jaus::kVersion of the plugin's build
  const char* toolchain;           // rt::kComponentPluginToolchain of the plugin's build
  std::size_t platform_kind_size;  // sizeof(PlatformKind) of the plugin's build
  const char* name;                // the plugin's name, for logs and errors
  PlatformPluginKinds kinds;
};
}

// The exported symbol's name, and its type.
inline constexpr const char* kPlatformPluginSymbol = "jaus_platform_plugin";
using PlatformPluginEntry = const PlatformPluginInfo* (*)();

}  // namespace jaus::host

// Writes the plugin's platform entry point. `plugin_name`: a string literal;
// `kinds_function`: a function std::vector<jaus::host::PlatformKind>() (its
// kinds; their names, written names and option keys are string literals, or
// live as long as the process).
#define JAUS_PLATFORM_PLUGIN(plugin_name, kinds_function)                                               \
  extern "C" __attribute__((visibility("default"))) const ::jaus::host::PlatformPluginInfo*            \
  jaus_platform_plugin() {                                                                              \
    static const ::jaus::host::PlatformPluginInfo info{                                                 \
        ::jaus::host::kPlatformPluginAbi,       ::jaus::kVersion.data(),                                \
        ::jaus::rt::kComponentPluginToolchain,  sizeof(::jaus::host::PlatformKind),                     \
        plugin_name,                            &kinds_function};                                       \
    return &info;                                                                                       \
  }
