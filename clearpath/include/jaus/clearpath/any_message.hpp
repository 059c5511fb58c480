// AnyMessage: one message of the Clearpath document, whichever its type.
//
// Not a std::variant: libstdc++'s variant is a recursive union, and with the
// document's 110 message types every copy, move, visit or converting
// constructor instantiates helpers quadratic in that count (copying alone
// took over 30 s to compile under the sanitizers). Here each operation is a
// table of one small function per type, built once; the storage is raw
// bytes sized for the largest message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <new>
#include <type_traits>
#include <utility>
#include <variant>  // std::bad_variant_access, what get() throws, as std::get does

#include "jaus/clearpath/ack.hpp"
#include "jaus/clearpath/command_messages.hpp"
#include "jaus/clearpath/data_messages.hpp"
#include "jaus/clearpath/request_messages.hpp"

namespace jaus::clearpath {

template <class... Ts>
struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);
};

// Every typed message of the document. Ack is first; it has no type code of
// its own (it carries the acknowledged message's type in the frame header).
using MessageTypes = TypeList<
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

namespace detail {

template <class T, class... Ts>
constexpr std::size_t index_in(TypeList<Ts...>) {
  constexpr bool matches[] = {std::is_same_v<T, Ts>...};
  for (std::size_t i = 0; i < sizeof...(Ts); ++i)
    if (matches[i]) return i;
  return sizeof...(Ts);
}

template <class... Ts>
constexpr std::size_t largest_size(TypeList<Ts...>) {
  std::size_t largest = 0;
  for (std::size_t size : {sizeof(Ts)...}) largest = size > largest ? size : largest;
  return largest;
}

template <class... Ts>
constexpr std::size_t largest_alignment(TypeList<Ts...>) {
  std::size_t largest = 0;
  for (std::size_t alignment : {alignof(Ts)...}) largest = alignment > largest ? alignment : largest;
  return largest;
}

}  // namespace detail

// Index of a message type in MessageTypes (MessageTypes::size if it is none).
template <class T>
inline constexpr std::size_t kMessageIndex = detail::index_in<T>(MessageTypes{});

template <class T>
concept ClearpathMessage = kMessageIndex<T> < MessageTypes::size;

class AnyMessage {
 public:
  AnyMessage() : AnyMessage(Ack{}) {}
  // From any message of the document (implicit, as a variant converts).
  template <class T>
    requires ClearpathMessage<std::remove_cvref_t<T>>
  AnyMessage(T&& message) {  // NOLINT(google-explicit-constructor)
    using M = std::remove_cvref_t<T>;
    ::new (static_cast<void*>(storage_)) M(std::forward<T>(message));
    index_ = static_cast<std::uint8_t>(kMessageIndex<M>);
  }
  // Defined once, in any_message.cpp.
  AnyMessage(const AnyMessage& other);
  AnyMessage(AnyMessage&& other) noexcept;
  AnyMessage& operator=(const AnyMessage& other);
  AnyMessage& operator=(AnyMessage&& other) noexcept;
  ~AnyMessage();

  // Position of the held type in MessageTypes.
  std::size_t index() const { return index_; }

  template <ClearpathMessage T>
  bool holds() const {
    return index_ == kMessageIndex<T>;
  }
  template <ClearpathMessage T>
  T* get_if() {
    return holds<T>() ? std::launder(reinterpret_cast<T*>(storage_)) : nullptr;
  }
  template <ClearpathMessage T>
  const T* get_if() const {
    return holds<T>() ? std::launder(reinterpret_cast<const T*>(storage_)) : nullptr;
  }
  // The held message as a T; throws std::bad_variant_access if it is another.
  template <ClearpathMessage T>
  T& get() {
    if (!holds<T>()) throw std::bad_variant_access();
    return *get_if<T>();
  }
  template <ClearpathMessage T>
  const T& get() const {
    if (!holds<T>()) throw std::bad_variant_access();
    return *get_if<T>();
  }

  // Same type and equal fields (defined in any_message.cpp).
  friend bool operator==(const AnyMessage& a, const AnyMessage& b);

  // f(held message), as std::visit: f must return the same type for every message.
  template <class F>
  decltype(auto) visit(F&& f) {
    return dispatch<F, AnyMessage, void>(f, *this, MessageTypes{});
  }
  template <class F>
  decltype(auto) visit(F&& f) const {
    return dispatch<F, const AnyMessage, const void>(f, *this, MessageTypes{});
  }

 private:
  // One function per message type, in a table indexed by index_.
  template <class F, class Self, class Void, class... Ts>
  static decltype(auto) dispatch(F& f, Self& self, TypeList<Ts...>) {
    using Result = std::invoke_result_t<F&, Qualified<Self, Ack>&>;
    using Call = Result (*)(F&, Void*);
    static constexpr Call kCalls[] = {&call<Result, F, Void, Qualified<Self, Ts>>...};
    return kCalls[self.index_](f, static_cast<Void*>(self.storage_));
  }
  template <class Self, class T>
  using Qualified = std::conditional_t<std::is_const_v<Self>, const T, T>;
  template <class Result, class F, class Void, class M>
  static Result call(F& f, Void* storage) {
    return std::invoke(f, *std::launder(static_cast<M*>(storage)));
  }

  alignas(detail::largest_alignment(MessageTypes{})) std::byte storage_[detail::largest_size(MessageTypes{})];
  std::uint8_t index_ = 0;
  static_assert(MessageTypes::size <= 256, "index_ holds every position");
};

// Free forms, for code written against std::visit.
template <class F>
decltype(auto) visit(F&& f, AnyMessage& message) {
  return message.visit(std::forward<F>(f));
}
template <class F>
decltype(auto) visit(F&& f, const AnyMessage& message) {
  return message.visit(std::forward<F>(f));
}

}  // namespace jaus::clearpath
