#include "jaus/components/navigation_frames.hpp"

#include <cmath>
#include <numbers>

namespace jaus::components {

double wrap_angle(double radians) {
  if (!std::isfinite(radians)) return radians;  // NaN stays NaN: the encoder refuses it, loudly
  double wrapped = std::remainder(radians, 2 * std::numbers::pi);  // in [-pi, pi]
  if (wrapped <= -std::numbers::pi) wrapped += 2 * std::numbers::pi;
  return wrapped;
}

double enu_yaw_to_ned_heading(double yaw) { return wrap_angle(std::numbers::pi / 2 - yaw); }
double ned_heading_to_enu_yaw(double heading) { return wrap_angle(std::numbers::pi / 2 - heading); }

Vector3 enu_to_ned(const Vector3& v) { return {v.y, v.x, -v.z}; }
Vector3 ned_to_enu(const Vector3& v) { return {v.y, v.x, -v.z}; }

}  // namespace jaus::components
