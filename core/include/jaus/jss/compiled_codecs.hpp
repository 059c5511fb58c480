// The codec of every JSS message body, compiled once in jaus_core (by
// the catalogue file of its family) and declared extern here, as
// jaus/messages/compiled_codecs.hpp does for the RA bodies: the face, the OCU
// and the tests call the library's code instead of compiling it again. The
// bodies JSS shares with RA (empty, authority, emergency, time, presence
// queries, query identification/configuration, wrench effort, poses, velocity
// state, travel speed, local waypoint, cancel event, confirm event request,
// event) are RA's, compiled in jaus_core.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "jaus/jss/messages/core.hpp"
#include "jaus/jss/messages/discovery.hpp"
#include "jaus/jss/messages/events.hpp"
#include "jaus/jss/messages/mobility.hpp"
#include "jaus/jss/messages/waypoints.hpp"
#include "jaus/messages/compiled_codecs.hpp"

#define JAUS_JSS_CORE_BODIES(X)                                                                                \
  X(jss::msg::ConfirmControlBody) X(jss::msg::RejectControlBody) X(jss::msg::ReportControlBody)               \
  X(jss::msg::TimeoutBody) X(jss::msg::StatusBody) X(jss::msg::CreateEventBody) X(jss::msg::UpdateEventBody)  \
  X(jss::msg::RejectEventRequestBody)                                                                         \
  X(jss::msg::QueryEventsBody) X(jss::msg::ReportEventsBody)                                                \
  X(jss::msg::EventTimeoutBody) X(jss::msg::CreateCommandEventBody) X(jss::msg::CommandEventBody)             \
  X(jss::msg::ReportIdentificationBody) X(jss::msg::RegisterServicesBody) X(jss::msg::ReportConfigurationBody) \
  X(jss::msg::ReportSubsystemListBody) X(jss::msg::QueryServicesBody) X(jss::msg::ReportServicesBody)         \
  X(jss::msg::QueryServiceListBody) X(jss::msg::ReportServiceListBody)
#define JAUS_JSS_MOBILITY_BODIES(X)                                                                            \
  X(jss::msg::GeomagneticPropertyBody) X(jss::msg::ElementRecord)                                          \
  X(jss::msg::SetElementBody)                                                                                 \
  X(jss::msg::DeleteElementBody) X(jss::msg::ElementRequestBody) X(jss::msg::RejectElementRequestBody)        \
  X(jss::msg::ElementUidBody) X(jss::msg::ElementListBody) X(jss::msg::ElementCountBody)                      \
  X(jss::msg::ExecuteListBody)
#define JAUS_JSS_ALL_BODIES(X) JAUS_JSS_CORE_BODIES(X) JAUS_JSS_MOBILITY_BODIES(X)

namespace jaus {

JAUS_JSS_ALL_BODIES(JAUS_DECLARE_CODEC)

#define JAUS_MARK_CODEC_COMPILED(Body) \
  template <>                          \
  inline constexpr bool kCodecCompiledOnce<Body> = true;
JAUS_JSS_ALL_BODIES(JAUS_MARK_CODEC_COMPILED)
#undef JAUS_MARK_CODEC_COMPILED

static_assert(codecs_compiled_once(jss::msg::AccessControlMessages{}), "a JSS access control body is not listed");
static_assert(codecs_compiled_once(jss::msg::ManagementMessages{}), "a JSS management body is not listed");
static_assert(codecs_compiled_once(jss::msg::TimeMessages{}), "a JSS time body is not listed");
static_assert(codecs_compiled_once(jss::msg::LivenessMessages{}), "a JSS liveness body is not listed");
static_assert(codecs_compiled_once(jss::msg::EventsMessages{}), "a JSS events body is not listed");
static_assert(codecs_compiled_once(jss::msg::DiscoveryMessages{}), "a JSS discovery body is not listed");
static_assert(codecs_compiled_once(jss::msg::SensorDriverMessages{}), "a JSS mobility body is not listed");
static_assert(codecs_compiled_once(jss::msg::WaypointMessages{}), "a JSS waypoint body is not listed");

}  // namespace jaus
