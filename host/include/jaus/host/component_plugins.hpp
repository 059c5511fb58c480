// Component and platform kinds from shared libraries
// (jaus/runtime/component_plugin.hpp, jaus/host/platform_plugin.hpp):
// a plugin is opened, its entry point checked (ABI number first, then the
// jaus version, toolchain and layout) and its kinds added to the host's list
// (component_kinds.hpp). Every failure is an error naming the file, never a
// crash: a library that will not open, has no entry point, was built for
// another ABI, version or toolchain, brings a kind whose name is taken, or
// throws. A loaded library stays loaded for the process's life (components
// of its kinds may exist until the end), and each kind's check and make are
// wrapped so that an exception from the plugin becomes an error.
//
// The program loading plugins must export the jaus symbols they use
// (jaus_enable_component_plugins() in cmake/jausPlugin.cmake).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::host {

struct LoadedPlugin {
  std::filesystem::path path;      // as opened (absolute)
  std::string name;                // the plugin's own name
  std::vector<std::string> kinds;  // the component kinds it added, in its order
  std::vector<std::string> platform_kinds;  // the platform kinds it added (jaus/host/platform_plugin.hpp)
  std::vector<std::string> jss_services;    // the names of the JSS translators it added (jaus/host/jss_plugin.hpp)
};

// Opens the plugin at `path` and adds what it brings: component kinds,
// platform kinds (platform_kinds.hpp), JSS services (jss_translators.hpp), or
// several, each entry point checked alike. Loading the same file again
// (the same canonical path) adds nothing and returns what the first load did.
Expected<LoadedPlugin> load_component_plugin(const std::filesystem::path& path);

// Every plugin this process has loaded, in load order.
const std::vector<LoadedPlugin>& loaded_component_plugins();

}  // namespace jaus::host
