#include "plugins_config.hpp"

#include <map>
#include <string>
#include <system_error>

#include "jausd_config.hpp"

namespace jausd {

using namespace yaml_reader;

std::vector<jaus::host::LoadedPlugin> load_plugins(const Entry& plugins,
                                                   const std::optional<std::filesystem::path>& folder) {
  std::vector<jaus::host::LoadedPlugin> loaded;
  const auto entries = read_list(plugins);
  if (!entries.empty() && !folder)
    fail(plugins.key_line, "'plugins' are loaded only from a configuration file (jausd --config FILE)");
  std::map<std::filesystem::path, int> listed;  // canonical path -> line
  for (const auto& node : entries) {
    const Entry entry{"plugins", line_of(node), node};
    const std::string& text = entry.scalar("a path to a plugin (.so)");
    if (text.empty()) entry.must_be("a path to a plugin (.so)");
    std::filesystem::path path(text);
    if (path.is_relative()) path = (*folder / path).lexically_normal();
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(path, ec);
    if (const auto [first, inserted] = listed.emplace(ec ? path : canonical, entry.key_line); !inserted)
      fail(entry.key_line, "plugin " + path.string() + " is listed twice" + first_at(first->second));
    auto plugin = jaus::host::load_component_plugin(path);
    if (!plugin) fail(entry.key_line, plugin.error().message());
    loaded.push_back(std::move(*plugin));
  }
  return loaded;
}

std::vector<std::string> plugin_summaries(const JausdConfig& config) {
  std::vector<std::string> lines;
  for (const auto& plugin : config.plugins) {
    std::string line = "plugin '" + plugin.name + "' (" + plugin.path.string() + "): ";
    if (!plugin.kinds.empty()) line += "component kinds " + join(plugin.kinds);
    if (!plugin.kinds.empty() && !plugin.platform_kinds.empty()) line += "; ";
    if (!plugin.platform_kinds.empty()) line += "platform kinds " + join(plugin.platform_kinds);
    if (!plugin.jss_services.empty())
      line += std::string(plugin.kinds.empty() && plugin.platform_kinds.empty() ? "" : "; ") + "JSS services " +
              join(plugin.jss_services);
    lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace jausd
