// A component plugin: a shared library that brings component kinds
// (rt::ComponentKind) to a jausd that lists it under `plugins:` in its
// configuration. The library exports one C symbol, jaus_component_plugin,
// written by JAUS_COMPONENT_PLUGIN; it returns a ComponentPluginInfo whose
// first field is the plugin ABI number, read before anything else, then what
// the loader checks before it calls any C++ code of the plugin: the jaus
// version it was built against (C++ classes change between versions), its
// standard library and sanitizers, and the size of rt::ComponentKind.
//
// A plugin is compiled against the installed headers only and links no jaus
// library: jausd carries the framework, exports its symbols, and the plugin's
// references resolve to that one copy when it is loaded
// (jaus_add_component_plugin() in the CMake package builds one this way).
//
//   std::vector<jaus::rt::ComponentKind> my_kinds() { return {my_kind()}; }
//   JAUS_COMPONENT_PLUGIN("my_plugin", my_kinds)
//
// docs/plugins.md describes the design and a complete plugin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "jaus/base/version.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::rt {

// Bumped when ComponentPluginInfo changes: a loader reads only `abi` of a
// plugin whose number differs.
inline constexpr std::uint32_t kComponentPluginAbi = 1;

// What a plugin and the program loading it must share beyond the jaus
// version: the C++ standard library and its ABI, its debug mode (which
// changes container layouts) and AddressSanitizer (its container checks need
// both sides instrumented alike).
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JAUS_PLUGIN_ASAN_TAG_ " asan"
#endif
#endif
#if !defined(JAUS_PLUGIN_ASAN_TAG_) && defined(__SANITIZE_ADDRESS__)
#define JAUS_PLUGIN_ASAN_TAG_ " asan"
#endif
#if !defined(JAUS_PLUGIN_ASAN_TAG_)
#define JAUS_PLUGIN_ASAN_TAG_ ""
#endif
#if defined(_LIBCPP_VERSION)
#define JAUS_PLUGIN_STDLIB_TAG_ "libc++"
#elif defined(__GLIBCXX__) && defined(_GLIBCXX_USE_CXX11_ABI) && _GLIBCXX_USE_CXX11_ABI
#define JAUS_PLUGIN_STDLIB_TAG_ "libstdc++ cxx11-abi"
#elif defined(__GLIBCXX__)
#define JAUS_PLUGIN_STDLIB_TAG_ "libstdc++ old-abi"
#else
#define JAUS_PLUGIN_STDLIB_TAG_ "unknown-stdlib"
#endif
#if defined(_GLIBCXX_DEBUG)
#define JAUS_PLUGIN_DEBUG_TAG_ " debug-containers"
#else
#define JAUS_PLUGIN_DEBUG_TAG_ ""
#endif
inline constexpr const char* kComponentPluginToolchain =
    JAUS_PLUGIN_STDLIB_TAG_ JAUS_PLUGIN_DEBUG_TAG_ JAUS_PLUGIN_ASAN_TAG_;

// The kinds a plugin brings; may fail (an exception is caught by the loader).
using ComponentPluginKinds = std::vector<ComponentKind> (*)();

extern "C" {
// C layout, so that `abi` is at offset 0 whatever else changes.
struct ComponentPluginInfo {
  std::uint32_t abi;                // kComponentPluginAbi of the plugin's build
  const char* jaus_version;         // jaus::kVersion of the plugin's build
  const char* toolchain;            // kComponentPluginToolchain of the plugin's build
  std::size_t component_kind_size;  // sizeof(ComponentKind) of the plugin's build
  const char* name;                 // the plugin's name, for logs and errors
  ComponentPluginKinds kinds;
};
}

// The exported symbol's name, and its type.
inline constexpr const char* kComponentPluginSymbol = "jaus_component_plugin";
using ComponentPluginEntry = const ComponentPluginInfo* (*)();

}  // namespace jaus::rt

// Writes the plugin's entry point, the one symbol it exports.
// `plugin_name`: a string literal; `kinds_function`: a function
// std::vector<jaus::rt::ComponentKind>() (its kinds; their names and option
// keys are string literals, or live as long as the process).
#define JAUS_COMPONENT_PLUGIN(plugin_name, kinds_function)                                               \
  extern "C" __attribute__((visibility("default"))) const ::jaus::rt::ComponentPluginInfo*              \
  jaus_component_plugin() {                                                                              \
    static const ::jaus::rt::ComponentPluginInfo info{                                                   \
        ::jaus::rt::kComponentPluginAbi,         ::jaus::kVersion.data(),                                \
        ::jaus::rt::kComponentPluginToolchain,   sizeof(::jaus::rt::ComponentKind),                      \
        plugin_name,                             &kinds_function};                                       \
    return &info;                                                                                        \
  }
