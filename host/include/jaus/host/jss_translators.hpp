// The JSS services of the component kinds components/ lists: each kind with
// JSS services keeps their translators in its folder (components/<name>/jss/)
// and lists its factory with jaus_jss_translators(); the host never names
// one. A plugin kind's come from its plugin (jss_plugin.hpp). A node host hands these to its JSS face (NodeHost, jss.enabled); a
// test that makes a face of its own hands it the same list.
#pragma once

#include <vector>

#include "jaus/jss_face/translator.hpp"

namespace jaus::host {

// Every kind's translator factory, in the order of components/CMakeLists.txt
// (generated from its CMake files). The face asks the core services first,
// then these in this order; services of different kinds never overlap (each
// answers only on its own RA component ID).
std::vector<jss_face::TranslatorFactory> builtin_jss_translators();

// The JSS plugins' factories (jss_plugin.hpp), in load order
// (component_plugins.hpp adds them when it loads a plugin).
std::vector<jss_face::TranslatorFactory> plugin_jss_translators();

// What a node host hands its JSS face: the built-in kinds' factories, then
// the plugins'.
std::vector<jss_face::TranslatorFactory> jss_translators();

}  // namespace jaus::host
