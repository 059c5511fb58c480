#include "jaus/console/kind_views.hpp"

#include <algorithm>

#include "jaus/host/component_kinds.hpp"

namespace jaus::console {

std::vector<std::string_view> views_of(std::uint8_t component_id) {
  std::vector<std::string_view> views;
  for (const auto& kind : jaus::host::component_kinds()) {
    if (kind.default_id != component_id) continue;
    for (const auto view : kind.operator_views)
      if (std::find(views.begin(), views.end(), view) == views.end()) views.push_back(view);
  }
  return views;
}

std::map<std::uint8_t, std::vector<std::string>> views_by_id() {
  std::map<std::uint8_t, std::vector<std::string>> table;
  for (const auto& kind : jaus::host::component_kinds()) {
    if (kind.operator_views.empty() || table.count(kind.default_id)) continue;
    const auto views = views_of(kind.default_id);
    table[kind.default_id] = std::vector<std::string>(views.begin(), views.end());
  }
  return table;
}

}  // namespace jaus::console
