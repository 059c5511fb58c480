// Scaled integers (docs/wire-format.md): a real value in [lower, upper] sent as
// an n-bit integer.
//   unsigned: scale = (upper - lower) / (2^n - 1), bias = lower
//   signed:   scale = (upper - lower) / (2^n - 2), bias = (upper + lower) / 2
//   encode: clamp to [lower, upper], integer = round((v - bias) / scale)
//   decode: v = integer * scale + bias
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace jaus {

template <std::integral I>
struct ScaledRange {
  static_assert(sizeof(I) <= 4, "scaled integers are at most 32 bits wide");
  double lower = 0;
  double upper = 0;
  // Interoperability knobs for the common RA 3.3 peer (docs/wire-format.md):
  // it divides 32-bit unsigned ranges into 2^32 - 2 steps, and rounds with
  // (int)(x + 0.5), one step high for negative values.
  bool peer_steps = false;
  bool peer_rounding = false;

  constexpr double steps() const {
    constexpr double full = static_cast<double>(std::numeric_limits<std::make_unsigned_t<I>>::max());
    if (std::is_signed_v<I> || (peer_steps && sizeof(I) == 4)) return full - 1.0;
    return full;
  }
  constexpr double scale() const { return (upper - lower) / steps(); }
  constexpr double bias() const { return std::is_signed_v<I> ? (upper + lower) / 2.0 : lower; }

  // Round half away from zero; |x| stays below 2^33 after clamping, so the
  // 64-bit truncation is exact and cheaper than std::round.
  static constexpr double round_half_away(double x) {
    return static_cast<double>(static_cast<std::int64_t>(x + (x >= 0 ? 0.5 : -0.5)));
  }

  [[gnu::always_inline]] I encode(double value) const {
    // Clamp first (NaN becomes the lower limit); a clamped value lands within
    // the integer range after rounding, so the result needs no second clamp.
    value = std::min(upper, std::max(lower, value));
    // Multiplying by the constant steps-per-unit (folded at compile time)
    // instead of dividing by the scale keeps the encoder free of divisions.
    const double exact = (value - bias()) * (steps() / (upper - lower));
    // round_half_away without its branch: copysign is a bit operation, and
    // adding +-0.5 then truncating gives the same integer for every value
    // (-0.0 gets -0.5 instead of +0.5; both truncate to 0). The peer rounds
    // with (int)(x + 0.5). The integer fits I, so no double -> I conversion
    // (undefined out of range) is needed, only an integer narrowing.
    const double half = peer_rounding ? 0.5 : std::copysign(0.5, exact);
    return static_cast<I>(static_cast<std::int64_t>(exact + half));
  }

  [[gnu::always_inline]] constexpr double decode(I raw) const {
    // The one signed value below -(2^(n-1) - 1) is outside the encoding; read it as the lower limit.
    if constexpr (std::is_signed_v<I>) {
      if (raw == std::numeric_limits<I>::min()) return lower;
    }
    return static_cast<double>(raw) * scale() + bias();
  }
};

}  // namespace jaus
