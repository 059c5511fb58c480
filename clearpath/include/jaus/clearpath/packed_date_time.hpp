// The protocol's date and time to the minute in a u32 (0x8003 Firmware Info,
// "write time"): minute bits 0-5 (0-59), hour 6-10 (0-23), day 11-16 (1-31),
// month 17-20 (1-12), year - 2000 21-27 (2000-2127); bits 28-31 unused (0).
// Shown as "YYYY-MM-DDTHH:MM" (ISO 8601, what people read and type, and it
// sorts); a value whose parts are out of range has no such form.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace jaus::clearpath {

struct DateTimeParts {
  int year = 2000;  // 2000-2127
  int month = 1;    // 1-12
  int day = 1;      // 1-31
  int hour = 0;     // 0-23
  int minute = 0;   // 0-59
  bool operator==(const DateTimeParts&) const = default;
};

constexpr bool valid(const DateTimeParts& p) {
  return p.year >= 2000 && p.year <= 2127 && p.month >= 1 && p.month <= 12 && p.day >= 1 && p.day <= 31 &&
         p.hour >= 0 && p.hour <= 23 && p.minute >= 0 && p.minute <= 59;
}

constexpr std::optional<std::uint32_t> pack_date_time(const DateTimeParts& p) {
  if (!valid(p)) return std::nullopt;
  return static_cast<std::uint32_t>(p.minute) | static_cast<std::uint32_t>(p.hour) << 6 |
         static_cast<std::uint32_t>(p.day) << 11 | static_cast<std::uint32_t>(p.month) << 17 |
         static_cast<std::uint32_t>(p.year - 2000) << 21;
}

// The parts of a packed value, or nothing when a part is out of range or an
// unused bit is set.
constexpr std::optional<DateTimeParts> unpack_date_time(std::uint32_t raw) {
  const DateTimeParts p{2000 + static_cast<int>((raw >> 21) & 0x7F), static_cast<int>((raw >> 17) & 0xF),
                        static_cast<int>((raw >> 11) & 0x3F), static_cast<int>((raw >> 6) & 0x1F),
                        static_cast<int>(raw & 0x3F)};
  if ((raw >> 28) != 0 || !valid(p)) return std::nullopt;
  return p;
}

// "2024-03-05T14:07".
inline std::string format_date_time(const DateTimeParts& p) {
  char text[24];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d", p.year, p.month, p.day, p.hour, p.minute);
  return text;
}

// Exactly "YYYY-MM-DDTHH:MM" with parts in range; nothing otherwise.
inline std::optional<DateTimeParts> parse_date_time(std::string_view text) {
  if (text.size() != 16 || text[4] != '-' || text[7] != '-' || text[10] != 'T' || text[13] != ':') return std::nullopt;
  const auto number = [&](std::size_t at, std::size_t digits, int& out) {
    out = 0;
    for (std::size_t i = at; i < at + digits; ++i) {
      if (text[i] < '0' || text[i] > '9') return false;
      out = out * 10 + (text[i] - '0');
    }
    return true;
  };
  DateTimeParts p;
  if (!number(0, 4, p.year) || !number(5, 2, p.month) || !number(8, 2, p.day) || !number(11, 2, p.hour) ||
      !number(14, 2, p.minute) || !valid(p))
    return std::nullopt;
  return p;
}

}  // namespace jaus::clearpath
