// Where JSS and RA 3.x scale the same quantity differently (docs/jss.md,
// "Scaling"; part of the translator kit, translator_kit.hpp). Every scaled
// field is a double in engineering units on both sides (the codecs decode
// and encode), so a translator only has to keep each value inside the range
// of the side it goes to, and give JSS's symmetric ranges the exact zero
// they lack: JSS's unsigned encoding of [-a, a] has no integer
// for 0 (0 % effort is 32767.5; JTS truncates to 32767, we round to 32768),
// so a value within one JSS step of 0 is 0 when it goes to RA.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace jaus::jss_face::scaling {

inline constexpr double kPi = 3.14159265358979323846;

// One step of a JSS unsigned n-bit field over [lo, hi].
constexpr double jss_step(double lo, double hi, int bits) {
  return (hi - lo) / (static_cast<double>((std::uint64_t{1} << bits) - 1));
}

// The JSS ranges (docs/jss-messages.md) and their steps.
inline constexpr double kEffortPercent = 100;      // U16[-100..100 %]
inline constexpr double kEffortStep = jss_step(-100, 100, 16);
inline constexpr double kAngleStep = jss_step(-kPi, kPi, 16);  // U16[-pi..pi rad]
inline constexpr double kLocalXyzM = 100'000;     // U32[-100000..100000 m]
inline constexpr double kLocalXyzStep = jss_step(-kLocalXyzM, kLocalXyzM, 32);
inline constexpr double kMaxTravelSpeedMps = 327.67;  // U16[0..327.67 m/s]
inline constexpr double kMaxWaypointToleranceM = 100;     // U16[0..100 m]
inline constexpr double kMaxPathToleranceM = 100'000;     // U32[0..100000 m]

// The RA ranges that are narrower than JSS's (the rest hold every JSS value).
inline constexpr double kRaMinElevationM = -10'000;   // RA local Z / elevation
inline constexpr double kRaMaxElevationM = 35'000;
inline constexpr double kRaMaxVelocityMps = 65.534;   // RA Report Velocity State
inline constexpr double kRaMaxTravelSpeedMps = 10'000;

// A value decoded from a JSS symmetric range [-a, a] with step `step`: within
// one step of 0 it is exactly 0 (so "stop" from any JSS encoder is RA's 0).
inline double exact_zero(double value, double step) { return std::abs(value) <= step ? 0.0 : value; }
inline std::optional<double> exact_zero(const std::optional<double>& value, double step) {
  if (!value) return std::nullopt;
  return exact_zero(*value, step);
}

// Into [lo, hi]; NaN (never produced by a decoder) becomes lo.
inline double clamp(double value, double lo, double hi) {
  if (std::isnan(value)) return lo;
  return std::min(hi, std::max(lo, value));
}
inline std::optional<double> clamp(const std::optional<double>& value, double lo, double hi) {
  if (!value) return std::nullopt;
  return clamp(*value, lo, hi);
}

// A JSS effort percentage (propulsive) as RA takes it.
inline std::optional<double> effort_to_ra(const std::optional<double>& jss_percent) {
  return clamp(exact_zero(jss_percent, kEffortStep), -kEffortPercent, kEffortPercent);
}
// A JSS local coordinate (X, Y) as RA takes it (same range).
inline double local_xy_to_ra(double jss_m) { return exact_zero(jss_m, kLocalXyzStep); }
// JSS local Z (+-100 km) into RA's elevation range (-10 km..35 km).
inline std::optional<double> local_z_to_ra(const std::optional<double>& jss_m) {
  return clamp(exact_zero(jss_m, kLocalXyzStep), kRaMinElevationM, kRaMaxElevationM);
}
inline std::optional<double> angle_to_ra(const std::optional<double>& jss_rad) {
  return exact_zero(jss_rad, kAngleStep);
}
// Travel speed: JSS 0..327.67 m/s, RA 0..10000 m/s (RA step 0.153 m/s).
inline double travel_speed_to_ra(double jss_mps) { return clamp(jss_mps, 0, kMaxTravelSpeedMps); }
inline double travel_speed_to_jss(double ra_mps) { return clamp(ra_mps, 0, kMaxTravelSpeedMps); }

}  // namespace jaus::jss_face::scaling
