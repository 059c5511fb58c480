// Commands (host -> platform, 0x0001-0x3FFF) of the Clearpath protocol
// document, each described once.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/message_layouts.hpp"

namespace jaus::clearpath {

struct SetPlatformName {
  static constexpr std::uint16_t kType = 0x0002;
  static constexpr std::string_view kName = "set_platform_name";
  std::string name;
  bool nul_terminated = false;  // one reference client appends and counts a NUL
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::text("name", s.name, 64, s.nul_terminated)); }
  bool operator==(const SetPlatformName&) const = default;
};

struct SetPlatformTime {
  static constexpr std::uint16_t kType = 0x0005;
  static constexpr std::string_view kName = "set_platform_time";
  std::uint32_t time_ms = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint32_t>("time_ms", s.time_ms)); }
  bool operator==(const SetPlatformTime&) const = default;
};

struct SetSafetySystem {
  static constexpr std::uint16_t kType = 0x0010;
  static constexpr std::string_view kName = "set_safety_system";
  std::uint16_t flags = 0;  // platform specific (Husky: 0x08 emergency stop, 0x10 pause...)
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint16_t>("flags", s.flags)); }
  bool operator==(const SetSafetySystem&) const = default;
};

struct SetDifferentialSpeeds : DifferentialSpeedsLayout {
  static constexpr std::uint16_t kType = 0x0200;
  static constexpr std::string_view kName = "set_differential_speeds";
  bool operator==(const SetDifferentialSpeeds&) const = default;
};

struct SetDifferentialControl : DifferentialControlLayout {
  static constexpr std::uint16_t kType = 0x0201;
  static constexpr std::string_view kName = "set_differential_control";
  bool operator==(const SetDifferentialControl&) const = default;
};

struct SetDifferentialOutput : DifferentialOutputLayout {
  static constexpr std::uint16_t kType = 0x0202;
  static constexpr std::string_view kName = "set_differential_output";
  bool operator==(const SetDifferentialOutput&) const = default;
};

struct SetAckermannOutput : AckermannOutputLayout {
  static constexpr std::uint16_t kType = 0x0203;
  static constexpr std::string_view kName = "set_ackermann_output";
  bool operator==(const SetAckermannOutput&) const = default;
};

struct SetVelocity : VelocityLayout {
  static constexpr std::uint16_t kType = 0x0204;
  static constexpr std::string_view kName = "set_velocity";
  bool operator==(const SetVelocity&) const = default;
};

struct SetTurn : TurnLayout {
  static constexpr std::uint16_t kType = 0x0205;
  static constexpr std::string_view kName = "set_turn";
  bool operator==(const SetTurn&) const = default;
};

struct SetAckermannControl : AckermannControlLayout {
  static constexpr std::uint16_t kType = 0x0206;
  static constexpr std::string_view kName = "set_ackermann_control";
  bool operator==(const SetAckermannControl&) const = default;
};

struct SetMaxSpeed : ForwardReverseLayout {
  static constexpr std::uint16_t kType = 0x0210;
  static constexpr std::string_view kName = "set_max_speed";
  bool operator==(const SetMaxSpeed&) const = default;
};

struct SetMaxAccel : ForwardReverseLayout {
  static constexpr std::uint16_t kType = 0x0211;
  static constexpr std::string_view kName = "set_max_accel";
  bool operator==(const SetMaxAccel&) const = default;
};

// The document sends one signed byte. Clearpath's Python client sends
// [flags, gear] (the 0x8212 layout); both are accepted, and a decoded
// two-byte command keeps its form so it re-encodes byte for byte.
struct ChangeGear {
  static constexpr std::uint16_t kType = 0x0212;
  static constexpr std::string_view kName = "change_gear";
  bool with_flags = false;
  std::uint8_t flags = 0;
  std::int8_t gear = 0;  // 0 neutral, -1 park, >0 forward, < -1 reverse
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(flag("with_flags", s.with_flags));
    if (s.with_flags) v(integer<std::uint8_t>("flags", s.flags));
    v(enumerated<std::int8_t>("gear", s.gear, kGearNames));
  }
  static void prepare_decode(ChangeGear& m, std::size_t payload_size) { m.with_flags = payload_size == 2; }
  bool operator==(const ChangeGear&) const = default;
};

struct SetAnalogOutputs {
  static constexpr std::uint16_t kType = 0x0300;
  static constexpr std::string_view kName = "set_analog_outputs";
  std::vector<AnalogOutputChannel> channels;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("channels", s.channels, Count::prefixed, Layout::rows));
  }
  bool operator==(const SetAnalogOutputs&) const = default;
};

struct SetGpioDirection {
  static constexpr std::uint16_t kType = 0x0301;
  static constexpr std::string_view kName = "set_gpio_direction";
  std::uint32_t mask = 0;
  std::uint32_t direction = 0;  // 1 = output
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint32_t>("mask", s.mask));
    v(integer<std::uint32_t>("direction", s.direction));
  }
  bool operator==(const SetGpioDirection&) const = default;
};

struct SetGpioOutput {
  static constexpr std::uint16_t kType = 0x0302;
  static constexpr std::string_view kName = "set_gpio_output";
  std::uint32_t mask = 0;
  std::uint32_t value = 0;  // 1 = high
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint32_t>("mask", s.mask));
    v(integer<std::uint32_t>("value", s.value));
  }
  bool operator==(const SetGpioOutput&) const = default;
};

struct SetPanTiltZoom : PanTiltZoomLayout {
  static constexpr std::uint16_t kType = 0x0400;
  static constexpr std::string_view kName = "set_pan_tilt_zoom";
  bool operator==(const SetPanTiltZoom&) const = default;
};

// No count byte: the number of encoders follows from the payload length.
struct ConfigureEncoders {
  static constexpr std::uint16_t kType = 0x0802;
  static constexpr std::string_view kName = "configure_encoders";
  std::vector<EncoderSetting> encoders;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("encoders", s.encoders, Count::implied, Layout::rows));
  }
  bool operator==(const ConfigureEncoders&) const = default;
};

struct SetAbsoluteJoints {
  static constexpr std::uint16_t kType = 0x1010;
  static constexpr std::string_view kName = "set_absolute_joints";
  std::vector<AbsoluteJointTarget> joints;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("joints", s.joints, Count::prefixed, Layout::rows));
  }
  bool operator==(const SetAbsoluteJoints&) const = default;
};

struct SetRelativeJoints {
  static constexpr std::uint16_t kType = 0x1011;
  static constexpr std::string_view kName = "set_relative_joints";
  std::vector<RelativeJointTarget> joints;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("joints", s.joints, Count::prefixed, Layout::rows));
  }
  bool operator==(const SetRelativeJoints&) const = default;
};

struct SetJointControl : JointControlLayout {
  static constexpr std::uint16_t kType = 0x1012;
  static constexpr std::string_view kName = "set_joint_control";
  bool operator==(const SetJointControl&) const = default;
};

struct HomeJoint {
  static constexpr std::uint16_t kType = 0x1013;
  static constexpr std::string_view kName = "home_joint";
  std::uint8_t joint = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint8_t>("joint", s.joint)); }
  bool operator==(const HomeJoint&) const = default;
};

struct SetEndEffectorPosition : PositionLayout {
  static constexpr std::uint16_t kType = 0x1020;
  static constexpr std::string_view kName = "set_end_effector_position";
  bool operator==(const SetEndEffectorPosition&) const = default;
};

struct SetEndEffectorPose : PoseLayout {
  static constexpr std::uint16_t kType = 0x1021;
  static constexpr std::string_view kName = "set_end_effector_pose";
  bool operator==(const SetEndEffectorPose&) const = default;
};

struct ResetProcessor {
  static constexpr std::uint16_t kType = 0x2000;
  static constexpr std::string_view kName = "reset_processor";
  std::uint16_t passcode = kSystemPasscode;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    v(fields::integer<std::uint16_t>("passcode", s.passcode, kSystemPasscode, kSystemPasscode));
  }
  bool operator==(const ResetProcessor&) const = default;
};

struct RestoreSettings {
  static constexpr std::uint16_t kType = 0x2001;
  static constexpr std::string_view kName = "restore_settings";
  static constexpr std::uint8_t kFromUserStorage = 1;
  static constexpr std::uint8_t kFactoryDefaults = 2;
  std::uint16_t passcode = kSystemPasscode;
  std::uint8_t source = kFromUserStorage;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint16_t>("passcode", s.passcode, kSystemPasscode, kSystemPasscode));
    v(integer<std::uint8_t>("source", s.source, 1, 2));
  }
  bool operator==(const RestoreSettings&) const = default;
};

struct StoreSettings {
  static constexpr std::uint16_t kType = 0x2002;
  static constexpr std::string_view kName = "store_settings";
  std::uint16_t passcode = kSystemPasscode;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    v(fields::integer<std::uint16_t>("passcode", s.passcode, kSystemPasscode, kSystemPasscode));
  }
  bool operator==(const StoreSettings&) const = default;
};

}  // namespace jaus::clearpath
