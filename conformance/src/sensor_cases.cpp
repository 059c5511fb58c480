// The pose and velocity sensor cases, one set per report (Report Global
// Pose, Report Local Pose, Report Velocity State): a query gets the
// requested AND available fields, time stamps advance, and what a query
// says agrees with what a service connection says at the same time. Each
// terminates the service connection it created; none commands anything.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "case_support.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "state_support.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

// The nine fields of each report: eight values (presence bits 0..7) and the
// time stamp (bit 8), with how far a query's value may lie outside the
// range of the service connection's values around it (far above the wire's
// resolution, far below what a wrong unit or frame would give).
constexpr std::uint32_t kDefinedFields = 0x1FF;
constexpr std::uint32_t kTimeStampBit = 1u << 8;
constexpr int kValueFields = 8;

template <class Body>
struct SensorFields;

template <>
struct SensorFields<msg::GlobalPoseBody> {
  using B = msg::GlobalPoseBody;
  static constexpr std::array<std::optional<double> B::*, kValueFields> members{
      &B::latitude_deg, &B::longitude_deg, &B::elevation_m, &B::position_rms_m,
      &B::roll_rad,     &B::pitch_rad,     &B::yaw_rad,     &B::attitude_rms_rad};
  static constexpr std::array<const char*, kValueFields> names{"latitude", "longitude", "elevation", "position RMS",
                                                               "roll",     "pitch",     "yaw",       "attitude RMS"};
  static constexpr std::array<double, kValueFields> tolerance{1e-6, 1e-6, 0.05, 0.05, 0.005, 0.005, 0.005, 0.005};
};

template <>
struct SensorFields<msg::LocalPoseBody> {
  using B = msg::LocalPoseBody;
  static constexpr std::array<std::optional<double> B::*, kValueFields> members{
      &B::x_m, &B::y_m, &B::z_m, &B::position_rms_m, &B::roll_rad, &B::pitch_rad, &B::yaw_rad, &B::attitude_rms_rad};
  static constexpr std::array<const char*, kValueFields> names{"x",    "y",     "z",   "position RMS",
                                                               "roll", "pitch", "yaw", "attitude RMS"};
  static constexpr std::array<double, kValueFields> tolerance{0.05, 0.05, 0.05, 0.05, 0.005, 0.005, 0.005, 0.005};
};

template <>
struct SensorFields<msg::VelocityStateBody> {
  using B = msg::VelocityStateBody;
  static constexpr std::array<std::optional<double> B::*, kValueFields> members{
      &B::velocity_x_mps, &B::velocity_y_mps, &B::velocity_z_mps, &B::velocity_rms_mps,
      &B::roll_rate_rps,  &B::pitch_rate_rps, &B::yaw_rate_rps,   &B::rate_rms_rps};
  static constexpr std::array<const char*, kValueFields> names{"velocity X", "velocity Y", "velocity Z", "velocity RMS",
                                                               "roll rate",  "pitch rate", "yaw rate",   "rate RMS"};
  static constexpr std::array<double, kValueFields> tolerance{0.01, 0.01, 0.01, 0.01, 0.005, 0.005, 0.005, 0.005};
};

std::string hex(std::uint32_t v) { return "0x" + wire::detail::hex_u32(v); }

// Milliseconds since the start of the month: time stamps carry no month.
std::int64_t month_ms(const TimeStamp& t) {
  return (((static_cast<std::int64_t>(t.day) * 24 + t.hour) * 60 + t.minute) * 60 + t.second) * 1000 + t.millisecond;
}

std::string time_text(const TimeStamp& t) {
  char text[40];
  std::snprintf(text, sizeof text, "day %u %02u:%02u:%02u.%03u", static_cast<unsigned>(t.day),
                static_cast<unsigned>(t.hour), static_cast<unsigned>(t.minute), static_cast<unsigned>(t.second),
                static_cast<unsigned>(t.millisecond));
  return text;
}

// The presence vector a reply carries (the first two bytes of its payload).
std::uint32_t presence_in(const ocu::Received& reply) {
  if (reply.payload.size() < 2) return 0;
  return static_cast<std::uint32_t>(reply.payload[0]) | (static_cast<std::uint32_t>(reply.payload[1]) << 8);
}

template <class Query, class Report>
struct Sensor {
  using Fields = SensorFields<typename Report::body_type>;

  static std::string not_applicable(const ComponentUnderTest& component) {
    // Appended, not `std::string(name) + " ("`: GCC 12 sees a false -Warray-bounds in that once inlined.
    std::string what(Query::name);
    what += " (" + ocu::code_text(Query::code) + ")";
    return unless_accepts(component, Query::code, what);
  }

  // Sends Query with `presence`; the reply as received (for its presence
  // vector) and decoded.
  static Expected<std::pair<std::uint32_t, Report>> query(CaseContext& c, std::uint32_t presence) {
    Query q;
    q.presence_vector = static_cast<std::uint16_t>(presence);
    send(c, q);
    auto reply = await(c, {Report::code});
    if (!reply) return unexpected(reply.error());
    auto report = decode<Report>(c, *reply);
    if (!report) return unexpected(report.error());
    return std::pair{presence_in(*reply), *report};
  }

  // The reply holds the requested AND available fields: all it has for all
  // defined, exactly the one it has for one it has plus one it lacks, none
  // for none. "Available" is what its Report Services says it provides,
  // when it says so.
  static CaseOutcome presence_and(CaseContext& c) {
    auto full = query(c, kDefinedFields);
    if (!full) return fail(full.error().message());
    const std::uint32_t available = full->first;
    if (c.component.provides(Report::code) && available != c.component.outputs.at(Report::code))
      return fail("presence vector " + hex(available) + " for " + hex(kDefinedFields) +
                  " asked; Report Services says " + hex(c.component.outputs.at(Report::code)) + " available");
    if (available == 0) return skip("it reports no field now (no sample yet?)");
    const std::uint32_t has = available & (~available + 1);
    const std::uint32_t lacking = kDefinedFields & ~available;
    const std::uint32_t asked = has | (lacking & (~lacking + 1));
    auto some = query(c, asked);
    if (!some) return fail(some.error().message());
    if (some->first != (asked & available))
      return fail("presence vector " + hex(some->first) + " for " + hex(asked) + " asked and " + hex(available) +
                  " available");
    auto none = query(c, 0);
    if (!none) return fail(none.error().message());
    if (none->first != 0) return fail("presence vector " + hex(none->first) + " for none asked");
    return pass(hex(available) + " of " + hex(kDefinedFields) + ", " + hex(some->first) + " of " + hex(asked) +
                ", none of none");
  }

  // Two time stamps 0.3 s apart: the second is later (the sample's time, so
  // a sensor that stamps a fixed or cached time shows).
  static CaseOutcome time_advances(CaseContext& c) {
    auto state = primary_status(c);
    if (!state) return fail(state.error().message());
    if (*state != msg::PrimaryStatus::ready)
      return skip("in " + state_text(*state) + ": a sensor without fresh samples may repeat its time stamp");
    auto first = query(c, kTimeStampBit);
    if (!first) return fail(first.error().message());
    if (!first->second.time_stamp) return skip("it reports no time stamp");
    c.session.run_for(std::chrono::milliseconds(300));
    auto second = query(c, kTimeStampBit);
    if (!second) return fail("0.3 s later, " + second.error().message());
    if (!second->second.time_stamp) return fail("0.3 s later, a report without the time stamp it had");
    const TimeStamp& a = *first->second.time_stamp;
    const TimeStamp& b = *second->second.time_stamp;
    const bool month_turned = b.day < a.day;  // time stamps carry the day of the month only
    if (!month_turned && month_ms(b) <= month_ms(a))
      return fail("time stamp " + time_text(a) + ", then " + time_text(b) + " 0.3 s later");
    return pass(time_text(a) + ", then " + time_text(b));
  }

  // A query in the middle of a service connection's reports says what they
  // say: each value within the range of theirs (the query's sample lies
  // between theirs in time), and the same fields.
  static CaseOutcome query_matches_sc(CaseContext& c) {
    if (!c.component.provides(Report::code))
      return skip("Report Services lists no " + std::string(Report::name) + " on service connections");
    const std::uint32_t available = c.component.outputs.at(Report::code);
    msg::CreateServiceConnection create;
    create.command_code = Report::code;
    create.periodic_rate_hz = 10;
    create.presence_vector = available;
    std::vector<ocu::Received> on_sc;
    std::optional<ocu::Received> answer;
    const auto listener = c.session.listen([&](const ocu::Received& r) {
      if (r.header.command_code != Report::code || r.header.source != c.target()) return;
      if (r.header.service_connection)
        on_sc.push_back(r);
      else if (!answer)
        answer = r;
    });
    auto confirm = ask<msg::ConfirmServiceConnection>(c, create);
    const bool created = confirm && confirm->response_code == msg::sc_response::kCreated;
    if (created) {
      c.session.run_for(std::chrono::milliseconds(300));
      Query q;
      q.presence_vector = static_cast<std::uint16_t>(available);
      send(c, q);
      c.session.run_for(std::chrono::milliseconds(300));
      send(c, msg::TerminateServiceConnection{{Report::code, confirm->instance_id}});
    }
    c.session.unlisten(listener);
    if (!confirm) return fail(confirm.error().message());
    if (!created) return fail("refused: " + ocu::service_connection_response_text(confirm->response_code));
    if (!answer) return fail("no reply to " + std::string(Query::name) + " while the service connection ran");
    if (on_sc.size() < 2) return fail(std::to_string(on_sc.size()) + " reports in 0.6 s at 10 Hz");
    auto queried = decode<Report>(c, *answer);
    if (!queried) return fail(queried.error().message());
    std::array<double, kValueFields> low, high;
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    for (const auto& r : on_sc) {
      if (presence_in(r) != presence_in(*answer))
        return fail("the query's presence vector " + hex(presence_in(*answer)) + ", the service connection's " +
                    hex(presence_in(r)) + ", both asked " + hex(available));
      auto report = decode<Report>(c, r);
      if (!report) return fail("on the service connection, " + report.error().message());
      for (int f = 0; f < kValueFields; ++f)
        if (const auto& v = (*report).*Fields::members[f]) {
          low[f] = std::min(low[f], *v);
          high[f] = std::max(high[f], *v);
        }
    }
    for (int f = 0; f < kValueFields; ++f) {
      const auto& v = (*queried).*Fields::members[f];
      if (!v) continue;
      if (*v < low[f] - Fields::tolerance[f] || *v > high[f] + Fields::tolerance[f]) {
        char text[160];
        std::snprintf(text, sizeof text, "%s %.7g by query, %.7g .. %.7g on the service connection around it",
                      Fields::names[f], *v, low[f], high[f]);
        return fail(text);
      }
    }
    return pass("the query's " + hex(presence_in(*answer)) + " fields within those of " + std::to_string(on_sc.size()) +
                " reports around it");
  }
};

using GlobalPose = Sensor<msg::QueryGlobalPose, msg::ReportGlobalPose>;
using LocalPose = Sensor<msg::QueryLocalPose, msg::ReportLocalPose>;
using VelocityState = Sensor<msg::QueryVelocityState, msg::ReportVelocityState>;

}  // namespace

std::span<const ConformanceCase> sensor_cases() {
  static const std::vector<ConformanceCase> list{
      {"sensor.global_pose.presence_and", "Query Global Pose gets the requested AND available fields",
       "Part 3, Code 2402h Query Global Pose, Code 4402h Report Global Pose; docs/wire-format.md: Presence vectors",
       GlobalPose::not_applicable, GlobalPose::presence_and},
      {"sensor.global_pose.time_advances", "Report Global Pose time stamps advance",
       "Part 3, Code 4402h Report Global Pose (Time Stamp)", GlobalPose::not_applicable, GlobalPose::time_advances},
      {"sensor.global_pose.query_matches_sc", "a query's Report Global Pose agrees with the service connection's",
       "Part 3, Code 4402h Report Global Pose, Code 0008h Create Service Connection", GlobalPose::not_applicable,
       GlobalPose::query_matches_sc},
      {"sensor.local_pose.presence_and", "Query Local Pose gets the requested AND available fields",
       "Part 3, Code 2403h Query Local Pose, Code 4403h Report Local Pose; docs/wire-format.md: Presence vectors",
       LocalPose::not_applicable, LocalPose::presence_and},
      {"sensor.local_pose.time_advances", "Report Local Pose time stamps advance",
       "Part 3, Code 4403h Report Local Pose (Time Stamp)", LocalPose::not_applicable, LocalPose::time_advances},
      {"sensor.local_pose.query_matches_sc", "a query's Report Local Pose agrees with the service connection's",
       "Part 3, Code 4403h Report Local Pose, Code 0008h Create Service Connection", LocalPose::not_applicable,
       LocalPose::query_matches_sc},
      {"sensor.velocity_state.presence_and", "Query Velocity State gets the requested AND available fields",
       "Part 3, Code 2404h Query Velocity State, Code 4404h Report Velocity State; "
       "docs/wire-format.md: Presence vectors",
       VelocityState::not_applicable, VelocityState::presence_and},
      {"sensor.velocity_state.time_advances", "Report Velocity State time stamps advance",
       "Part 3, Code 4404h Report Velocity State (Time Stamp)", VelocityState::not_applicable,
       VelocityState::time_advances},
      {"sensor.velocity_state.query_matches_sc", "a query's Report Velocity State agrees with the service connection's",
       "Part 3, Code 4404h Report Velocity State, Code 0008h Create Service Connection", VelocityState::not_applicable,
       VelocityState::query_matches_sc},
  };
  return list;
}

}  // namespace jaus::conform
