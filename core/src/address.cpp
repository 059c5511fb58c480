#include "jaus/core/address.hpp"

#include <charconv>

namespace jaus {

namespace {
bool level_matches(std::uint8_t pattern, std::uint8_t id) { return pattern == Address::kBroadcast || pattern == id; }
}  // namespace

bool Address::matches(const Address& target) const {
  return level_matches(subsystem, target.subsystem) && level_matches(node, target.node) &&
         level_matches(component, target.component) && level_matches(instance, target.instance);
}

std::string Address::to_string() const {
  return std::to_string(subsystem) + "." + std::to_string(node) + "." + std::to_string(component) + "." +
         std::to_string(instance);
}

std::optional<Address> Address::parse(std::string_view s) {
  std::uint8_t parts[4];
  const char* p = s.data();
  const char* end = s.data() + s.size();
  for (int i = 0; i < 4; ++i) {
    unsigned value = 0;
    auto [next, ec] = std::from_chars(p, end, value);
    if (ec != std::errc{} || next == p || value > 255) return std::nullopt;
    parts[i] = static_cast<std::uint8_t>(value);
    p = next;
    if (i < 3) {
      if (p == end || *p != '.') return std::nullopt;
      ++p;
    }
  }
  if (p != end) return std::nullopt;
  return Address{parts[0], parts[1], parts[2], parts[3]};
}

}  // namespace jaus
