// The codec of every message body (encode and decode; the JSON form of its
// fields in compiled_json_codecs.hpp) is compiled once, in jaus_core, by the
// catalogue file of the body's group; this header declares those
// instantiations extern. A Message<Code, Name, Body> is encoded as its body
// (wire/message.hpp), so every message with that body uses them. The
// component base (runtime/component.hpp) includes it, so components, the
// OCU and the tests call the library's code rather than compile the codec
// again in every file: under the sanitizers that halves a component's
// compile time. In optimised builds the tests so check the library's own
// -O3 code.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "jaus/messages/all.hpp"

// Every body, listed under the catalogue file that compiles its codec (a body
// shared by several groups is listed once, under the first).
#define JAUS_CORE_BODIES(X)                                                                                   \
  X(msg::AuthorityBody) X(wire::Empty) X(msg::EmergencyBody) X(msg::CreateServiceConnectionBody)             \
  X(msg::ConfirmServiceConnectionBody) X(msg::ServiceConnectionRefBody) X(msg::ResponseCodeBody)              \
  X(msg::TimeBody) X(msg::PresenceQueryBody<std::uint8_t>) X(msg::ComponentStatusBody)                        \
  X(msg::ComponentControlBody)
#define JAUS_COMMUNICATIONS_BODIES(X) X(msg::DataLinkStateBody) X(msg::DataLinkIdBody) X(msg::DataLinkStatusBody)
#define JAUS_PLATFORM_STATE_BODIES(X)                                                                         \
  X(msg::WrenchEffortBody) X(msg::DiscreteDevicesBody) X(msg::GlobalVectorBody) X(msg::LocalVectorBody)       \
  X(msg::PresenceQueryBody<std::uint32_t>) X(msg::PresenceQueryBody<std::uint16_t>)                           \
  X(msg::PlatformSpecificationsBody) X(msg::PlatformOperationalDataBody) X(msg::GlobalPoseBody)               \
  X(msg::LocalPoseBody) X(msg::VelocityStateBody)
#define JAUS_PLATFORM_WAYPOINT_BODIES(X)                                                                      \
  X(msg::TravelSpeedBody) X(msg::GlobalWaypointBody) X(msg::LocalWaypointBody) X(msg::GlobalPathSegmentBody) \
  X(msg::LocalPathSegmentBody) X(msg::WaypointNumberBody) X(msg::PathSegmentQueryBody)                       \
  X(msg::WaypointCountBody) X(msg::PathSegmentCountBody)
#define JAUS_MANIPULATOR_BODIES(X)                                                                            \
  X(msg::JointEffortsBody) X(msg::JointPositionsBody) X(msg::JointVelocitiesBody) X(msg::ToolPointBody)       \
  X(msg::EndEffectorPoseBody) X(msg::EndEffectorVelocityStateBody) X(msg::JointMotionBody)                    \
  X(msg::EndEffectorPathMotionBody) X(msg::ManipulatorSpecificationsBody) X(msg::JointForceTorquesBody)
#define JAUS_ENVIRONMENT_BODIES(X)                                                                            \
  X(msg::CameraPoseCommandBody) X(msg::CameraIdBody) X(msg::CameraCapabilitiesCommandBody)                    \
  X(msg::CameraFormatCommandBody) X(msg::CameraQueryBody<std::uint16_t>) X(msg::CameraQueryBody<std::uint8_t>) \
  X(msg::CameraPoseReportBody) X(msg::CameraCountBody) X(msg::RelativeObjectPositionBody)                     \
  X(msg::CameraCapabilitiesReportBody) X(msg::CameraFormatReportBody) X(msg::ImageBody)
#define JAUS_DISCOVERY_AND_EVENT_BODIES(X)                                                                    \
  X(msg::QueryIdentificationBody) X(msg::QueryConfigurationBody) X(msg::IdentificationBody)                   \
  X(msg::ConfigurationBody) X(msg::SubsystemListBody) X(msg::ServicesBody) X(msg::EventRequestBody)           \
  X(msg::EventUpdateBody) X(msg::CancelEventBody) X(msg::ConfirmEventRequestBody) X(msg::EventBody)
#define JAUS_ALL_BODIES(X)                                                                                    \
  JAUS_CORE_BODIES(X) JAUS_COMMUNICATIONS_BODIES(X) JAUS_PLATFORM_STATE_BODIES(X)                             \
  JAUS_PLATFORM_WAYPOINT_BODIES(X) JAUS_MANIPULATOR_BODIES(X) JAUS_ENVIRONMENT_BODIES(X)                      \
  JAUS_DISCOVERY_AND_EVENT_BODIES(X)

// The codec's function templates for one body, as explicit instantiations:
// declarations with `extern`, the definition without.
#define JAUS_CODEC_INSTANCES(extern_or_not, Body)                                                             \
  extern_or_not template Expected<std::size_t, Error> wire::encode_payload<Body>(const Body&,                  \
                                                                                 std::span<std::uint8_t>,      \
                                                                                 wire::Dialect);               \
  extern_or_not template Expected<void> wire::decode_payload_into<Body>(std::span<const std::uint8_t>, Body&,   \
                                                                        wire::Dialect, std::size_t);
#define JAUS_DECLARE_CODEC(Body) JAUS_CODEC_INSTANCES(extern, Body)

namespace jaus {

JAUS_ALL_BODIES(JAUS_DECLARE_CODEC)

// Every body of every message is listed above, and only once (a second
// specialisation is a redefinition): a body left out would compile its codec
// in every file that uses it.
template <class Body>
inline constexpr bool kCodecCompiledOnce = false;
#define JAUS_MARK_CODEC_COMPILED(Body) \
  template <>                          \
  inline constexpr bool kCodecCompiledOnce<Body> = true;
JAUS_ALL_BODIES(JAUS_MARK_CODEC_COMPILED)
#undef JAUS_MARK_CODEC_COMPILED

template <class... Ms>
constexpr bool codecs_compiled_once(msg::TypeList<Ms...>) {
  return (kCodecCompiledOnce<typename Ms::body_type> && ...);
}
static_assert(codecs_compiled_once(msg::CoreMessages{}), "a core message body is not listed");
static_assert(codecs_compiled_once(msg::CommunicationsMessages{}), "a communications message body is not listed");
static_assert(codecs_compiled_once(msg::PlatformMessages{}), "a platform message body is not listed");
static_assert(codecs_compiled_once(msg::ManipulatorMessages{}), "a manipulator message body is not listed");
static_assert(codecs_compiled_once(msg::EnvironmentMessages{}), "an environment message body is not listed");
static_assert(codecs_compiled_once(msg::DiscoveryMessages{}), "a discovery message body is not listed");
static_assert(codecs_compiled_once(msg::EventMessages{}), "an event message body is not listed");

}  // namespace jaus
