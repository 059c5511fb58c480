// Requests (host -> platform, 0x4000-0x7FFF) of the Clearpath protocol
// document. Each carries a subscription: 0 = one immediate reply, 0xFFFF =
// cancel, N = N Hz. The reply is the data message of type request + 0x4000.
#pragma once

#include <cstdint>
#include <string_view>

#include "jaus/clearpath/fields.hpp"

namespace jaus::clearpath {

inline constexpr std::uint16_t kReplyOnce = 0;
inline constexpr std::uint16_t kCancelSubscription = 0xFFFF;

template <std::uint16_t Type>
struct Request {
  static constexpr std::uint16_t kType = Type;
  std::uint16_t subscription = kReplyOnce;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint16_t>("subscription", s.subscription)); }
  bool operator==(const Request&) const = default;
};

struct RequestEcho : Request<0x4000> { static constexpr std::string_view kName = "request_echo"; };
struct RequestPlatformInfo : Request<0x4001> { static constexpr std::string_view kName = "request_platform_info"; };
struct RequestPlatformName : Request<0x4002> { static constexpr std::string_view kName = "request_platform_name"; };
struct RequestFirmwareInfo : Request<0x4003> { static constexpr std::string_view kName = "request_firmware_info"; };
struct RequestSystemStatus : Request<0x4004> { static constexpr std::string_view kName = "request_system_status"; };
struct RequestPowerStatus : Request<0x4005> { static constexpr std::string_view kName = "request_power_status"; };
struct RequestProcessorStatus : Request<0x4006> { static constexpr std::string_view kName = "request_processor_status"; };
struct RequestSafetyStatus : Request<0x4010> { static constexpr std::string_view kName = "request_safety_status"; };
struct RequestDifferentialSpeeds : Request<0x4200> { static constexpr std::string_view kName = "request_differential_speeds"; };
struct RequestDifferentialControl : Request<0x4201> { static constexpr std::string_view kName = "request_differential_control"; };
struct RequestDifferentialOutput : Request<0x4202> { static constexpr std::string_view kName = "request_differential_output"; };
struct RequestAckermannOutput : Request<0x4203> { static constexpr std::string_view kName = "request_ackermann_output"; };
struct RequestVelocity : Request<0x4204> { static constexpr std::string_view kName = "request_velocity"; };
struct RequestTurn : Request<0x4205> { static constexpr std::string_view kName = "request_turn"; };
struct RequestAckermannControl : Request<0x4206> { static constexpr std::string_view kName = "request_ackermann_control"; };
struct RequestMaxSpeed : Request<0x4210> { static constexpr std::string_view kName = "request_max_speed"; };
struct RequestMaxAccel : Request<0x4211> { static constexpr std::string_view kName = "request_max_accel"; };
struct RequestGear : Request<0x4212> { static constexpr std::string_view kName = "request_gear"; };
struct RequestAnalogOutputs : Request<0x4300> { static constexpr std::string_view kName = "request_analog_outputs"; };
struct RequestGpio : Request<0x4301> { static constexpr std::string_view kName = "request_gpio"; };
struct RequestAnalogInputs : Request<0x4303> { static constexpr std::string_view kName = "request_analog_inputs"; };
struct RequestRangefinders : Request<0x4500> { static constexpr std::string_view kName = "request_rangefinders"; };
struct RequestRangefinderTiming : Request<0x4501> { static constexpr std::string_view kName = "request_rangefinder_timing"; };
struct RequestOrientation : Request<0x4600> { static constexpr std::string_view kName = "request_orientation"; };
struct RequestRotationalRates : Request<0x4601> { static constexpr std::string_view kName = "request_rotational_rates"; };
struct RequestAcceleration : Request<0x4602> { static constexpr std::string_view kName = "request_acceleration"; };
struct RequestSixAxis : Request<0x4603> { static constexpr std::string_view kName = "request_six_axis"; };
struct RequestSixAxisOrientation : Request<0x4604> { static constexpr std::string_view kName = "request_six_axis_orientation"; };
struct RequestMagnetometer : Request<0x4606> { static constexpr std::string_view kName = "request_magnetometer"; };
struct RequestEncoders : Request<0x4800> { static constexpr std::string_view kName = "request_encoders"; };
struct RequestRawEncoders : Request<0x4801> { static constexpr std::string_view kName = "request_raw_encoders"; };
struct RequestEncoderConfig : Request<0x4802> { static constexpr std::string_view kName = "request_encoder_config"; };
struct RequestAbsoluteJoints : Request<0x5010> { static constexpr std::string_view kName = "request_absolute_joints"; };
struct RequestRelativeJoints : Request<0x5011> { static constexpr std::string_view kName = "request_relative_joints"; };
struct RequestJointHoming : Request<0x5013> { static constexpr std::string_view kName = "request_joint_homing"; };
struct RequestJointTorques : Request<0x5014> { static constexpr std::string_view kName = "request_joint_torques"; };
struct RequestEndEffectorPosition : Request<0x5020> { static constexpr std::string_view kName = "request_end_effector_position"; };
struct RequestEndEffectorPoseSetpoint : Request<0x5021> { static constexpr std::string_view kName = "request_end_effector_pose_setpoint"; };
struct RequestEndEffectorPose : Request<0x5022> { static constexpr std::string_view kName = "request_end_effector_pose"; };

// The two requests that name what they ask about in one byte after the subscription.
struct RequestPanTiltZoom {
  static constexpr std::uint16_t kType = 0x4400;
  static constexpr std::string_view kName = "request_pan_tilt_zoom";
  std::uint16_t subscription = kReplyOnce;
  std::uint8_t mount = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint16_t>("subscription", s.subscription));
    v(integer<std::uint8_t>("mount", s.mount));
  }
  bool operator==(const RequestPanTiltZoom&) const = default;
};

struct RequestJointControl {
  static constexpr std::uint16_t kType = 0x5012;
  static constexpr std::string_view kName = "request_joint_control";
  std::uint16_t subscription = kReplyOnce;
  std::uint8_t joint = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint16_t>("subscription", s.subscription));
    v(integer<std::uint8_t>("joint", s.joint));
  }
  bool operator==(const RequestJointControl&) const = default;
};

}  // namespace jaus::clearpath
