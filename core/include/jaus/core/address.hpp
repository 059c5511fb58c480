// A JAUS address: subsystem.node.component.instance. 0 is invalid, 255 means
// broadcast at that level.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace jaus {

struct Address {
  std::uint8_t subsystem = 0;
  std::uint8_t node = 0;
  std::uint8_t component = 0;
  std::uint8_t instance = 0;

  static constexpr std::uint8_t kBroadcast = 255;

  bool operator==(const Address&) const = default;
  auto operator<=>(const Address&) const = default;

  bool is_valid() const { return subsystem != 0 && node != 0 && component != 0 && instance != 0; }
  bool is_broadcast() const {
    return subsystem == kBroadcast || node == kBroadcast || component == kBroadcast || instance == kBroadcast;
  }
  // True when a message sent to *this should reach `target` (255 matches any ID at that level).
  bool matches(const Address& target) const;
  // True when `other` is *this or lies under it: octets of 0 from some level
  // down name everything below (5.2.0.0 is node 2 of subsystem 5 and all its
  // components, as the liveness table keys nodes and subsystems).
  bool covers(const Address& other) const {
    const std::uint8_t mine[] = {subsystem, node, component, instance};
    const std::uint8_t theirs[] = {other.subsystem, other.node, other.component, other.instance};
    for (int level = 0; level < 4; ++level) {
      if (mine[level] == 0) return true;
      if (mine[level] != theirs[level]) return false;
    }
    return true;
  }

  std::string to_string() const;                            // "1.1.33.1"
  static std::optional<Address> parse(std::string_view s);  // accepts "S.N.C.I"
};

}  // namespace jaus
