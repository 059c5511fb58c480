// Fuzz target: any text as a jausd configuration file. It loads or gives one
// error with a line inside the text; it never throws or crashes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "jausd_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto loaded = jausd::load_config_string(text, "fuzz.yaml");
  if (!loaded) {
    const auto& error = loaded.error();  // where: "fuzz.yaml" or "fuzz.yaml:<line>"
    if (!error.field.starts_with("fuzz.yaml") || error.message().size() <= error.field.size() + 2) std::abort();
    const std::string_view line_text = std::string_view(error.field).substr(std::string_view("fuzz.yaml").size());
    if (!line_text.empty()) {
      if (line_text.front() != ':') std::abort();
      const long line = std::strtol(std::string(line_text.substr(1)).c_str(), nullptr, 10);
      // A line past the end of the text would point the user nowhere.
      std::size_t lines = 1;
      for (const char c : text) lines += c == '\n';
      if (line < 1 || static_cast<std::size_t>(line) > lines + 1) std::abort();
    }
  }
  return 0;
}
