// The whole Clearpath message set as one variant, and look-up by type code.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>

#include "jaus/clearpath/ack.hpp"
#include "jaus/clearpath/command_messages.hpp"
#include "jaus/clearpath/data_messages.hpp"
#include "jaus/clearpath/message_kind.hpp"
#include "jaus/clearpath/request_messages.hpp"

namespace jaus::clearpath {

// Every typed message of the document. Ack is first; it has no type code of
// its own (it carries the acknowledged message's type in the frame header).
using MessageVariant = std::variant<
    Ack,
    // commands
    SetPlatformName, SetPlatformTime, SetSafetySystem, SetDifferentialSpeeds, SetDifferentialControl,
    SetDifferentialOutput, SetAckermannOutput, SetVelocity, SetTurn, SetAckermannControl, SetMaxSpeed, SetMaxAccel,
    ChangeGear, SetAnalogOutputs, SetGpioDirection, SetGpioOutput, SetPanTiltZoom, ConfigureEncoders,
    SetAbsoluteJoints, SetRelativeJoints, SetJointControl, HomeJoint, SetEndEffectorPosition, SetEndEffectorPose,
    ResetProcessor, RestoreSettings, StoreSettings,
    // requests
    RequestEcho, RequestPlatformInfo, RequestPlatformName, RequestFirmwareInfo, RequestSystemStatus,
    RequestPowerStatus, RequestProcessorStatus, RequestSafetyStatus, RequestDifferentialSpeeds,
    RequestDifferentialControl, RequestDifferentialOutput, RequestAckermannOutput, RequestVelocity, RequestTurn,
    RequestAckermannControl, RequestMaxSpeed, RequestMaxAccel, RequestGear, RequestAnalogOutputs, RequestGpio,
    RequestAnalogInputs, RequestPanTiltZoom, RequestRangefinders, RequestRangefinderTiming, RequestOrientation,
    RequestRotationalRates, RequestAcceleration, RequestSixAxis, RequestSixAxisOrientation, RequestMagnetometer,
    RequestEncoders, RequestRawEncoders, RequestEncoderConfig, RequestAbsoluteJoints, RequestRelativeJoints,
    RequestJointControl, RequestJointHoming, RequestJointTorques, RequestEndEffectorPosition,
    RequestEndEffectorPoseSetpoint, RequestEndEffectorPose,
    // data
    EchoData, PlatformInfo, PlatformName, FirmwareInfo, SystemStatus, PowerStatus, ProcessorStatus, SafetyStatus,
    DifferentialSpeedsData, DifferentialControlData, DifferentialOutputData, AckermannOutputData, VelocityData,
    TurnData, AckermannControlData, MaxSpeedData, MaxAccelData, GearData, AnalogOutputsData, GpioData,
    AnalogInputsData, PanTiltZoomData, RangefinderData, RangefinderTimingData, OrientationData, RotationalRateData,
    AccelerationData, SixAxisData, SixAxisOrientationData, MagnetometerData, EncoderData, RawEncoderData,
    EncoderConfigData, AbsoluteJointsData, RelativeJointsData, JointControlData, JointHomingData, JointTorqueData,
    EndEffectorPositionData, EndEffectorPoseSetpointData, EndEffectorPoseData>;

// A named type rather than an alias keeps symbol names (and object files)
// short. Copying, moving and destroying a variant of this many alternatives
// instantiates code for every one of them (quadratically many helpers in
// libstdc++'s recursive union): defined once (any_message.cpp) rather than
// in every file that passes a message on.
struct AnyMessage : MessageVariant {
  using MessageVariant::MessageVariant;
  AnyMessage(const AnyMessage& other);
  AnyMessage(AnyMessage&& other) noexcept;
  AnyMessage& operator=(const AnyMessage& other);
  AnyMessage& operator=(AnyMessage&& other) noexcept;
  ~AnyMessage();
};

// A type code of the document and its message name.
struct MessageTypeInfo {
  std::uint16_t type;
  std::string_view name;
  MessageKind kind;
};

// All typed messages of the document, ordered by type code (Ack excluded).
std::span<const MessageTypeInfo> message_catalogue();
std::optional<MessageTypeInfo> find_message(std::uint16_t type);
std::optional<MessageTypeInfo> find_message(std::string_view name);

// Default-constructed message of that type (nullopt for types the document lacks).
std::optional<AnyMessage> make_message(std::uint16_t type);

// The type code a message is sent with (Ack: nullopt, it borrows its target's).
std::optional<std::uint16_t> type_of(const AnyMessage& message);
std::string_view name_of(const AnyMessage& message);

}  // namespace jaus::clearpath
