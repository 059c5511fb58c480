// The page's files (console/web/), embedded at build time
// (console/cmake/embed_web.cmake): the console works offline, with nothing
// to install on the operator's side.
#pragma once

#include <span>
#include <string_view>

namespace jaus::console {

struct WebAsset {
  std::string_view path;          // "/index.html"
  std::string_view content_type;  // "text/html; charset=utf-8"
  std::span<const unsigned char> bytes;
};

std::span<const WebAsset> web_assets();

// The asset served for a request path ("/" is "/index.html"); null if none.
const WebAsset* find_web_asset(std::string_view path);

}  // namespace jaus::console
