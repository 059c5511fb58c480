#include "jaus/console/web_assets.hpp"

namespace jaus::console {

const WebAsset* find_web_asset(std::string_view path) {
  if (const auto query = path.find('?'); query != std::string_view::npos) path = path.substr(0, query);
  if (path == "/") path = "/index.html";
  for (const auto& asset : web_assets())
    if (asset.path == path) return &asset;
  return nullptr;
}

}  // namespace jaus::console
