#include "jaus/host/component_plugins.hpp"

#include <dlfcn.h>

#include <cstring>
#include <exception>
#include <map>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>

#include "jaus/base/version.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/jss_plugin.hpp"
#include "jaus/host/jss_translators.hpp"
#include "jaus/host/platform_kinds.hpp"
#include "jaus/host/platform_plugin.hpp"
#include "jaus/jss_face/face.hpp"  // FaceConfig: a plugin's factories are tried with the defaults
#include "jaus/runtime/component_plugin.hpp"

namespace jaus::host {

namespace {

struct PluginRegistry {
  std::vector<LoadedPlugin> plugins;
  std::map<std::string, std::string, std::less<>> kind_owner;           // kind -> "plugin 'name' (path)"
  std::map<std::string, std::string, std::less<>> platform_kind_owner;  // platform kind -> the same
  std::vector<jss_face::TranslatorFactory> jss_translators;              // the JSS plugins', in load order
};

PluginRegistry& registry() {
  static PluginRegistry r;
  return r;
}

Error plugin_error(const std::filesystem::path& path, std::string what) {
  return make_error(ErrorCode::invalid_argument, path.string() + ": " + std::move(what));
}

std::string text_or(const char* text, std::string_view fallback) { return text ? text : std::string(fallback); }

// What an exception escaping the plugin said.
std::string what_of(std::exception_ptr thrown) {
  try {
    std::rethrow_exception(std::move(thrown));
  } catch (const std::exception& e) {
    return std::string("threw: ") + e.what();
  } catch (...) {
    return "threw an exception that is not a std::exception";
  }
}

// The plugin's check and make, with any exception turned into an error
// naming the plugin and the kind: the plugin never unwinds into the host.
void guard(ComponentKind& kind, const std::string& plugin) {
  const std::string who = plugin + " kind '" + std::string(kind.name) + "'";
  if (kind.check)
    kind.check = [check = std::move(kind.check), who](const rt::KindOptions& options) -> Expected<void> {
      try {
        return check(options);
      } catch (...) {
        return unexpected(
            make_error(ErrorCode::invalid_argument, who + " checking its options " + what_of(std::current_exception())));
      }
    };
  kind.make = [make = std::move(kind.make),
               who](const rt::KindContext& context) -> Expected<std::unique_ptr<rt::Component>> {
    try {
      return make(context);
    } catch (...) {
      return unexpected(
          make_error(ErrorCode::invalid_argument, who + " making a component " + what_of(std::current_exception())));
    }
  };
}

// The same for a platform kind's check and make.
void guard(PlatformKind& kind, const std::string& plugin) {
  const std::string who = plugin + " platform kind '" + std::string(kind.name) + "'";
  if (kind.check)
    kind.check = [check = std::move(kind.check), who](const PlatformSettings& settings,
                                                      const SimulationSettings& simulation) -> Expected<void> {
      try {
        return check(settings, simulation);
      } catch (...) {
        return unexpected(make_error(ErrorCode::invalid_argument,
                                     who + " checking its settings " + what_of(std::current_exception())));
      }
    };
  kind.make = [make = std::move(kind.make), who](const PlatformSettings& settings, const SimulationSettings& simulation,
                                                 PlatformEnvironment environment) -> Expected<std::unique_ptr<Platform>> {
    try {
      return make(settings, simulation, std::move(environment));
    } catch (...) {
      return unexpected(
          make_error(ErrorCode::invalid_argument, who + " making the platform " + what_of(std::current_exception())));
    }
  };
}

// A plugin of either kind was built against this jaus, with this toolchain.
Expected<void> check_build(const std::filesystem::path& path, const std::string& name, const char* jaus_version,
                           const char* plugin_toolchain) {
  const std::string version = text_or(jaus_version, "(none)");
  if (version != kVersion)
    return unexpected(plugin_error(path, "plugin '" + name + "' was built against jaus " + version +
                                             ", this jausd is " + std::string(kVersion) + ": rebuild it"));
  const std::string toolchain = text_or(plugin_toolchain, "(none)");
  if (toolchain != rt::kComponentPluginToolchain)
    return unexpected(plugin_error(path, "plugin '" + name + "' was built for " + toolchain + ", this jausd for " +
                                             rt::kComponentPluginToolchain + ": rebuild it with the same flags"));
  return {};
}

// The entry point's description, checked field by field in the order the
// fields may be trusted: the ABI number first (nothing else is read when it
// differs), then the version, toolchain and layout.
Expected<const rt::ComponentPluginInfo*> checked_info(const std::filesystem::path& path, void* handle) {
  dlerror();
  void* symbol = dlsym(handle, rt::kComponentPluginSymbol);
  if (!symbol)
    return unexpected(plugin_error(path, "not a jaus component plugin: no " + std::string(rt::kComponentPluginSymbol) +
                                             " symbol (write JAUS_COMPONENT_PLUGIN, jaus/runtime/component_plugin.hpp)"));
  const auto entry = reinterpret_cast<rt::ComponentPluginEntry>(symbol);
  const rt::ComponentPluginInfo* info = entry();
  if (!info) return unexpected(plugin_error(path, std::string(rt::kComponentPluginSymbol) + " returned nothing"));
  if (info->abi != rt::kComponentPluginAbi)
    return unexpected(plugin_error(path, "plugin ABI " + std::to_string(info->abi) + ", this jausd loads ABI " +
                                             std::to_string(rt::kComponentPluginAbi) +
                                             ": rebuild the plugin against this jaus"));
  const std::string name = text_or(info->name, "(unnamed)");
  if (auto built = check_build(path, name, info->jaus_version, info->toolchain); !built)
    return unexpected(built.error());
  if (info->component_kind_size != sizeof(rt::ComponentKind))
    return unexpected(plugin_error(path, "plugin '" + name + "' sees a component kind of " +
                                             std::to_string(info->component_kind_size) + " bytes, this jausd of " +
                                             std::to_string(sizeof(rt::ComponentKind)) +
                                             ": built against other headers; rebuild it"));
  if (!info->name || !*info->name) return unexpected(plugin_error(path, "the plugin has no name"));
  if (!info->kinds) return unexpected(plugin_error(path, "plugin '" + name + "' has no kinds function"));
  return info;
}

// A platform entry point's description, checked as a component one's.
Expected<const PlatformPluginInfo*> checked_platform_info(const std::filesystem::path& path, void* symbol) {
  const auto entry = reinterpret_cast<PlatformPluginEntry>(symbol);
  const PlatformPluginInfo* info = entry();
  if (!info) return unexpected(plugin_error(path, std::string(kPlatformPluginSymbol) + " returned nothing"));
  if (info->abi != kPlatformPluginAbi)
    return unexpected(plugin_error(path, "platform plugin ABI " + std::to_string(info->abi) +
                                             ", this jausd loads ABI " + std::to_string(kPlatformPluginAbi) +
                                             ": rebuild the plugin against this jaus"));
  const std::string name = text_or(info->name, "(unnamed)");
  if (auto built = check_build(path, name, info->jaus_version, info->toolchain); !built)
    return unexpected(built.error());
  if (info->platform_kind_size != sizeof(PlatformKind))
    return unexpected(plugin_error(path, "plugin '" + name + "' sees a platform kind of " +
                                             std::to_string(info->platform_kind_size) + " bytes, this jausd of " +
                                             std::to_string(sizeof(PlatformKind)) +
                                             ": built against other headers; rebuild it"));
  if (!info->name || !*info->name) return unexpected(plugin_error(path, "the plugin has no name"));
  if (!info->kinds) return unexpected(plugin_error(path, "plugin '" + name + "' has no platform kinds function"));
  return info;
}

// The platform kinds a plugin brings, each checked before any is added.
Expected<std::vector<PlatformKind>> listed_platform_kinds(const std::filesystem::path& path,
                                                          const PlatformPluginInfo& info, const PluginRegistry& r) {
  const std::string name = info.name;
  std::vector<PlatformKind> kinds;
  try {
    kinds = info.kinds();
  } catch (...) {
    return unexpected(
        plugin_error(path, "plugin '" + name + "' listing its platform kinds " + what_of(std::current_exception())));
  }
  if (kinds.empty()) return unexpected(plugin_error(path, "plugin '" + name + "' brings no platform kind"));
  std::set<std::string_view> names;
  for (const auto& kind : kinds) {
    const std::string kind_name(kind.name);
    if (kind.name.empty())
      return unexpected(plugin_error(path, "plugin '" + name + "' brings a platform kind without a name"));
    if (!names.insert(kind.name).second)
      return unexpected(plugin_error(path, "plugin '" + name + "' brings platform kind '" + kind_name + "' twice"));
    if (find_platform_kind(kind.name)) {
      const auto owner = r.platform_kind_owner.find(kind.name);
      return unexpected(plugin_error(path, "plugin '" + name + "' brings platform kind '" + kind_name +
                                               "', a name already taken by " +
                                               (owner != r.platform_kind_owner.end() ? owner->second
                                                                                      : "a built-in platform kind")));
    }
    if (!kind.make)
      return unexpected(plugin_error(path, "plugin '" + name + "' platform kind '" + kind_name +
                                               "' cannot make platforms"));
  }
  return kinds;
}

// A JSS entry point's description, checked as a component one's.
Expected<const JssPluginInfo*> checked_jss_info(const std::filesystem::path& path, void* symbol) {
  const auto entry = reinterpret_cast<JssPluginEntry>(symbol);
  const JssPluginInfo* info = entry();
  if (!info) return unexpected(plugin_error(path, std::string(kJssPluginSymbol) + " returned nothing"));
  if (info->abi != kJssPluginAbi)
    return unexpected(plugin_error(path, "JSS plugin ABI " + std::to_string(info->abi) + ", this jausd loads ABI " +
                                             std::to_string(kJssPluginAbi) + ": rebuild the plugin against this jaus"));
  const std::string name = text_or(info->name, "(unnamed)");
  if (auto built = check_build(path, name, info->jaus_version, info->toolchain); !built)
    return unexpected(built.error());
  if (!info->name || !*info->name) return unexpected(plugin_error(path, "the plugin has no name"));
  if (!info->services) return unexpected(plugin_error(path, "plugin '" + name + "' has no JSS services function"));
  return info;
}

// The translator factories a JSS plugin brings, each tried once (with the
// default face settings) before any is added: a factory that throws or makes
// nothing is refused now, not when a JSS face is made. `names`: each
// translator's name, for the plugin's summary.
Expected<std::vector<jss_face::TranslatorFactory>> listed_jss_services(const std::filesystem::path& path,
                                                                       const JssPluginInfo& info,
                                                                       std::vector<std::string>& names) {
  const std::string name = info.name;
  std::vector<jss_face::TranslatorFactory> factories;
  try {
    factories = info.services();
    for (const auto factory : factories) {
      if (factory == nullptr) return unexpected(plugin_error(path, "plugin '" + name + "' lists an empty JSS factory"));
      const jss_face::Translators made = factory(jss_face::FaceConfig{});
      if (made.empty()) return unexpected(plugin_error(path, "plugin '" + name + "' has a JSS factory that makes nothing"));
      for (const auto& translator : made) {
        if (!translator) return unexpected(plugin_error(path, "plugin '" + name + "' made an empty JSS translator"));
        names.emplace_back(translator->name());
      }
    }
  } catch (...) {
    return unexpected(
        plugin_error(path, "plugin '" + name + "' listing its JSS services " + what_of(std::current_exception())));
  }
  if (factories.empty()) return unexpected(plugin_error(path, "plugin '" + name + "' brings no JSS service"));
  return factories;
}

}  // namespace

const std::vector<LoadedPlugin>& loaded_component_plugins() { return registry().plugins; }

std::vector<jss_face::TranslatorFactory> plugin_jss_translators() { return registry().jss_translators; }

std::vector<jss_face::TranslatorFactory> jss_translators() {
  auto all = builtin_jss_translators();
  const auto& plugins = registry().jss_translators;
  all.insert(all.end(), plugins.begin(), plugins.end());
  return all;
}

Expected<LoadedPlugin> load_component_plugin(const std::filesystem::path& requested) {
  std::error_code ec;
  // Absolute, so dlopen never searches the library path for a bare name.
  std::filesystem::path path = std::filesystem::absolute(requested, ec).lexically_normal();
  if (ec) path = requested;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  auto& r = registry();
  for (const auto& loaded : r.plugins)
    if (!ec && std::filesystem::weakly_canonical(loaded.path, ec) == canonical) return loaded;

  // RTLD_NOW: an undefined symbol is an error here, not a crash later.
  // Never closed: components of its kinds, and their code, live until exit.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    // dlerror() names the file too ("<path>: undefined symbol: ..."): said once.
    std::string why = text_or(dlerror(), "?");
    if (why.starts_with(path.string() + ": ")) why.erase(0, path.string().size() + 2);
    return unexpected(plugin_error(path, "cannot load the plugin: " + why));
  }
  // A plugin writes any of the entry points, or several.
  dlerror();
  void* platform_symbol = dlsym(handle, kPlatformPluginSymbol);
  dlerror();
  void* jss_symbol = dlsym(handle, kJssPluginSymbol);
  dlerror();
  const bool has_components = dlsym(handle, rt::kComponentPluginSymbol) != nullptr;
  if (!has_components && !platform_symbol && !jss_symbol)
    return unexpected(plugin_error(path, "not a jaus component plugin: no " + std::string(rt::kComponentPluginSymbol) +
                                             " symbol (write JAUS_COMPONENT_PLUGIN, jaus/runtime/component_plugin.hpp), "
                                             "nor a platform plugin: no " + std::string(kPlatformPluginSymbol) +
                                             " symbol (JAUS_PLATFORM_PLUGIN, jaus/host/platform_plugin.hpp), "
                                             "nor a JSS plugin: no " + std::string(kJssPluginSymbol) +
                                             " symbol (JAUS_JSS_PLUGIN, jaus/host/jss_plugin.hpp)"));
  std::string name;
  std::vector<ComponentKind> kinds;
  if (has_components) {
    const auto info = checked_info(path, handle);
    if (!info) return unexpected(info.error());
    name = (*info)->name;
    try {
      kinds = (*info)->kinds();
    } catch (...) {
      return unexpected(plugin_error(path, "plugin '" + name + "' listing its kinds " + what_of(std::current_exception())));
    }
    if (kinds.empty()) return unexpected(plugin_error(path, "plugin '" + name + "' brings no component kind"));
  }
  std::vector<PlatformKind> platforms;
  if (platform_symbol) {
    const auto info = checked_platform_info(path, platform_symbol);
    if (!info) return unexpected(info.error());
    if (name.empty()) name = (*info)->name;
    auto listed = listed_platform_kinds(path, **info, r);
    if (!listed) return unexpected(listed.error());
    platforms = std::move(*listed);
  }
  std::vector<jss_face::TranslatorFactory> jss_services;
  std::vector<std::string> jss_service_names;
  if (jss_symbol) {
    const auto info = checked_jss_info(path, jss_symbol);
    if (!info) return unexpected(info.error());
    if (name.empty()) name = (*info)->name;
    auto listed = listed_jss_services(path, **info, jss_service_names);
    if (!listed) return unexpected(listed.error());
    jss_services = std::move(*listed);
  }
  const std::string who = "plugin '" + name + "' (" + path.string() + ")";

  // Every kind is checked before any is added: a plugin loads whole or not at all.
  std::set<std::string_view> names;
  for (const auto& kind : kinds) {
    const std::string kind_name(kind.name);
    if (kind.name.empty()) return unexpected(plugin_error(path, "plugin '" + name + "' brings a kind without a name"));
    if (!names.insert(kind.name).second)
      return unexpected(plugin_error(path, "plugin '" + name + "' brings kind '" + kind_name + "' twice"));
    if (find_component_kind(kind.name)) {
      const auto owner = r.kind_owner.find(kind.name);
      return unexpected(plugin_error(path, "plugin '" + name + "' brings kind '" + kind_name +
                                               "', a name already taken by " +
                                               (owner != r.kind_owner.end() ? owner->second : "a built-in kind")));
    }
    if (!kind.make)
      return unexpected(plugin_error(path, "plugin '" + name + "' kind '" + kind_name + "' cannot make components"));
  }
  LoadedPlugin loaded{path, name, {}, {}, {}};
  // Undoes what this load added (a kind the list then refuses).
  const auto undo = [&] {
    for (const auto& done : loaded.kinds) {
      remove_component_kind(done);
      r.kind_owner.erase(done);
    }
    for (const auto& done : loaded.platform_kinds) {
      remove_platform_kind(done);
      r.platform_kind_owner.erase(done);
    }
  };
  for (auto& kind : kinds) {
    const std::string kind_name(kind.name);
    guard(kind, who);
    if (auto added = add_component_kind(std::move(kind)); !added) {
      undo();
      return unexpected(plugin_error(path, "plugin '" + name + "': " + added.error().message()));
    }
    loaded.kinds.push_back(kind_name);
    r.kind_owner.emplace(kind_name, who);
  }
  for (auto& kind : platforms) {
    const std::string kind_name(kind.name);
    guard(kind, who);
    // Its written name and options too must be its own (add_platform_kind says whose they are).
    if (auto added = add_platform_kind(std::move(kind)); !added) {
      undo();
      return unexpected(plugin_error(path, "plugin '" + name + "': " + added.error().message()));
    }
    loaded.platform_kinds.push_back(kind_name);
    r.platform_kind_owner.emplace(kind_name, who);
  }
  // Last: nothing can refuse the plugin any more, so no undo is needed.
  r.jss_translators.insert(r.jss_translators.end(), jss_services.begin(), jss_services.end());
  loaded.jss_services = std::move(jss_service_names);
  r.plugins.push_back(loaded);
  return loaded;
}

}  // namespace jaus::host
