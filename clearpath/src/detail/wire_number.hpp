// Engineering value <-> fixed-point wire integer. raw = value * scale,
// rounded to nearest (the reference clients truncate; the settled choice is
// rounding, identical on every exactly representable value).
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

namespace jaus::clearpath::detail {

template <class Wire, class T>
std::optional<Wire> to_wire(T value, double scale) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return std::nullopt;
    const double raw = std::round(static_cast<double>(value) * scale);
    if (raw < static_cast<double>(std::numeric_limits<Wire>::min()) ||
        raw > static_cast<double>(std::numeric_limits<Wire>::max()))
      return std::nullopt;
    return static_cast<Wire>(raw);
  } else {
    if (!std::in_range<Wire>(value)) return std::nullopt;
    return static_cast<Wire>(value);
  }
}

template <class T, class Wire>
T from_wire(Wire raw, double scale) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(static_cast<double>(raw) / scale);
  } else {
    return static_cast<T>(raw);
  }
}

// Is value inside [min, max]? Scaled values get half a wire step of slack so
// that a value rounded to the wire grid at a limit (pi) stays in range.
template <class T>
bool within(T value, double scale, double min, double max) {
  const double v = static_cast<double>(value);
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return false;
    const double slack = 0.5 / scale;
    return v >= min - slack && v <= max + slack;
  } else {
    return v >= min && v <= max;
  }
}

}  // namespace jaus::clearpath::detail
