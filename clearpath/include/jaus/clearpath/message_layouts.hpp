// Payload layouts that a command and its data message share (a Set X command
// and the X data the platform reports). Messages derive from these and add
// their type code and name.
#pragma once

#include <cstdint>
#include <string>

#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/message_records.hpp"

namespace jaus::clearpath {

struct DifferentialSpeedsLayout {
  bool operator==(const DifferentialSpeedsLayout&) const = default;
  double left_speed = 0, right_speed = 0;  // m/s
  double left_accel = 0, right_accel = 0;  // m/s^2 (magnitude)
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("left_speed", s.left_speed, 100, -320, 320, "m/s"));
    v(scaled<std::int16_t>("right_speed", s.right_speed, 100, -320, 320, "m/s"));
    v(scaled<std::int16_t>("left_accel", s.left_accel, 100, 0, 320, "m/s^2"));
    v(scaled<std::int16_t>("right_accel", s.right_accel, 100, 0, 320, "m/s^2"));
  }
};

struct DifferentialControlLayout {
  bool operator==(const DifferentialControlLayout&) const = default;
  MotorControlConstants left, right;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    v(fields::group("left", s.left));
    v(fields::group("right", s.right));
  }
};

struct DifferentialOutputLayout {
  bool operator==(const DifferentialOutputLayout&) const = default;
  double left = 0, right = 0;  // % of maximum output
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("left", s.left, 100, -100, 100, "%"));
    v(scaled<std::int16_t>("right", s.right, 100, -100, 100, "%"));
  }
};

// Throttle is signed [-100, 100] in both directions: the data table's [0, 100]
// contradicts its own text (settled in the protocol notes).
struct AckermannOutputLayout {
  bool operator==(const AckermannOutputLayout&) const = default;
  double steering = 0;  // %, positive = left
  double throttle = 0;  // %
  double brake = 0;     // %
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("steering", s.steering, 100, -100, 100, "%"));
    v(scaled<std::int16_t>("throttle", s.throttle, 100, -100, 100, "%"));
    v(scaled<std::int16_t>("brake", s.brake, 100, 0, 100, "%"));
  }
};

struct VelocityLayout {
  bool operator==(const VelocityLayout&) const = default;
  double translational = 0;  // m/s
  double rotational = 0;     // rad/s, positive = left turn
  double acceleration = 0;   // m/s^2 (magnitude)
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("translational", s.translational, 100, -320, 320, "m/s"));
    v(scaled<std::int16_t>("rotational", s.rotational, 100, -320, 320, "rad/s"));
    v(scaled<std::int16_t>("acceleration", s.acceleration, 100, 0, 320, "m/s^2"));
  }
};

struct TurnLayout {
  bool operator==(const TurnLayout&) const = default;
  double translational = 0;  // m/s
  double radius = 0;         // m, positive = left turn
  double acceleration = 0;   // m/s^2
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("translational", s.translational, 100, -320, 320, "m/s"));
    v(scaled<std::int16_t>("radius", s.radius, 100, -320, 320, "m"));
    v(scaled<std::int16_t>("acceleration", s.acceleration, 100, 0, 320, "m/s^2"));
  }
};

struct AckermannControlLayout {
  bool operator==(const AckermannControlLayout&) const = default;
  MotorControlConstants speed, heading;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    v(fields::group("speed", s.speed));
    v(fields::group("heading", s.heading));
  }
};

struct ForwardReverseLayout {
  bool operator==(const ForwardReverseLayout&) const = default;
  double forward = 0, reverse = 0;  // m/s or m/s^2 (both non-negative)
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("forward", s.forward, 100, 0, 320, ""));
    v(scaled<std::int16_t>("reverse", s.reverse, 100, 0, 320, ""));
  }
};

struct PanTiltZoomLayout {
  bool operator==(const PanTiltZoomLayout&) const = default;
  std::uint8_t mount = 0;
  double pan = 0, tilt = 0;  // deg
  double zoom = 1;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("mount", s.mount));
    v(scaled<std::int16_t>("pan", s.pan, 100, -180, 180, "deg"));
    v(scaled<std::int16_t>("tilt", s.tilt, 100, -180, 180, "deg"));
    // Zoom 0 is allowed too: the document says to send 0 for a mount without zoom.
    v(scaled<std::int16_t>("zoom", s.zoom, 100, 0, 320, ""));
  }
};

struct JointControlLayout {
  bool operator==(const JointControlLayout&) const = default;
  std::uint8_t joint = 0;
  JointControlConstants constants;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("joint", s.joint));
    v(group("constants", s.constants));
  }
};

struct PositionLayout {
  bool operator==(const PositionLayout&) const = default;
  double x = 0, y = 0, z = 0;  // m
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("x", s.x, 1000, -32, 32, "m"));
    v(scaled<std::int16_t>("y", s.y, 1000, -32, 32, "m"));
    v(scaled<std::int16_t>("z", s.z, 1000, -32, 32, "m"));
  }
};

struct PoseLayout {
  bool operator==(const PoseLayout&) const = default;
  double x = 0, y = 0, z = 0;           // m
  double roll = 0, pitch = 0, yaw = 0;  // rad
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("x", s.x, 1000, -32, 32, "m"));
    v(scaled<std::int16_t>("y", s.y, 1000, -32, 32, "m"));
    v(scaled<std::int16_t>("z", s.z, 1000, -32, 32, "m"));
    v(scaled<std::int16_t>("roll", s.roll, 1000, -kPi, kPi, "rad"));
    v(scaled<std::int16_t>("pitch", s.pitch, 1000, -kPi, kPi, "rad"));
    v(scaled<std::int16_t>("yaw", s.yaw, 1000, -kPi, kPi, "rad"));
  }
};

// Reset / restore / store carry a fixed passcode so a stray frame cannot reset the platform.
inline constexpr std::uint16_t kSystemPasscode = 0x3A18;

}  // namespace jaus::clearpath
