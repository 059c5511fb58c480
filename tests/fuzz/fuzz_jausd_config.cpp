// Fuzz target: any text as a jausd configuration file. It loads or gives one
// error with a line inside the text; it never throws or crashes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "jausd_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto loaded = jausd::load_config_string(text, "fuzz.yaml");
  if (!loaded) {
    const auto& error = loaded.error();
    if (error.what.empty() || error.line < 0) std::abort();
    // A line past the end of the text would point the user nowhere.
    std::size_t lines = 1;
    for (const char c : text) lines += c == '\n';
    if (static_cast<std::size_t>(error.line) > lines + 1) std::abort();
  }
  return 0;
}
