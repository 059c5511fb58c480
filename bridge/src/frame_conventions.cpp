#include "jaus/bridge/frame_conventions.hpp"

namespace jaus::bridge {

Vector3 flu_to_frd(const Vector3& v) { return {v.x, -v.y, -v.z}; }
Vector3 frd_to_flu(const Vector3& v) { return {v.x, -v.y, -v.z}; }

EulerAngles flu_to_frd(const EulerAngles& a) { return {a.roll, -a.pitch, wrap_angle(-a.yaw)}; }
EulerAngles frd_to_flu(const EulerAngles& a) { return {a.roll, -a.pitch, wrap_angle(-a.yaw)}; }

}  // namespace jaus::bridge
