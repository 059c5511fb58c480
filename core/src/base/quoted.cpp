#include "jaus/base/quoted.hpp"

namespace jaus {

std::string quoted(std::string_view text) {
  constexpr std::size_t kMax = 60;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7F) out += '?';
    else out += static_cast<char>(c);
  }
  if (text.size() > kMax) out += "...";
  return out + "'";
}

}  // namespace jaus
