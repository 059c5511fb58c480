#include "jaus/bridge/frame_conventions.hpp"

#include <cmath>
#include <numbers>

namespace jaus::bridge {

double wrap_angle(double radians) {
  if (!std::isfinite(radians)) return radians;  // NaN stays NaN: the encoder refuses it, loudly
  double wrapped = std::remainder(radians, 2 * std::numbers::pi);  // in [-pi, pi]
  if (wrapped <= -std::numbers::pi) wrapped += 2 * std::numbers::pi;
  return wrapped;
}

Vector3 flu_to_frd(const Vector3& v) { return {v.x, -v.y, -v.z}; }
Vector3 frd_to_flu(const Vector3& v) { return {v.x, -v.y, -v.z}; }

EulerAngles flu_to_frd(const EulerAngles& a) { return {a.roll, -a.pitch, wrap_angle(-a.yaw)}; }
EulerAngles frd_to_flu(const EulerAngles& a) { return {a.roll, -a.pitch, wrap_angle(-a.yaw)}; }

double enu_yaw_to_ned_heading(double yaw) { return wrap_angle(std::numbers::pi / 2 - yaw); }
double ned_heading_to_enu_yaw(double heading) { return wrap_angle(std::numbers::pi / 2 - heading); }

}  // namespace jaus::bridge
