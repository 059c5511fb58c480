// A JSS (SAE JAUS, AS5669A) endpoint ID: 16-bit subsystem, 8-bit node and
// component, no instance (docs/jss.md, "The bytes on the wire"). 0 is invalid at every level;
// 65535 (subsystem) and 255 (node, component) mean "all".
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace jaus::jss {

struct JssId {
  std::uint16_t subsystem = 0;
  std::uint8_t node = 0;
  std::uint8_t component = 0;

  static constexpr std::uint16_t kAllSubsystems = 65535;
  static constexpr std::uint8_t kAll = 255;

  bool operator==(const JssId&) const = default;
  auto operator<=>(const JssId&) const = default;

  bool is_valid() const { return subsystem != 0 && node != 0 && component != 0; }
  bool is_broadcast() const { return subsystem == kAllSubsystems || node == kAll || component == kAll; }
  // A message sent to *this reaches `target` (wildcards match any ID at their level).
  bool matches(const JssId& target) const {
    return (subsystem == kAllSubsystems || subsystem == target.subsystem) && (node == kAll || node == target.node) &&
           (component == kAll || component == target.component);
  }
  // The header's u32: component in bits 0-7, node 8-15, subsystem 16-31.
  std::uint32_t packed() const {
    return static_cast<std::uint32_t>(component) | (static_cast<std::uint32_t>(node) << 8) |
           (static_cast<std::uint32_t>(subsystem) << 16);
  }
  static JssId unpack(std::uint32_t v) {
    return JssId{static_cast<std::uint16_t>(v >> 16), static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
  }
  std::string to_string() const {  // "42.1.1"
    return std::to_string(subsystem) + "." + std::to_string(node) + "." + std::to_string(component);
  }
  static std::optional<JssId> parse(std::string_view text);  // "S.N.C"
};

}  // namespace jaus::jss
