#include "jaus/host/platform_kinds.hpp"

#include <algorithm>
#include <string>

#include "jaus/base/quoted.hpp"

namespace jaus::host {

namespace {

std::vector<PlatformKind>& platform_registry() {
  static std::vector<PlatformKind> registry = [] {
    std::vector<PlatformKind> r;
    for (const PlatformKind* kind : builtin_platform_kinds()) r.push_back(*kind);
    return r;
  }();
  return registry;
}

Error platform_kind_error(std::string what, std::string field = {}) {
  Error e = make_error(ErrorCode::invalid_argument, std::move(what));
  e.field = std::move(field);
  return e;
}

std::string known_platform_kinds() {
  std::string out;
  for (const auto& kind : platform_registry()) out += (out.empty() ? "" : ", ") + std::string(kind.name);
  return out.empty() ? "none" : out;
}

}  // namespace

const std::vector<PlatformKind>& platform_kinds() { return platform_registry(); }

const PlatformKind* find_platform_kind(std::string_view name) {
  for (const auto& kind : platform_registry())
    if (kind.name == name) return &kind;
  return nullptr;
}

const PlatformKind* platform_kind_written(std::string_view written) {
  if (written.empty()) return nullptr;
  for (const auto& kind : platform_registry())
    if (kind.written == written) return &kind;
  return nullptr;
}

const PlatformKind* platform_kind_with_option(std::string_view key) {
  for (const auto& kind : platform_registry())
    if (std::find(kind.options.begin(), kind.options.end(), key) != kind.options.end()) return &kind;
  return nullptr;
}

Expected<void> add_platform_kind(PlatformKind kind) {
  if (kind.name.empty()) return unexpected(platform_kind_error("a platform kind needs a name"));
  const std::string name(kind.name);
  if (find_platform_kind(kind.name)) return unexpected(platform_kind_error("platform kind '" + name + "' already exists"));
  if (const PlatformKind* other = platform_kind_written(kind.written))
    return unexpected(platform_kind_error("platform kind '" + name + "' is written '" + std::string(kind.written) +
                              "', as platform kind '" + std::string(other->name) + "' is"));
  for (const auto key : kind.options)
    if (const PlatformKind* other = platform_kind_with_option(key))
      return unexpected(platform_kind_error("platform kind '" + name + "' takes option '" + std::string(key) +
                                "', which names platform kind '" + std::string(other->name) + "'"));
  if (!kind.make) return unexpected(platform_kind_error("platform kind '" + name + "' cannot make platforms"));
  platform_registry().push_back(std::move(kind));
  return {};
}

bool remove_platform_kind(std::string_view name) {
  auto& all = platform_registry();
  for (auto it = all.begin(); it != all.end(); ++it)
    if (it->name == name) {
      all.erase(it);
      return true;
    }
  return false;
}

Expected<void> check_platform(const PlatformSettings& settings, const SimulationSettings& simulation) {
  const PlatformKind* kind = find_platform_kind(settings.kind);
  if (!kind)
    return unexpected(
        platform_kind_error("platform kind " + jaus::quoted(settings.kind) + " is not in this build (known: " + known_platform_kinds() + ")"));
  for (const auto& [key, value] : settings.options)
    if (std::find(kind->options.begin(), kind->options.end(), key) == kind->options.end())
      return unexpected(platform_kind_error("platform " + std::string(kind->name) + " takes no option " + jaus::quoted(key), key));
  if (kind->check) return kind->check(settings, simulation);
  return {};
}

Expected<std::unique_ptr<Platform>> make_platform(const PlatformSettings& settings, const SimulationSettings& simulation,
                                                  PlatformEnvironment environment) {
  if (auto checked = check_platform(settings, simulation); !checked) return unexpected(checked.error());
  if (!environment.log) environment.log = rt::silent_log();
  auto made = find_platform_kind(settings.kind)->make(settings, simulation, std::move(environment));
  if (made && !*made) return unexpected(platform_kind_error("platform kind '" + settings.kind + "' made no platform"));
  return made;
}

}  // namespace jaus::host
