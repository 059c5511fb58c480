#include "jaus/jss/jss_id.hpp"

#include <charconv>

namespace jaus::jss {

std::optional<JssId> JssId::parse(std::string_view text) {
  unsigned parts[3] = {0, 0, 0};
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    if (i > 0) {
      if (p == end || *p != '.') return std::nullopt;
      ++p;
    }
    const auto [next, ec] = std::from_chars(p, end, parts[i]);
    if (ec != std::errc{} || next == p) return std::nullopt;
    p = next;
  }
  if (p != end || parts[0] > 65535 || parts[1] > 255 || parts[2] > 255) return std::nullopt;
  return JssId{static_cast<std::uint16_t>(parts[0]), static_cast<std::uint8_t>(parts[1]),
               static_cast<std::uint8_t>(parts[2])};
}

}  // namespace jaus::jss
