// A JSS plugin: a shared library that brings SAE JAUS services (the
// translators of jss_face::ServiceTranslator, jaus/jss_face/translator.hpp)
// for its component kinds to a jausd that lists it under `plugins:`, as a
// component plugin brings the kinds themselves (jaus/runtime/component_plugin.hpp),
// with the same checks: the library exports one C symbol, jaus_jss_plugin,
// written by JAUS_JSS_PLUGIN; it returns a JssPluginInfo whose first field is
// the plugin ABI number, read before anything else, then the jaus version it
// was built against and its standard library and sanitizers. One library may
// write every entry point: a kind, its JSS service and its platform travel
// together. The node's JSS face asks the plugins' translators after the
// built-in kinds' (jss_translators.hpp).
//
//   jaus::jss_face::Translators my_translators(const jaus::jss_face::FaceConfig&) { ... }
//   std::vector<jaus::jss_face::TranslatorFactory> my_services() { return {&my_translators}; }
//   JAUS_JSS_PLUGIN("my_plugin", my_services)
//
// docs/plugins.md describes the design and a complete plugin.
#pragma once

#include <cstdint>
#include <vector>

#include "jaus/base/version.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/runtime/component_plugin.hpp"  // kComponentPluginToolchain: the same toolchain tag

namespace jaus::host {

// Bumped when JssPluginInfo changes: a loader reads only `abi` of a plugin
// whose number differs.
inline constexpr std::uint32_t kJssPluginAbi = 1;

// The translator factories a plugin brings; may fail (an exception is caught
// by the loader).
using JssPluginServices = std::vector<jss_face::TranslatorFactory> (*)();

extern "C" {
// C layout, so that `abi` is at offset 0 whatever else changes.
struct JssPluginInfo {
  std::uint32_t abi;         // kJssPluginAbi of the plugin's build
  const char* jaus_version;  // jaus::kVersion of the plugin's build
  const char* toolchain;     // rt::kComponentPluginToolchain of the plugin's build
  const char* name;          // the plugin's name, for logs and errors
  JssPluginServices services;
};
}

// The exported symbol's name, and its type.
inline constexpr const char* kJssPluginSymbol = "jaus_jss_plugin";
using JssPluginEntry = const JssPluginInfo* (*)();

}  // namespace jaus::host

// Writes the plugin's JSS entry point. `plugin_name`: a string literal;
// `services_function`: a function std::vector<jaus::jss_face::TranslatorFactory>().
#define JAUS_JSS_PLUGIN(plugin_name, services_function)                                                 \
  extern "C" __attribute__((visibility("default"))) const ::jaus::host::JssPluginInfo* jaus_jss_plugin() { \
    static const ::jaus::host::JssPluginInfo info{::jaus::host::kJssPluginAbi, ::jaus::kVersion.data(),      \
                                                  ::jaus::rt::kComponentPluginToolchain, plugin_name,        \
                                                  &services_function};                                       \
    return &info;                                                                                            \
  }
