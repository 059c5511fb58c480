// The `plugins:` key of jausd's configuration: component plugins
// (docs/plugins.md) listed by path, loaded before the components are read so
// that their kinds can be configured and their options checked like the
// built-in ones. Paths are relative to the configuration file's folder.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "config_reader.hpp"
#include "jaus/host/component_plugins.hpp"

namespace jausd {

// Loads every plugin the entry lists, in order; the first problem is a
// yaml_reader::Failure at the line of its list entry. Without a folder (a
// configuration from memory, not a file) a plugin list is refused: nothing
// is loaded from text that names no place.
std::vector<jaus::host::LoadedPlugin> load_plugins(const yaml_reader::Entry& plugins,
                                                   const std::optional<std::filesystem::path>& folder);

}  // namespace jausd
