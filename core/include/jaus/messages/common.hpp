// Shared vocabulary of the message descriptions.
#pragma once

#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "jaus/wire/message.hpp"

namespace jaus::msg {

using wire::Dialect;
using wire::Empty;
using wire::Message;

template <class... Ts>
struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);
};

inline constexpr double kPi = std::numbers::pi;

// Wire types by their RA names.
using Byte = wire::Int<std::uint8_t>;
using UShort = wire::Int<std::uint16_t>;
using UInt = wire::Int<std::uint32_t>;

// Frequently used scaled ranges.
inline constexpr wire::Scaled<std::int16_t> kAngleShort{-kPi, kPi};
inline constexpr wire::Scaled<std::int32_t> kAngleInt{-kPi, kPi};
inline constexpr wire::Scaled<std::int32_t> kLatitude{-90, 90};
inline constexpr wire::Scaled<std::int32_t> kLongitude{-180, 180};
inline constexpr wire::Scaled<std::int32_t> kElevation{-10'000, 35'000};
inline constexpr wire::Scaled<std::int32_t> kLocalXY{-100'000, 100'000};
inline constexpr wire::Scaled<std::uint16_t> kServiceRate{0, 1092};  // Hz

// Manipulator quantities: the openjaus dialect sends these signed values as
// unsigned with bias = lower limit (jaus-wire-notes.md, Interoperability).
constexpr wire::Scaled<std::int32_t> manipulator_int(double lower, double upper) {
  return {lower, upper, wire::Quirk::openjaus_unsigned_bias};
}
constexpr wire::Scaled<std::int16_t> manipulator_short(double lower, double upper) {
  return {lower, upper, wire::Quirk::openjaus_unsigned_bias};
}

}  // namespace jaus::msg
