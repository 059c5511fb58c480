// Records that several Clearpath messages share (control constants, list
// elements). Each is described once, like the messages that contain them.
#pragma once

#include <cstdint>
#include <string_view>

#include "jaus/clearpath/fields.hpp"

namespace jaus::clearpath {

namespace detail {
template <class Self, class V>
void describe_control_constants(Self& s, V& v, std::string_view output_unit) {
  using namespace fields;
  v(scaled<std::int16_t>("p", s.p, 100, -320, 320, ""));
  v(scaled<std::int16_t>("i", s.i, 100, -320, 320, ""));
  v(scaled<std::int16_t>("d", s.d, 100, -320, 320, ""));
  v(scaled<std::int16_t>("feed_forward", s.feed_forward, 100, -320, 320, ""));
  v(scaled<std::int16_t>("stiction", s.stiction, 100, 0, 100, output_unit));
  v(scaled<std::int16_t>("integral_limit", s.integral_limit, 100, 0, 100, output_unit));
}
}  // namespace detail

// Controller whose output is a percentage of the motor's nominal voltage.
struct MotorControlConstants {
  double p = 0, i = 0, d = 0, feed_forward = 0, stiction = 0, integral_limit = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_control_constants(s, v, "%"); }
  bool operator==(const MotorControlConstants&) const = default;
};

// Joint controller whose output is a torque.
struct JointControlConstants {
  double p = 0, i = 0, d = 0, feed_forward = 0, stiction = 0, integral_limit = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_control_constants(s, v, "N-m"); }
  bool operator==(const JointControlConstants&) const = default;
};

struct AnalogOutputChannel {
  std::uint8_t channel = 0;
  std::uint16_t value = 0;  // 0xFFFF = the channel's maximum voltage
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("channel", s.channel));
    v(integer<std::uint16_t>("value", s.value));
  }
  bool operator==(const AnalogOutputChannel&) const = default;
};

struct AbsoluteJointTarget {
  std::uint8_t joint = 0;
  double angle = 0;  // rad
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("joint", s.joint));
    v(scaled<std::int16_t>("angle", s.angle, 10000, -kPi, kPi, "rad"));
  }
  bool operator==(const AbsoluteJointTarget&) const = default;
};

struct RelativeJointTarget {
  std::uint8_t joint = 0;
  double angle = 0;  // rad, relative to the angle when the command arrives
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("joint", s.joint));
    v(scaled<std::int16_t>("angle", s.angle, 10000, -3.1416, 3.1416, "rad"));
  }
  bool operator==(const RelativeJointTarget&) const = default;
};

struct EncoderSetting {
  std::int16_t ppr = 0;  // pulses per revolution
  double scale = 0;      // m/rev or rev/rev
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::int16_t>("ppr", s.ppr, 0, 32000));
    v(scaled<std::int16_t>("scale", s.scale, 1000, -32, 32, "m/rev"));
  }
  bool operator==(const EncoderSetting&) const = default;
};

struct Battery {
  double charge = 0;           // %
  std::int16_t capacity = 0;   // W-h (litres for a gas engine)
  std::uint8_t description = 0;  // bit 7 present, bit 6 in use, bits 0-3 type
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("charge", s.charge, 100, 0, 100, "%"));
    v(integer<std::int16_t>("capacity", s.capacity, 0, 32000));
    v(integer<std::uint8_t>("description", s.description));
  }
  bool operator==(const Battery&) const = default;
};

struct TimedRange {
  double distance = 0;         // m
  std::uint32_t acquired = 0;  // ms, platform clock
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int16_t>("distance", s.distance, 1000, 0, 32, "m"));
    v(integer<std::uint32_t>("acquired", s.acquired));
  }
  bool operator==(const TimedRange&) const = default;
};

struct EncoderReading {
  double travel = 0;  // m since startup
  double speed = 0;   // m/s
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(scaled<std::int32_t>("travel", s.travel, 1000, -2e6, 2e6, "m"));
    v(scaled<std::int16_t>("speed", s.speed, 1000, -32, 32, "m/s"));
  }
  bool operator==(const EncoderReading&) const = default;
};

}  // namespace jaus::clearpath
