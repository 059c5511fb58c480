// The platform kinds a node host can put its components on, and how one is
// made from PlatformSettings. A kind describes itself (PlatformKind): its
// name, how a configuration names it, the options it takes and how it checks
// them, and how to make the platform. The host walks the list and never
// names one: the list is the kinds the platform libraries register
// (builtin_platform_kinds(), generated at build time from
// jaus_platform_kind() in host/CMakeLists.txt) and those added at run time
// (add_platform_kind: a test's, a plugin's, jaus/host/platform_plugin.hpp).
// Header only for what a plugin needs (PlatformKind).
#pragma once

#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/host/platform.hpp"
#include "jaus/host/platform_settings.hpp"

namespace jaus::host {

struct PlatformKind {
  std::string_view name;  // "model", "clearpath_sim", "clearpath"
  // How a configuration names the kind alone (jausd's `platform: sim`);
  // empty: only by its options (`platform: {serial: ...}`).
  std::string_view written;
  // The option keys it takes (PlatformSettings::options); a configuration
  // that gives one of them names this kind.
  std::vector<std::string_view> options;
  // The first problem with `settings` (its options, its sections, how they
  // agree with `simulation`), or nothing; nothing is built. Error::field
  // says where: an option's key, or the configuration sections the problem
  // lies in, most to blame first, separated by '|' ("clearpath|cameras");
  // empty: the platform itself. Empty function: nothing to check.
  std::function<Expected<void>(const PlatformSettings& settings, const SimulationSettings& simulation)> check;
  // The platform, on `environment` (settings checked first). An error: one
  // it cannot be made in (a real link without an io_context).
  std::function<Expected<std::unique_ptr<Platform>>(const PlatformSettings& settings,
                                                    const SimulationSettings& simulation,
                                                    PlatformEnvironment environment)>
      make;
};

// Every platform kind this process knows, built-in first. Add or remove
// kinds before any host opens or configuration is read (pointers into the
// list stay valid until the next change).
const std::vector<PlatformKind>& platform_kinds();
const PlatformKind* find_platform_kind(std::string_view name);
// The kind a configuration names alone by `written`, or the one taking
// option `key` (nullptr: none).
const PlatformKind* platform_kind_written(std::string_view written);
const PlatformKind* platform_kind_with_option(std::string_view key);
// A kind of one's own: an error (invalid_argument) when the name is empty
// or taken, its written name or an option key is another kind's, or it
// cannot make platforms.
Expected<void> add_platform_kind(PlatformKind kind);
bool remove_platform_kind(std::string_view name);  // false: no such kind
// What the platform libraries register (generated from host/CMakeLists.txt).
std::vector<const PlatformKind*> builtin_platform_kinds();

// `settings` are good for their kind: the kind exists, every option is one
// it takes, and its check passes. The error's field as PlatformKind::check.
Expected<void> check_platform(const PlatformSettings& settings, const SimulationSettings& simulation);

// The platform `settings` names (checked first), on `environment`.
Expected<std::unique_ptr<Platform>> make_platform(const PlatformSettings& settings, const SimulationSettings& simulation,
                                                  PlatformEnvironment environment);

}  // namespace jaus::host
