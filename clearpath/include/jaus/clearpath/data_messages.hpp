// Data (platform -> host, 0x8000-0xBFFF) of the Clearpath protocol document,
// each described once. Yaw in 0x8600/0x8601 is left-handed (positive towards
// east / right turn) and in 0x8603/0x8604 right-handed: the numbers are kept
// as they are on the wire; conversion happens where JAUS values are made.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/message_layouts.hpp"

namespace jaus::clearpath {

struct EchoData {
  static constexpr std::uint16_t kType = 0x8000;
  static constexpr std::string_view kName = "echo";
  template <class Self, class V>
  static void describe(Self&, V&) {}
  bool operator==(const EchoData&) const = default;
};

struct PlatformInfo {
  static constexpr std::uint16_t kType = 0x8001;
  static constexpr std::string_view kName = "platform_info";
  std::string model;  // not NUL terminated
  std::uint8_t revision = 0;
  std::uint32_t serial = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(text("model", s.model, 238));
    v(integer<std::uint8_t>("revision", s.revision));
    v(integer<std::uint32_t>("serial", s.serial));
  }
  bool operator==(const PlatformInfo&) const = default;
};

struct PlatformName {
  static constexpr std::uint16_t kType = 0x8002;
  static constexpr std::string_view kName = "platform_name";
  std::string name;
  bool nul_terminated = false;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::text("name", s.name, 64, s.nul_terminated)); }
  bool operator==(const PlatformName&) const = default;
};

// write_time packs minute (bits 0-5), hour (6-10), day 1-31 (11-16),
// month 1-12 (17-20) and year - 2000 (21-27); see packed_date_time.hpp.
struct FirmwareInfo {
  static constexpr std::uint16_t kType = 0x8003;
  static constexpr std::string_view kName = "firmware_info";
  std::uint8_t firmware_major = 0, firmware_minor = 0;
  std::uint8_t protocol_major = 0, protocol_minor = 0;
  std::uint32_t write_time = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("firmware_major", s.firmware_major));
    v(integer<std::uint8_t>("firmware_minor", s.firmware_minor));
    v(integer<std::uint8_t>("protocol_major", s.protocol_major));
    v(integer<std::uint8_t>("protocol_minor", s.protocol_minor));
    v(packed_date_time("write_time", s.write_time));
  }
  bool operator==(const FirmwareInfo&) const = default;
};

// Size 7 + 2(V + I + T): the document's formula forgets the 4-byte uptime.
struct SystemStatus {
  static constexpr std::uint16_t kType = 0x8004;
  static constexpr std::string_view kName = "system_status";
  std::uint32_t uptime_ms = 0;
  std::vector<double> voltages, currents, temperatures;  // V, A, degC
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint32_t>("uptime_ms", s.uptime_ms));
    v(scaled_list<std::int16_t>("voltages", s.voltages, 100, -320, 320, "V"));
    v(scaled_list<std::int16_t>("currents", s.currents, 100, -320, 320, "A"));
    v(scaled_list<std::int16_t>("temperatures", s.temperatures, 100, -320, 320, "degC"));
  }
  bool operator==(const SystemStatus&) const = default;
};

struct PowerStatus {
  static constexpr std::uint16_t kType = 0x8005;
  static constexpr std::string_view kName = "power_status";
  std::vector<Battery> batteries;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("batteries", s.batteries, Count::prefixed, Layout::columns));
  }
  bool operator==(const PowerStatus&) const = default;
};

struct ProcessorStatus {
  static constexpr std::uint16_t kType = 0x8006;
  static constexpr std::string_view kName = "processor_status";
  std::vector<std::int16_t> errors;  // error count per process
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer_list<std::int16_t>("errors", s.errors, 0, 32000)); }
  bool operator==(const ProcessorStatus&) const = default;
};

struct SafetyStatus {
  static constexpr std::uint16_t kType = 0x8010;
  static constexpr std::string_view kName = "safety_status";
  std::uint16_t flags = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint16_t>("flags", s.flags)); }
  bool operator==(const SafetyStatus&) const = default;
};

struct DifferentialSpeedsData : DifferentialSpeedsLayout {
  static constexpr std::uint16_t kType = 0x8200;
  static constexpr std::string_view kName = "differential_speeds";
  bool operator==(const DifferentialSpeedsData&) const = default;
};
struct DifferentialControlData : DifferentialControlLayout {
  static constexpr std::uint16_t kType = 0x8201;
  static constexpr std::string_view kName = "differential_control";
  bool operator==(const DifferentialControlData&) const = default;
};
struct DifferentialOutputData : DifferentialOutputLayout {
  static constexpr std::uint16_t kType = 0x8202;
  static constexpr std::string_view kName = "differential_output";
  bool operator==(const DifferentialOutputData&) const = default;
};
struct AckermannOutputData : AckermannOutputLayout {
  static constexpr std::uint16_t kType = 0x8203;
  static constexpr std::string_view kName = "ackermann_output";
  bool operator==(const AckermannOutputData&) const = default;
};
struct VelocityData : VelocityLayout {
  static constexpr std::uint16_t kType = 0x8204;
  static constexpr std::string_view kName = "velocity";
  bool operator==(const VelocityData&) const = default;
};
struct TurnData : TurnLayout {
  static constexpr std::uint16_t kType = 0x8205;
  static constexpr std::string_view kName = "turn";
  bool operator==(const TurnData&) const = default;
};
struct AckermannControlData : AckermannControlLayout {
  static constexpr std::uint16_t kType = 0x8206;
  static constexpr std::string_view kName = "ackermann_control";
  bool operator==(const AckermannControlData&) const = default;
};
struct MaxSpeedData : ForwardReverseLayout {
  static constexpr std::uint16_t kType = 0x8210;
  static constexpr std::string_view kName = "max_speed";
  bool operator==(const MaxSpeedData&) const = default;
};
struct MaxAccelData : ForwardReverseLayout {
  static constexpr std::uint16_t kType = 0x8211;
  static constexpr std::string_view kName = "max_accel";
  bool operator==(const MaxAccelData&) const = default;
};

struct GearData {
  static constexpr std::uint16_t kType = 0x8212;
  static constexpr std::string_view kName = "gear";
  static constexpr std::uint8_t kDownshifting = 0x01;
  static constexpr std::uint8_t kUpshifting = 0x02;
  std::uint8_t flags = 0;
  std::int8_t gear = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint8_t>("flags", s.flags, 0, 3));
    v(enumerated<std::int8_t>("gear", s.gear, kGearNames));
  }
  bool operator==(const GearData&) const = default;
};

struct AnalogOutputsData {
  static constexpr std::uint16_t kType = 0x8300;
  static constexpr std::string_view kName = "analog_outputs";
  std::vector<std::uint16_t> values;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer_list<std::uint16_t>("values", s.values)); }
  bool operator==(const AnalogOutputsData&) const = default;
};

struct GpioData {
  static constexpr std::uint16_t kType = 0x8301;
  static constexpr std::string_view kName = "gpio";
  std::uint32_t direction = 0;  // 1 = output
  std::uint32_t value = 0;      // 1 = high
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(integer<std::uint32_t>("direction", s.direction));
    v(integer<std::uint32_t>("value", s.value));
  }
  bool operator==(const GpioData&) const = default;
};

struct AnalogInputsData {
  static constexpr std::uint16_t kType = 0x8303;
  static constexpr std::string_view kName = "analog_inputs";
  std::vector<std::uint16_t> values;  // 0xFFFF = reference voltage
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer_list<std::uint16_t>("values", s.values)); }
  bool operator==(const AnalogInputsData&) const = default;
};

struct PanTiltZoomData : PanTiltZoomLayout {
  static constexpr std::uint16_t kType = 0x8400;
  static constexpr std::string_view kName = "pan_tilt_zoom";
  bool operator==(const PanTiltZoomData&) const = default;
};

struct RangefinderData {
  static constexpr std::uint16_t kType = 0x8500;
  static constexpr std::string_view kName = "rangefinders";
  std::vector<double> distances;  // m
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::scaled_list<std::int16_t>("distances", s.distances, 1000, 0, 32, "m")); }
  bool operator==(const RangefinderData&) const = default;
};

struct RangefinderTimingData {
  static constexpr std::uint16_t kType = 0x8501;
  static constexpr std::string_view kName = "rangefinder_timing";
  std::vector<TimedRange> ranges;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("ranges", s.ranges, Count::prefixed, Layout::columns));
  }
  bool operator==(const RangefinderTimingData&) const = default;
};

namespace detail {
template <class Self, class V>
void describe_angles(Self& s, V& v) {
  using namespace fields;
  v(scaled<std::int16_t>("roll", s.roll, 1000, -kPi, kPi, "rad"));
  v(scaled<std::int16_t>("pitch", s.pitch, 1000, -kPi, kPi, "rad"));
  v(scaled<std::int16_t>("yaw", s.yaw, 1000, -kPi, kPi, "rad"));
}
template <class Self, class V>
void describe_rates(Self& s, V& v) {
  using namespace fields;
  v(scaled<std::int16_t>("roll_rate", s.roll_rate, 1000, -10 * kPi, 10 * kPi, "rad/s"));
  v(scaled<std::int16_t>("pitch_rate", s.pitch_rate, 1000, -10 * kPi, 10 * kPi, "rad/s"));
  v(scaled<std::int16_t>("yaw_rate", s.yaw_rate, 1000, -10 * kPi, 10 * kPi, "rad/s"));
}
template <class Self, class V>
void describe_xyz(Self& s, V& v, std::string_view unit) {
  using namespace fields;
  v(scaled<std::int16_t>("x", s.x, 1000, -32, 32, unit));
  v(scaled<std::int16_t>("y", s.y, 1000, -32, 32, unit));
  v(scaled<std::int16_t>("z", s.z, 1000, -32, 32, unit));
}
}  // namespace detail

// Yaw left-handed: increases turning east.
struct OrientationData {
  static constexpr std::uint16_t kType = 0x8600;
  static constexpr std::string_view kName = "orientation";
  double roll = 0, pitch = 0, yaw = 0;  // rad
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_angles(s, v); }
  bool operator==(const OrientationData&) const = default;
};

// Yaw rate left-handed: positive = right turn.
struct RotationalRateData {
  static constexpr std::uint16_t kType = 0x8601;
  static constexpr std::string_view kName = "rotational_rates";
  double roll_rate = 0, pitch_rate = 0, yaw_rate = 0;  // rad/s
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_rates(s, v); }
  bool operator==(const RotationalRateData&) const = default;
};

struct AccelerationData {
  static constexpr std::uint16_t kType = 0x8602;
  static constexpr std::string_view kName = "acceleration";
  double x = 0, y = 0, z = 0;  // m/s^2
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_xyz(s, v, "m/s^2"); }
  bool operator==(const AccelerationData&) const = default;
};

// Rates right-handed: positive yaw rate = left turn.
struct SixAxisData {
  static constexpr std::uint16_t kType = 0x8603;
  static constexpr std::string_view kName = "six_axis";
  double x = 0, y = 0, z = 0;
  double roll_rate = 0, pitch_rate = 0, yaw_rate = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    detail::describe_xyz(s, v, "m/s^2");
    detail::describe_rates(s, v);
  }
  bool operator==(const SixAxisData&) const = default;
};

// Yaw and rates right-handed.
struct SixAxisOrientationData {
  static constexpr std::uint16_t kType = 0x8604;
  static constexpr std::string_view kName = "six_axis_orientation";
  double roll = 0, pitch = 0, yaw = 0;
  double x = 0, y = 0, z = 0;
  double roll_rate = 0, pitch_rate = 0, yaw_rate = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    detail::describe_angles(s, v);
    detail::describe_xyz(s, v, "m/s^2");
    detail::describe_rates(s, v);
  }
  bool operator==(const SixAxisOrientationData&) const = default;
};

struct MagnetometerData {
  static constexpr std::uint16_t kType = 0x8606;
  static constexpr std::string_view kName = "magnetometer";
  double x = 0, y = 0, z = 0;  // gauss
  template <class Self, class V>
  static void describe(Self& s, V& v) { detail::describe_xyz(s, v, "G"); }
  bool operator==(const MagnetometerData&) const = default;
};

struct EncoderData {
  static constexpr std::uint16_t kType = 0x8800;
  static constexpr std::string_view kName = "encoders";
  std::vector<EncoderReading> encoders;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("encoders", s.encoders, Count::prefixed, Layout::columns));
  }
  bool operator==(const EncoderData&) const = default;
};

struct RawEncoderData {
  static constexpr std::uint16_t kType = 0x8801;
  static constexpr std::string_view kName = "raw_encoders";
  std::vector<std::int32_t> ticks;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer_list<std::int32_t>("ticks", s.ticks)); }
  bool operator==(const RawEncoderData&) const = default;
};

// Unlike 0x0802, the data form has a count byte.
struct EncoderConfigData {
  static constexpr std::uint16_t kType = 0x8802;
  static constexpr std::string_view kName = "encoder_config";
  std::vector<EncoderSetting> encoders;
  template <class Self, class V>
  static void describe(Self& s, V& v) {
    using namespace fields;
    v(records("encoders", s.encoders, Count::prefixed, Layout::rows));
  }
  bool operator==(const EncoderConfigData&) const = default;
};

// Angles only (no joint IDs), unlike the 0x1010/0x1011 commands.
struct AbsoluteJointsData {
  static constexpr std::uint16_t kType = 0x9010;
  static constexpr std::string_view kName = "absolute_joints";
  std::vector<double> angles;  // rad
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::scaled_list<std::int16_t>("angles", s.angles, 10000, -fields::kPi, fields::kPi, "rad")); }
  bool operator==(const AbsoluteJointsData&) const = default;
};

struct RelativeJointsData {
  static constexpr std::uint16_t kType = 0x9011;
  static constexpr std::string_view kName = "relative_joints";
  std::vector<double> angles;  // rad
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::scaled_list<std::int16_t>("angles", s.angles, 10000, -3.1416, 3.1416, "rad")); }
  bool operator==(const RelativeJointsData&) const = default;
};

struct JointControlData : JointControlLayout {
  static constexpr std::uint16_t kType = 0x9012;
  static constexpr std::string_view kName = "joint_control";
  bool operator==(const JointControlData&) const = default;
};

struct JointHomingData {
  static constexpr std::uint16_t kType = 0x9013;
  static constexpr std::string_view kName = "joint_homing";
  static constexpr std::uint8_t kUnhomed = 0, kHomedAtHome = 1, kHomedMoved = 2;
  std::vector<std::uint8_t> status;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer_list<std::uint8_t>("status", s.status, 0, 2)); }
  bool operator==(const JointHomingData&) const = default;
};

struct JointTorqueData {
  static constexpr std::uint16_t kType = 0x9014;
  static constexpr std::string_view kName = "joint_torques";
  std::vector<double> torques;  // N-m
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::scaled_list<std::int16_t>("torques", s.torques, 100, -320, 320, "N-m")); }
  bool operator==(const JointTorqueData&) const = default;
};

struct EndEffectorPositionData : PositionLayout {
  static constexpr std::uint16_t kType = 0x9020;
  static constexpr std::string_view kName = "end_effector_position_setpoint";
  bool operator==(const EndEffectorPositionData&) const = default;
};
// The document prints 0x9021 twice: 0x9021 is the pose setpoint, 0x9022 the calculated pose.
struct EndEffectorPoseSetpointData : PoseLayout {
  static constexpr std::uint16_t kType = 0x9021;
  static constexpr std::string_view kName = "end_effector_pose_setpoint";
  bool operator==(const EndEffectorPoseSetpointData&) const = default;
};
struct EndEffectorPoseData : PoseLayout {
  static constexpr std::uint16_t kType = 0x9022;
  static constexpr std::string_view kName = "end_effector_pose";
  bool operator==(const EndEffectorPoseData&) const = default;
};

}  // namespace jaus::clearpath
