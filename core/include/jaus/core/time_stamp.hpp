// RA time stamp (u32) and date stamp (u16), docs/wire-format.md. Both are kept
// as their parts; decoding never rejects odd values (peers send them), encoding
// rejects parts that do not fit their bits.
#pragma once

#include <cstdint>
#include <optional>

namespace jaus {

struct TimeStamp {
  std::uint16_t millisecond = 0;  // bits 0-9, 0-999
  std::uint8_t second = 0;        // bits 10-15, 0-59
  std::uint8_t minute = 0;        // bits 16-21, 0-59
  std::uint8_t hour = 0;          // bits 22-26, 0-23
  std::uint8_t day = 1;           // bits 27-31, 1-31

  bool operator==(const TimeStamp&) const = default;

  static TimeStamp unpack(std::uint32_t raw) {
    return TimeStamp{static_cast<std::uint16_t>(raw & 0x3FF), static_cast<std::uint8_t>((raw >> 10) & 0x3F),
                     static_cast<std::uint8_t>((raw >> 16) & 0x3F), static_cast<std::uint8_t>((raw >> 22) & 0x1F),
                     static_cast<std::uint8_t>((raw >> 27) & 0x1F)};
  }
  // Empty when a part does not fit its bits.
  std::optional<std::uint32_t> pack() const {
    if (millisecond > 0x3FF || second > 0x3F || minute > 0x3F || hour > 0x1F || day > 0x1F) return std::nullopt;
    return static_cast<std::uint32_t>(millisecond) | (static_cast<std::uint32_t>(second) << 10) |
           (static_cast<std::uint32_t>(minute) << 16) | (static_cast<std::uint32_t>(hour) << 22) |
           (static_cast<std::uint32_t>(day) << 27);
  }
};

struct DateStamp {
  std::uint8_t day = 1;      // bits 0-4, 1-31
  std::uint8_t month = 1;    // bits 5-8, 1-12
  std::uint16_t year = 2000; // bits 9-15, years since 2000 (2000-2127)

  bool operator==(const DateStamp&) const = default;

  static DateStamp unpack(std::uint16_t raw) {
    return DateStamp{static_cast<std::uint8_t>(raw & 0x1F), static_cast<std::uint8_t>((raw >> 5) & 0x0F),
                     static_cast<std::uint16_t>(2000 + ((raw >> 9) & 0x7F))};
  }
  std::optional<std::uint16_t> pack() const {
    if (day > 0x1F || month > 0x0F || year < 2000 || year > 2127) return std::nullopt;
    return static_cast<std::uint16_t>(day | (month << 5) | ((year - 2000) << 9));
  }
};

}  // namespace jaus
