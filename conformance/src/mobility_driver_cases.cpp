// The drivers above the primitive driver (Part 3: the vector, waypoint and
// path segment drivers, components 34 and 44-48): the lists count from zero
// and element 0 starts a new one, a number past the end is refused, each
// element is reported exactly as it was set, the travel speed is echoed,
// only the controller's Set is executed, and a vector is reported as set.
//
// Safety first, as in the primitive driver cases:
//   - a list (and a travel speed) is loaded in Standby and never resumed.
//     Both start rules a route driver may have are accepted and neither
//     can move a vehicle here: one that drives only after Standby -> load
//     -> Resume, and one that drives a list loaded in Ready once its
//     controller's travel speed is above zero (the RA implementations',
//     OpenJAUS's; jausd's drivers have both). Every list case that loaded
//     something ends with Reset under control (ResetOnExit), so nothing it
//     loaded is driven by a later Resume;
//   - a vector case commands at most a crawl (0.1 m/s; the global vector
//     speed 0, its smallest step on the wire being 0.15 m/s) and ends, however
//     it ends, commanding speed 0 and Standby (StopVectorOnExit) before it
//     releases control.
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>

#include "case_support.hpp"
#include "jaus/messages/catalogue.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "state_support.hpp"
#include "stop_paths.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

constexpr double kCrawlMps = 0.1;
constexpr std::uint16_t kListLength = 3;  // elements a case loads

template <class M>
std::vector<std::uint8_t> body_bytes(const M& message) {
  std::vector<std::uint8_t> bytes(kMaxPayloadSize);
  const auto size = wire::encode_payload(message, bytes);
  bytes.resize(size ? *size : 0);
  return bytes;
}

std::string hex_text(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string text;
  for (const std::uint8_t b : bytes) {
    text += kDigits[b >> 4];
    text += kDigits[b & 0x0F];
  }
  return text.empty() ? "(empty)" : text;
}

std::string number_text(double value, const char* unit) {
  char text[40];
  std::snprintf(text, sizeof text, "%.3f %s", value, unit);
  return text;
}

// ------------------------------------------------------------ the lists

// One kind of list (global/local waypoints, global/local path segments):
// its messages and the elements the cases load. Every element of a list
// carries the same presence vector (Part 3: "the presence vector applies to
// all waypoints"), with optional fields, so that their echo shows too.
struct GlobalWaypoints {
  using Set = msg::SetGlobalWaypoint;
  using Query = msg::QueryGlobalWaypoint;
  using Report = msg::ReportGlobalWaypoint;
  using QueryCount = msg::QueryWaypointCount;
  using ReportCount = msg::ReportWaypointCount;
  static constexpr const char* kElement = "waypoint";
  // `variant` tells two elements with one number apart.
  static Set element(std::uint16_t n, int variant) {
    Set m;
    m.waypoint_number = n;
    m.latitude_deg = 45.0 + 0.0001 * (n + 1) + 0.001 * variant;
    m.longitude_deg = -73.0 + 0.0001 * n;
    m.yaw_rad = 0.25 * n;
    return m;
  }
  static Query query(std::uint16_t n) { return Query{{n}}; }
  static std::uint16_t count(const ReportCount& r) { return r.waypoint_count; }
};

struct LocalWaypoints {
  using Set = msg::SetLocalWaypoint;
  using Query = msg::QueryLocalWaypoint;
  using Report = msg::ReportLocalWaypoint;
  using QueryCount = msg::QueryWaypointCount;
  using ReportCount = msg::ReportWaypointCount;
  static constexpr const char* kElement = "waypoint";
  static Set element(std::uint16_t n, int variant) {
    Set m;
    m.waypoint_number = n;
    m.x_m = 1.0 * (n + 1) + 10.0 * variant;
    m.y_m = 0.5 * n;
    m.yaw_rad = 0.25 * n;
    return m;
  }
  static Query query(std::uint16_t n) { return Query{{n}}; }
  static std::uint16_t count(const ReportCount& r) { return r.waypoint_count; }
};

struct GlobalPathSegments {
  using Set = msg::SetGlobalPathSegment;
  using Query = msg::QueryGlobalPathSegment;
  using Report = msg::ReportGlobalPathSegment;
  using QueryCount = msg::QueryPathSegmentCount;
  using ReportCount = msg::ReportPathSegmentCount;
  static constexpr const char* kElement = "path segment";
  static Set element(std::uint16_t n, int variant) {
    Set m;
    m.path_segment_number = n;
    m.p1_latitude_deg = 45.0 + 0.0001 * n + 0.00005 + 0.001 * variant;
    m.p1_longitude_deg = -73.0 + 0.00005;
    m.p1_elevation_m = 50;
    m.p2_latitude_deg = 45.0 + 0.0001 * (n + 1) + 0.001 * variant;
    m.p2_longitude_deg = -73.0;
    m.p2_elevation_m = 50;
    m.weighting_factor = n % 2 == 0 ? 0.0 : 1.5;
    return m;
  }
  // Every field the segment may carry asked for (Part 3: the reply holds
  // the requested AND available ones).
  static Query query(std::uint16_t n) { return Query{{n, 0x03}}; }
  static std::uint16_t count(const ReportCount& r) { return r.path_segment_count; }
};

struct LocalPathSegments {
  using Set = msg::SetLocalPathSegment;
  using Query = msg::QueryLocalPathSegment;
  using Report = msg::ReportLocalPathSegment;
  using QueryCount = msg::QueryPathSegmentCount;
  using ReportCount = msg::ReportPathSegmentCount;
  static constexpr const char* kElement = "path segment";
  static Set element(std::uint16_t n, int variant) {
    Set m;
    m.path_segment_number = n;
    m.p1_x_m = 2.0 * n + 1.0 + 10.0 * variant;
    m.p1_y_m = 0.5;
    m.p1_z_m = 0;
    m.p2_x_m = 2.0 * (n + 1) + 10.0 * variant;
    m.p2_y_m = 0;
    m.p2_z_m = 0;
    m.weighting_factor = n % 2 == 0 ? 0.0 : 1.5;
    return m;
  }
  static Query query(std::uint16_t n) { return Query{{n, 0x03}}; }
  static std::uint16_t count(const ReportCount& r) { return r.path_segment_count; }
};

// Reset when the case ends, however it ends, once it may have loaded
// something (arm()), under control taken for it (declared before the case's
// own ControlHeld, it runs after that one's release): whatever the case
// loaded is cleared, so no later Resume drives it. A case that loaded
// nothing leaves the state it found alone.
class ResetOnExit {
 public:
  explicit ResetOnExit(CaseContext& c) : c_(c) {}
  ~ResetOnExit() {
    if (!armed_) return;
    ControlHeld control(c_);
    send(c_, msg::Reset{});
  }
  ResetOnExit(const ResetOnExit&) = delete;
  ResetOnExit& operator=(const ResetOnExit&) = delete;
  void arm() { armed_ = true; }

 private:
  CaseContext& c_;
  bool armed_ = false;
};

// Puts the controlled driver in Standby, where loading cannot move anything
// (after the time a Reset of an earlier case takes to re-initialise). The
// verdict when it cannot: control not granted, a state it does not leave
// for Standby, no answer.
std::optional<CaseOutcome> unless_in_standby(CaseContext& c, const ControlHeld& control) {
  if (!control.granted()) return skip("control not granted (" + control.why() + ")");
  auto state = state_after_initialising(c);
  if (state && *state == msg::PrimaryStatus::ready) {
    send(c, msg::Standby{});
    state = primary_status(c);
  }
  if (!state) return fail(state.error().message());
  if (*state != msg::PrimaryStatus::standby)
    return skip("in " + state_text(*state) + ": lists are loaded in Standby here, where nothing can move");
  return std::nullopt;
}

// The travel speed it reports (Query Travel Speed), as received.
Expected<std::vector<std::uint8_t>> reported_travel_speed(CaseContext& c) {
  send(c, msg::QueryTravelSpeed{});
  auto reply = await(c, {msg::ReportTravelSpeed::code});
  if (!reply) return unexpected(reply.error());
  return reply->payload;
}

msg::SetTravelSpeed travel_speed(double mps) {
  msg::SetTravelSpeed m;
  m.speed_mps = mps;
  return m;
}

std::string unless_accepts_code(const ComponentUnderTest& component, std::uint16_t code) {
  const msg::MessageInfo* info = msg::find_message(wire::Dialect::ra, code);
  return unless_accepts(component, code,
                        (info ? std::string(info->name) + " (" : "(") + ocu::code_text(code) + ")");
}

template <class L>
struct ListDriver {
  static std::string not_applicable(const ComponentUnderTest& component) {
    for (const std::uint16_t code : {L::Set::code, L::Query::code, L::QueryCount::code})
      if (auto why = unless_accepts_code(component, code); !why.empty()) return why;
    return {};
  }

  static Expected<std::uint16_t> count(CaseContext& c) {
    auto report = ask<typename L::ReportCount>(c, typename L::QueryCount{});
    if (!report) return unexpected(report.error());
    return L::count(*report);
  }

  // Element n as reported (the payload as received); an error when it does
  // not answer.
  static Expected<std::vector<std::uint8_t>> reported(CaseContext& c, std::uint16_t n) {
    send(c, L::query(n));
    auto reply = await(c, {L::Report::code});
    if (!reply) return unexpected(reply.error());
    return reply->payload;
  }

  static std::string element_text(std::uint16_t n) { return std::string(L::kElement) + " " + std::to_string(n); }

  // Sends elements first..last-1 of `variant`; empty, or why the count
  // afterwards is not `last`.
  static std::string load(CaseContext& c, std::uint16_t first, std::uint16_t last, int variant) {
    for (std::uint16_t n = first; n < last; ++n) send(c, L::element(n, variant));
    auto loaded = count(c);
    if (!loaded) return "after " + element_text(last - 1) + ", " + loaded.error().message();
    if (*loaded != last)
      return std::to_string(*loaded) + " " + L::kElement + "s counted after " + std::to_string(last) +
             " loaded (numbers 0.." + std::to_string(last - 1) + ")";
    return {};
  }

  // Empty, or how element n is reported otherwise than it was set.
  static std::string echoed(CaseContext& c, std::uint16_t n, int variant) {
    auto got = reported(c, n);
    if (!got) return "Query " + element_text(n) + ": " + got.error().message();
    const auto set = body_bytes(L::element(n, variant));
    if (*got != set) return element_text(n) + " reported as " + hex_text(*got) + ", set as " + hex_text(set);
    return {};
  }

  // Element 0 starts the list (count 1); each next number adds one; each
  // element is reported exactly as set (presence vector and optional
  // fields included).
  static CaseOutcome count_and_echo(CaseContext& c) {
    ResetOnExit reset(c);
    ControlHeld control(c);
    if (auto verdict = unless_in_standby(c, control)) return *verdict;
    reset.arm();
    if (auto wrong = load(c, 0, 1, 0); !wrong.empty()) return fail(wrong);
    if (auto wrong = load(c, 1, kListLength, 0); !wrong.empty()) return fail(wrong);
    for (std::uint16_t n = 0; n < kListLength; ++n)
      if (auto wrong = echoed(c, n, 0); !wrong.empty()) return fail(wrong);
    return pass("counted 1 after " + element_text(0) + ", " + std::to_string(kListLength) + " after " +
                element_text(kListLength - 1) + "; each reported as set");
  }

  // A number past the end is refused (Part 3: each next element is the
  // last one's number plus one); element 0 starts a new list, the old one
  // dropped: what it held is no longer reported.
  static CaseOutcome numbering(CaseContext& c) {
    ResetOnExit reset(c);
    ControlHeld control(c);
    if (auto verdict = unless_in_standby(c, control)) return *verdict;
    reset.arm();
    if (auto wrong = load(c, 0, kListLength, 0); !wrong.empty()) return fail(wrong);
    const std::uint16_t past_end = kListLength + 1;
    send(c, L::element(past_end, 0));
    auto after_gap = count(c);
    if (!after_gap) return fail("after " + element_text(past_end) + ", " + after_gap.error().message());
    if (*after_gap != kListLength)
      return fail(element_text(past_end) + " sent with " + std::to_string(kListLength) + " loaded: counted " +
                  std::to_string(*after_gap) + " (a number past the end must be refused)");
    send(c, L::element(0, 1));
    auto restarted = count(c);
    if (!restarted) return fail("after a new " + element_text(0) + ", " + restarted.error().message());
    if (*restarted != 1)
      return fail("a new " + element_text(0) + " with " + std::to_string(kListLength) + " loaded: counted " +
                  std::to_string(*restarted) + ", not 1 (element 0 starts a new list)");
    if (auto wrong = echoed(c, 0, 1); !wrong.empty()) return fail("the new list's " + wrong);
    const auto dropped = reported(c, 1);
    if (dropped && *dropped == body_bytes(L::element(1, 0)))
      return fail("the dropped list's " + element_text(1) + " is still reported after a new " + element_text(0));
    return pass(element_text(past_end) + " refused (" + std::to_string(kListLength) + " still counted); a new " +
                element_text(0) + " counted 1 and reported as set; the dropped " + element_text(1) + " " +
                (dropped ? "answered with other data" : "not reported"));
  }

  // A Set from a non-controller is not executed: the count and element 0
  // stay as they were, and so does the travel speed when it has one. The
  // runner loads one element in Standby and releases control first (so a
  // wrongly executed Set cannot start a route); Reset clears it all at the end.
  static CaseOutcome non_controller_ignored(CaseContext& c) {
    ResetOnExit reset(c);
    {
      ControlHeld control(c);
      if (auto verdict = unless_in_standby(c, control)) return *verdict;
      reset.arm();
      if (auto wrong = load(c, 0, 1, 0); !wrong.empty()) return fail(wrong);
    }
    auto controller = current_controller(c);
    if (!controller) return fail(controller.error().message());
    if (*controller == c.session.self()) return skip("the runner still controls it after releasing control");
    const bool has_travel_speed =
        c.component.accepts(msg::SetTravelSpeed::code) && c.component.accepts(msg::QueryTravelSpeed::code);
    std::optional<std::vector<std::uint8_t>> speed_before;
    if (has_travel_speed) {
      auto before = reported_travel_speed(c);
      if (!before) return fail(before.error().message());
      speed_before = *before;
    }
    send(c, L::element(0, 2));
    if (has_travel_speed) {
      // A speed it does not have now (one of two, unless both are: then nothing to see).
      const auto first = body_bytes(travel_speed(0.37));
      send(c, travel_speed(*speed_before == first ? 0.53 : 0.37));
    }
    auto after = count(c);
    if (!after) return fail("after Set from a non-controller, " + after.error().message());
    const std::string by = " from a non-controller (controller " + controller->to_string() + ")";
    if (*after != 1)
      return fail("a new " + element_text(0) + by + ": counted " + std::to_string(*after) + ", 1 before");
    if (auto wrong = echoed(c, 0, 0); !wrong.empty())
      return fail("after a new " + element_text(0) + by + ", " + wrong);
    if (has_travel_speed) {
      auto speed_after = reported_travel_speed(c);
      if (!speed_after) return fail("after Set Travel Speed" + by + ", " + speed_after.error().message());
      if (*speed_after != *speed_before)
        return fail("Set Travel Speed" + by + " executed: reported " + hex_text(*speed_after) + ", " +
                    hex_text(*speed_before) + " before");
    }
    return pass(std::string("a new ") + element_text(0) + (has_travel_speed ? " and Set Travel Speed" : "") + by +
                ": not executed");
  }
};

// Set Travel Speed from its controller is reported by Report Travel Speed
// (set in Standby, where it cannot move anything; Reset at the end).
std::string unless_travel_speed(const ComponentUnderTest& component) {
  for (const std::uint16_t code : {msg::SetTravelSpeed::code, msg::QueryTravelSpeed::code})
    if (auto why = unless_accepts_code(component, code); !why.empty()) return why;
  return {};
}

CaseOutcome travel_speed_echo(CaseContext& c) {
  ResetOnExit reset(c);
  ControlHeld control(c);
  if (auto verdict = unless_in_standby(c, control)) return *verdict;
  reset.arm();
  std::string seen;
  for (const double mps : {0.3, 0.7}) {
    send(c, travel_speed(mps));
    auto got = reported_travel_speed(c);
    if (!got) return fail("after Set Travel Speed " + number_text(mps, "m/s") + ", " + got.error().message());
    const auto set = body_bytes(travel_speed(mps));
    if (*got != set)
      return fail("Set Travel Speed " + number_text(mps, "m/s") + " (" + hex_text(set) + ") reported as " +
                  hex_text(*got));
    seen += (seen.empty() ? "" : ", then ") + number_text(mps, "m/s");
  }
  return pass(seen + " set and reported as set");
}

// ------------------------------------------------------------ the vectors

// The global vector: speed 0 (its smallest step on the wire, 0.15 m/s, is
// more than a crawl) with a heading; the local vector: a crawl with a heading.
struct GlobalVector {
  using Set = msg::SetGlobalVector;
  using Query = msg::QueryGlobalVector;
  using Report = msg::ReportGlobalVector;
  static constexpr const char* kName = "global vector";
  static Set vector(double speed_mps, double heading_rad) {
    Set m;
    m.speed_mps = speed_mps;
    m.heading_rad = heading_rad;
    return m;
  }
  static Set moving(double heading_rad) { return vector(0, heading_rad); }
  static Query query() { return Query{{0x1F}}; }  // every field asked for
  static double speed(const Report& r) { return r.speed_mps.value_or(NAN); }
  static double heading(const Report& r) { return r.heading_rad.value_or(NAN); }
  static double set_speed(const Set& m) { return m.speed_mps.value_or(NAN); }
  static double set_heading(const Set& m) { return m.heading_rad.value_or(NAN); }
};

struct LocalVector {
  using Set = msg::SetLocalVector;
  using Query = msg::QueryLocalVector;
  using Report = msg::ReportLocalVector;
  static constexpr const char* kName = "local vector";
  static Set vector(double speed_mps, double heading_rad) {
    Set m;
    m.speed_mps = speed_mps;
    m.heading_rad = heading_rad;
    return m;
  }
  static Set moving(double heading_rad) { return vector(kCrawlMps, heading_rad); }
  static Query query() { return Query{}; }
  static double speed(const Report& r) { return r.speed_mps; }
  static double heading(const Report& r) { return r.heading_rad; }
  static double set_speed(const Set& m) { return m.speed_mps; }
  static double set_heading(const Set& m) { return m.heading_rad; }
};

// The value `m` has once through the wire (what an exact echo reports).
template <class M>
M on_the_wire(const M& m) {
  M decoded{};
  const auto bytes = body_bytes(m);
  if (!wire::decode_payload_into(bytes, decoded, wire::Dialect::ra, 0)) return m;
  return decoded;
}

template <class V>
struct VectorDriver {
  static std::string not_applicable(const ComponentUnderTest& component) {
    for (const std::uint16_t code : {V::Set::code, V::Query::code})
      if (auto why = unless_accepts_code(component, code); !why.empty()) return why;
    return {};
  }

  // Speed 0 and Standby when the case ends, however it ends: sent while the
  // runner still controls it (declared after its ControlHeld).
  class StopVectorOnExit {
   public:
    StopVectorOnExit(CaseContext& c, double heading_rad) : c_(c), heading_rad_(heading_rad) {}
    ~StopVectorOnExit() {
      send(c_, V::vector(0, heading_rad_));
      send(c_, msg::Standby{});
    }
    StopVectorOnExit(const StopVectorOnExit&) = delete;
    StopVectorOnExit& operator=(const StopVectorOnExit&) = delete;

   private:
    CaseContext& c_;
    double heading_rad_;
  };

  static std::string vector_text(double speed, double heading) {
    return number_text(speed, "m/s") + " heading " + number_text(heading, "rad");
  }

  // Set Vector (executed in Ready only) from its controller is what Report
  // Vector says: speed and heading as on the wire.
  static CaseOutcome echo(CaseContext& c) {
    auto state = state_after_initialising(c);
    if (!state) return fail(state.error().message());
    if (*state != msg::PrimaryStatus::ready) return skip("in " + state_text(*state) + ": a vector is set in Ready");
    constexpr double kHeadingRad = 0.5;
    ControlHeld control(c);
    if (!control.granted()) return skip("control not granted (" + control.why() + ")");
    StopVectorOnExit stop(c, kHeadingRad);
    const auto set = V::moving(kHeadingRad);
    send(c, set);
    auto report = ask<typename V::Report>(c, V::query());
    if (!report) return fail("after " + std::string(V::Set::name) + ", " + report.error().message());
    const auto want = on_the_wire(set);
    const double want_speed = V::set_speed(want), want_heading = V::set_heading(want);
    const double speed = V::speed(*report), heading = V::heading(*report);
    constexpr double kSame = 1e-9;  // both went through the same encoding
    if (!(std::fabs(speed - want_speed) <= kSame) || !(std::fabs(heading - want_heading) <= kSame))
      return fail(std::string(V::Set::name) + " " + vector_text(want_speed, want_heading) + " reported as " +
                  vector_text(speed, heading));
    return pass(std::string(V::kName) + " " + vector_text(speed, heading) + " set and reported; then speed 0 and Standby");
  }

  // Set Vector from a non-controller is not executed: its report does not
  // change (no report before and after is as good).
  static CaseOutcome non_controller_ignored(CaseContext& c) {
    auto state = state_after_initialising(c);
    if (!state) return fail(state.error().message());
    if (*state != msg::PrimaryStatus::ready)
      return skip("in " + state_text(*state) + ": outside Ready no vector is executed, whoever sends it");
    auto controller = current_controller(c);
    if (!controller) return fail(controller.error().message());
    if (*controller == c.session.self()) return skip("the runner controls it");
    auto before = ask<typename V::Report>(c, V::query());
    const double heading = before && std::fabs(V::heading(*before) - 1.0) < 0.01 ? 1.5 : 1.0;
    send(c, V::moving(heading));
    auto after = ask<typename V::Report>(c, V::query());
    const bool changed = after && (!before || !(*after == *before));
    if (changed) {
      // Stopped again: speed 0 and Standby from its controller, or Standby alone.
      ControlHeld control(c);
      StopVectorOnExit stop(c, heading);
      return fail(std::string(V::Set::name) + " from a non-controller (controller " + controller->to_string() +
                  ") executed: reported " + vector_text(V::speed(*after), V::heading(*after)) +
                  "; stopped again with speed 0 and Standby");
    }
    return pass(std::string(V::Set::name) + " from a non-controller: " +
                (after ? "report unchanged" : "no report before or after"));
  }
};

using GlobalWaypointDriver = ListDriver<GlobalWaypoints>;
using LocalWaypointDriver = ListDriver<LocalWaypoints>;
using GlobalPathSegmentDriver = ListDriver<GlobalPathSegments>;
using LocalPathSegmentDriver = ListDriver<LocalPathSegments>;
using GlobalVectorDriver = VectorDriver<GlobalVector>;
using LocalVectorDriver = VectorDriver<LocalVector>;

constexpr const char* kControlReference =
    "Part 3, Code 000Dh Request Component Control (commands are the controller's)";

}  // namespace

std::span<const ConformanceCase> mobility_driver_cases() {
  static const std::vector<ConformanceCase> list{
      {"mobility.global_vector.non_controller_ignored", "Set Global Vector from a non-controller is never executed",
       "Part 3, Code 0407h Set Global Vector, Code 4407h Report Global Vector; Code 000Dh Request Component Control",
       GlobalVectorDriver::not_applicable, GlobalVectorDriver::non_controller_ignored},
      {"mobility.global_vector.echo", "its controller's Set Global Vector is reported by Report Global Vector",
       "Part 3, Code 0407h Set Global Vector, Code 4407h Report Global Vector (the current commanded vector)",
       GlobalVectorDriver::not_applicable, GlobalVectorDriver::echo},
      {"mobility.local_vector.non_controller_ignored", "Set Local Vector from a non-controller is never executed",
       "Part 3, Code 0408h Set Local Vector, Code 4408h Report Local Vector; Code 000Dh Request Component Control",
       LocalVectorDriver::not_applicable, LocalVectorDriver::non_controller_ignored},
      {"mobility.local_vector.echo", "its controller's Set Local Vector is reported by Report Local Vector",
       "Part 3, Code 0408h Set Local Vector, Code 4408h Report Local Vector (the current commanded vector)",
       LocalVectorDriver::not_applicable, LocalVectorDriver::echo},
      {"mobility.travel_speed.echo", "its controller's Set Travel Speed is reported by Report Travel Speed",
       "Part 3, Code 040Ah Set Travel Speed, Code 440Ah Report Travel Speed (the commanded travel speed)",
       unless_travel_speed, travel_speed_echo},
      {"mobility.global_waypoint.count_and_echo",
       "waypoints count from 0; Report Global Waypoint is each as set, Report Waypoint Count the number loaded",
       "Part 3, Code 040Ch Set Global Waypoint (numbered from zero, each next one plus one), Code 440Bh Report "
       "Waypoint Count, Code 440Ch Report Global Waypoint (identical to Set Global Waypoint)",
       GlobalWaypointDriver::not_applicable, GlobalWaypointDriver::count_and_echo},
      {"mobility.global_waypoint.numbering",
       "waypoint 0 starts a new list; a number past the end is refused",
       "Part 3, Code 040Ch Set Global Waypoint (the waypoint number starts at zero, incremented by one for each "
       "additional waypoint)",
       GlobalWaypointDriver::not_applicable, GlobalWaypointDriver::numbering},
      {"mobility.global_waypoint.non_controller_ignored",
       "Set Global Waypoint and Set Travel Speed from a non-controller are never executed",
       kControlReference, GlobalWaypointDriver::not_applicable, GlobalWaypointDriver::non_controller_ignored},
      {"mobility.local_waypoint.count_and_echo",
       "waypoints count from 0; Report Local Waypoint is each as set, Report Waypoint Count the number loaded",
       "Part 3, Code 040Dh Set Local Waypoint (numbered from zero, each next one plus one), Code 440Bh Report "
       "Waypoint Count, Code 440Dh Report Local Waypoint (identical to Set Local Waypoint)",
       LocalWaypointDriver::not_applicable, LocalWaypointDriver::count_and_echo},
      {"mobility.local_waypoint.numbering", "waypoint 0 starts a new list; a number past the end is refused",
       "Part 3, Code 040Dh Set Local Waypoint (the waypoint number starts at zero, incremented by one for each "
       "additional waypoint)",
       LocalWaypointDriver::not_applicable, LocalWaypointDriver::numbering},
      {"mobility.local_waypoint.non_controller_ignored",
       "Set Local Waypoint and Set Travel Speed from a non-controller are never executed", kControlReference,
       LocalWaypointDriver::not_applicable, LocalWaypointDriver::non_controller_ignored},
      {"mobility.global_path_segment.count_and_echo",
       "path segments count from 0; Report Global Path Segment is each as set, Report Path Segment Count the "
       "number loaded",
       "Part 3, Code 040Fh Set Global Path Segment (numbered from zero, each next one plus one), Code 440Eh Report "
       "Path Segment Count, Code 440Fh Report Global Path Segment (identical to Set Global Path Segment)",
       GlobalPathSegmentDriver::not_applicable, GlobalPathSegmentDriver::count_and_echo},
      {"mobility.global_path_segment.numbering", "path segment 0 starts a new list; a number past the end is refused",
       "Part 3, Code 040Fh Set Global Path Segment (the path segment number starts at zero, incremented by one for "
       "each additional path segment)",
       GlobalPathSegmentDriver::not_applicable, GlobalPathSegmentDriver::numbering},
      {"mobility.global_path_segment.non_controller_ignored",
       "Set Global Path Segment and Set Travel Speed from a non-controller are never executed", kControlReference,
       GlobalPathSegmentDriver::not_applicable, GlobalPathSegmentDriver::non_controller_ignored},
      {"mobility.local_path_segment.count_and_echo",
       "path segments count from 0; Report Local Path Segment is each as set, Report Path Segment Count the number "
       "loaded",
       "Part 3, Code 0410h Set Local Path Segment (numbered from zero, each next one plus one), Code 440Eh Report "
       "Path Segment Count, Code 4410h Report Local Path Segment (identical to Set Local Path Segment)",
       LocalPathSegmentDriver::not_applicable, LocalPathSegmentDriver::count_and_echo},
      {"mobility.local_path_segment.numbering", "path segment 0 starts a new list; a number past the end is refused",
       "Part 3, Code 0410h Set Local Path Segment (the path segment number starts at zero, incremented by one for "
       "each additional path segment)",
       LocalPathSegmentDriver::not_applicable, LocalPathSegmentDriver::numbering},
      {"mobility.local_path_segment.non_controller_ignored",
       "Set Local Path Segment and Set Travel Speed from a non-controller are never executed", kControlReference,
       LocalPathSegmentDriver::not_applicable, LocalPathSegmentDriver::non_controller_ignored},
  };
  return list;
}

}  // namespace jaus::conform
