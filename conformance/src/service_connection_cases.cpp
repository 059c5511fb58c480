// The service connection cases, for components that provide reports (their
// Report Services outputs): create and confirm, the reports that follow
// (SC flag, sequence numbers, presence vector, rate), termination, and the
// answers to what cannot be served. Each terminates what it created.
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <optional>

#include "case_support.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

std::string unless_it_provides_reports(const ComponentUnderTest& component) {
  if (!component.services_known) return "its services are unknown (no Report Services)";
  return component.outputs.empty() ? "it provides no reports on service connections" : std::string();
}

// Presence vector widths of the reports this suite checks the presence of;
// others are checked for everything else.
std::size_t presence_bytes(std::uint16_t code) {
  switch (code) {
    case msg::ReportGlobalPose::code:
    case msg::ReportLocalPose::code:
    case msg::ReportVelocityState::code:
    case msg::ReportWrenchEffort::code:
      return 2;
    default:
      return 0;
  }
}

// The report the cases subscribe to: one whose presence vector they can
// read if there is one, else the first.
std::pair<std::uint16_t, std::uint32_t> chosen_report(const ComponentUnderTest& component) {
  for (const auto& [code, presence] : component.outputs)
    if (presence_bytes(code) != 0 && presence != 0) return {code, presence};
  return *component.outputs.begin();
}

struct Created {
  msg::ConfirmServiceConnection confirm;
  std::uint16_t code = 0;
};

Expected<Created> create(CaseContext& c, std::uint16_t code, double rate_hz, std::uint32_t presence) {
  msg::CreateServiceConnection m;
  m.command_code = code;
  m.periodic_rate_hz = rate_hz;
  m.presence_vector = presence;
  auto confirm = ask<msg::ConfirmServiceConnection>(c, m);
  if (!confirm) return unexpected(confirm.error());
  return Created{*confirm, code};
}

// The same, for the cases that need the connection: one refused is the
// component's failure ("refused: ..."), as one that gets no answer is.
Expected<Created> create_accepted(CaseContext& c, std::uint16_t code, double rate_hz, std::uint32_t presence) {
  auto created = create(c, code, rate_hz, presence);
  if (created && created->confirm.response_code != msg::sc_response::kCreated)
    return unexpected(make_error(ErrorCode::refused,
                                 "refused: " + ocu::service_connection_response_text(created->confirm.response_code)));
  return created;
}

void terminate(CaseContext& c, const Created& created) {
  if (created.confirm.response_code == msg::sc_response::kCreated)
    send(c, msg::TerminateServiceConnection{{created.code, created.confirm.instance_id}});
}

// The reports with `code` that reach the runner within `window`.
std::vector<ocu::Received> collect_reports(CaseContext& c, std::uint16_t code, rt::Duration window) {
  std::vector<ocu::Received> reports;
  const auto listener = c.session.listen([&](const ocu::Received& r) {
    if (r.header.command_code == code && r.header.source == c.target()) reports.push_back(r);
  });
  c.session.run_for(window);
  c.session.unlisten(listener);
  return reports;
}

// A connection at 10 Hz that has sent a report (the cases that then see
// what ends or pauses the reports); terminated again when it has not.
Expected<Created> created_and_reporting(CaseContext& c, std::uint16_t code, std::uint32_t presence) {
  auto created = create_accepted(c, code, 10, presence);
  if (!created) return created;
  if (collect_reports(c, code, std::chrono::milliseconds(300)).empty()) {
    terminate(c, *created);
    return unexpected(make_error(ErrorCode::timeout, "no report in 0.3 s at 10 Hz"));
  }
  return created;
}

CaseOutcome create_and_confirm(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  auto created = create(c, code, 2, available);
  if (!created) return fail(created.error().message());
  terminate(c, *created);
  const auto& confirm = created->confirm;
  if (confirm.command_code != code)
    return fail("Confirm Service Connection names " + ocu::code_text(confirm.command_code) + ", asked " +
                ocu::code_text(code));
  if (confirm.response_code != msg::sc_response::kCreated)
    return fail("refused: " + ocu::service_connection_response_text(confirm.response_code));
  // The confirmed rate is at most the requested one (Part 3: "less than the
  // requested rate" when the provider cannot keep it), and not zero.
  if (!(confirm.confirmed_rate_hz > 0) || confirm.confirmed_rate_hz > 2 + 0.02)
    return fail("confirmed rate " + ocu::hz_text(confirm.confirmed_rate_hz) + " for 2 Hz asked");
  return pass(ocu::code_text(code) + " instance " + std::to_string(confirm.instance_id) + " at " +
              ocu::hz_text(confirm.confirmed_rate_hz));
}

// Reports on an SC carry the SC flag and numbers that go up by one; their
// presence vector is the requested AND the available one.
CaseOutcome reports_flagged_numbered_and_masked(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  const std::size_t width = presence_bytes(code);
  // One field the component has and, where there is one, one it has not: a
  // component that echoes the request instead of masking it shows.
  std::uint32_t requested = available & (~available + 1);
  const std::uint32_t defined = width >= 4 ? 0xFFFFFFFF : (1u << (8 * width)) - 1;
  if (const std::uint32_t missing = defined & ~available; missing != 0) requested |= missing & (~missing + 1);
  auto created = create_accepted(c, code, 10, requested);
  if (!created) return fail(created.error().message());
  const auto reports = collect_reports(c, code, std::chrono::seconds(1));
  terminate(c, *created);
  if (reports.size() < 3) return fail(std::to_string(reports.size()) + " reports in 1 s at 10 Hz");
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const Header& h = reports[i].header;
    if (!h.service_connection) return fail("report " + std::to_string(i + 1) + " lacks the SC flag");
    if (i > 0 && h.sequence != static_cast<std::uint16_t>(reports[i - 1].header.sequence + 1))
      return fail("sequence numbers " + std::to_string(reports[i - 1].header.sequence) + " then " +
                  std::to_string(h.sequence));
  }
  if (width == 0) return pass(std::to_string(reports.size()) + " reports, flagged and numbered in order");
  for (const auto& r : reports) {
    if (r.payload.size() < width) return fail("a report shorter than its presence vector");
    std::uint32_t presence = 0;
    for (std::size_t b = 0; b < width; ++b) presence |= static_cast<std::uint32_t>(r.payload[b]) << (8 * b);
    if (presence != (requested & available))
      return fail("presence vector 0x" + wire::detail::hex_u32(presence) + " for 0x" +
                  wire::detail::hex_u32(requested) + " asked and 0x" + wire::detail::hex_u32(available) + " available");
  }
  return pass(std::to_string(reports.size()) + " reports, flagged, numbered in order, presence 0x" +
              wire::detail::hex_u32(requested & available));
}

// The measured rate is the confirmed one, within what a network allows.
CaseOutcome rate(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  auto created = create_accepted(c, code, 20, available);
  if (!created) return fail(created.error().message());
  const double confirmed = created->confirm.confirmed_rate_hz;
  const auto reports = collect_reports(c, code, std::chrono::seconds(1));
  terminate(c, *created);
  const double expected = confirmed;
  // Half to one and a half times the confirmed count, plus the first report
  // (sent at once): timing on a real network, not a benchmark.
  if (reports.size() + 0.0 < expected * 0.5 || reports.size() + 0.0 > expected * 1.5 + 1)
    return fail(std::to_string(reports.size()) + " reports in 1 s at a confirmed " + ocu::hz_text(confirmed));
  return pass(std::to_string(reports.size()) + " reports in 1 s at a confirmed " + ocu::hz_text(confirmed));
}

// After Terminate Service Connection, reports stop.
CaseOutcome terminate_stops_reports(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  auto created = created_and_reporting(c, code, available);
  if (!created) return fail(created.error().message());
  terminate(c, *created);
  c.session.run_for(std::chrono::milliseconds(200));  // reports already on their way
  const auto after = collect_reports(c, code, std::chrono::milliseconds(500));
  std::size_t on_sc = 0;
  for (const auto& r : after) on_sc += r.header.service_connection;
  if (on_sc > 0) return fail(std::to_string(on_sc) + " reports in the half second after Terminate");
  return pass("no report after Terminate");
}

// Suspend Service Connection from its creator stops the reports ("the
// service provided on this connection shall be suspended"). Activate is not
// checked: Part 3 gives it "no effect if sent by Inform requesters", and a
// command service connection would make the runner a controller whose
// silence stops the platform.
CaseOutcome suspend_stops_reports(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  auto created = created_and_reporting(c, code, available);
  if (!created) return fail(created.error().message());
  send(c, msg::SuspendServiceConnection{{code, created->confirm.instance_id}});
  c.session.run_for(std::chrono::milliseconds(200));  // reports already on their way
  const auto after = collect_reports(c, code, std::chrono::milliseconds(500));
  terminate(c, *created);
  std::size_t on_sc = 0;
  for (const auto& r : after) on_sc += r.header.service_connection;
  if (on_sc > 0) return fail(std::to_string(on_sc) + " reports in the half second after Suspend");
  return pass("no report after Suspend; terminated");
}

// The slowest rate the limit case asks for: well above the RA's 0.0166 Hz
// (one wire step), so that no rounding makes it invalid, and slow enough
// that a few hundred connections send little.
constexpr double kSlowRateHz = 0.05;
// Instance IDs are one byte: a provider runs out of them at 256 connections
// of one report, so it must refuse by then.
constexpr std::size_t kMostInstances = 256;

// The `index`-th subset of `available`'s bits (the bits of `index` spread
// over those of `available`), as a presence vector.
std::uint32_t subset_of(std::uint32_t available, std::size_t index) {
  std::uint32_t presence = 0;
  for (std::uint32_t bit = 1; bit != 0 && index != 0; bit <<= 1) {
    if ((available & bit) == 0) continue;
    if (index & 1u) presence |= bit;
    index >>= 1;
  }
  return presence;
}

// Connections of one report, each with a presence vector of its own (so no
// two may share an instance), until the provider refuses: it must refuse
// with 4 ("refused due to internal component restrictions") by the time its
// instance IDs run out, and give every connection it creates an instance ID
// of its own.
CaseOutcome too_many_refused(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  const std::size_t subsets =
      std::popcount(available) >= 9 ? kMostInstances + 1 : std::size_t{1} << std::popcount(available);
  std::vector<Created> created;
  std::map<std::uint8_t, std::uint32_t> presence_of_instance;
  std::optional<CaseOutcome> outcome;
  for (std::size_t i = 0; i < subsets && !outcome; ++i) {
    const std::uint32_t presence = subset_of(available, i);
    auto made = create(c, code, kSlowRateHz, presence);
    if (!made) {
      outcome = fail("connection " + std::to_string(i + 1) + ": " + made.error().message());
      break;
    }
    const auto& confirm = made->confirm;
    if (confirm.response_code == msg::sc_response::kCreated) {
      created.push_back(*made);
      const auto [at, fresh] = presence_of_instance.emplace(confirm.instance_id, presence);
      if (!fresh)
        outcome = fail("instance " + std::to_string(confirm.instance_id) + " given to presence 0x" +
                       wire::detail::hex_u32(at->second) + " and to 0x" + wire::detail::hex_u32(presence) +
                       " (Part 3: one instance per code and presence vector)");
    } else if (confirm.response_code == msg::sc_response::kRefused) {
      outcome = pass(std::to_string(created.size()) + " connections of " + ocu::code_text(code) +
                     ", each its own instance, then refused with 4");
    } else {
      outcome = fail("connection " + std::to_string(i + 1) + " refused with " +
                     ocu::service_connection_response_text(confirm.response_code) + ", not 4");
    }
  }
  for (const auto& made : created) terminate(c, made);
  // (A 257th connection accepted would have shared an instance: failed above.)
  if (outcome) return *outcome;
  return skip(std::to_string(created.size()) + " connections created, each its own instance, with every presence " +
              "vector of its report: no limit reached");
}

// Activate Service Connection "has no effect if sent by Inform requesters"
// (Part 3): an inform connection its creator suspended stays suspended.
// (Activate of a command connection is not tried: it would make the runner a
// commander whose silence stops the platform.)
CaseOutcome activate_from_inform_requester_ignored(CaseContext& c) {
  const auto [code, available] = chosen_report(c.component);
  auto created = created_and_reporting(c, code, available);
  if (!created) return fail(created.error().message());
  const msg::ServiceConnectionRefBody id{code, created->confirm.instance_id};
  send(c, msg::SuspendServiceConnection{id});
  c.session.run_for(std::chrono::milliseconds(200));  // reports already on their way
  const auto suspended = collect_reports(c, code, std::chrono::milliseconds(300));
  if (!suspended.empty()) {
    terminate(c, *created);
    return skip("reports went on after Suspend (sc.suspend judges that): Activate cannot be told apart");
  }
  send(c, msg::ActivateServiceConnection{id});
  const auto after = collect_reports(c, code, std::chrono::milliseconds(500));
  terminate(c, *created);
  std::size_t on_sc = 0;
  for (const auto& r : after) on_sc += r.header.service_connection;
  if (on_sc > 0)
    return fail(std::to_string(on_sc) + " reports in the half second after Activate from the inform requester");
  return pass("suspended, and still suspended after Activate from the inform requester; terminated");
}

// What cannot be served is answered with the RA's response codes: a report
// it does not provide (6), a rate below the RA's slowest (5).
CaseOutcome refusals(CaseContext& c) {
  // A code in the report range that no RA message has: nothing provides it.
  constexpr std::uint16_t kNotProvided = 0x4FFE;
  auto unknown = create(c, kNotProvided, 1, 0);
  if (!unknown) return fail(unknown.error().message());
  terminate(c, *unknown);
  if (unknown->confirm.response_code == msg::sc_response::kCreated)
    return fail("created a service connection for " + ocu::code_text(kNotProvided) + ", which it does not provide");
  const auto [code, available] = chosen_report(c.component);
  auto too_slow = create(c, code, 0, available);
  if (!too_slow) return fail(too_slow.error().message());
  terminate(c, *too_slow);
  if (too_slow->confirm.response_code == msg::sc_response::kCreated)
    return fail("created a service connection at 0 Hz (the RA's slowest rate is 0.0166 Hz)");
  if (unknown->confirm.response_code != msg::sc_response::kCommandNotSupported)
    return fail("an unprovided report refused with " +
                ocu::service_connection_response_text(unknown->confirm.response_code) + ", not 6");
  if (too_slow->confirm.response_code != msg::sc_response::kInvalidParameters)
    return fail("0 Hz refused with " + ocu::service_connection_response_text(too_slow->confirm.response_code) +
                ", not 5");
  return pass("unprovided report: " + std::to_string(unknown->confirm.response_code) +
              ", 0 Hz: " + std::to_string(too_slow->confirm.response_code));
}

}  // namespace

std::span<const ConformanceCase> service_connection_cases() {
  static const std::vector<ConformanceCase> list{
      {"sc.create", "Create Service Connection for a report it provides is confirmed at most at the asked rate",
       "Part 3, Code 0008h Create Service Connection, Code 0009h Confirm Service Connection",
       unless_it_provides_reports, create_and_confirm},
      {"sc.reports", "reports carry the SC flag, sequence numbers up by one, the requested AND available presence",
       "Part 3, Code 0009h Confirm Service Connection; Part 2 header (SC flag, sequence number)",
       unless_it_provides_reports, reports_flagged_numbered_and_masked},
      {"sc.rate", "reports come at the confirmed rate", "Part 3, Code 0009h Confirm Service Connection",
       unless_it_provides_reports, rate},
      {"sc.terminate", "Terminate Service Connection ends the reports",
       "Part 3, Code 000Ch Terminate Service Connection", unless_it_provides_reports, terminate_stops_reports},
      {"sc.suspend", "Suspend Service Connection from its creator stops the reports",
       "Part 3, Code 000Bh Suspend Service Connection", unless_it_provides_reports, suspend_stops_reports},
      {"sc.refusals", "an unprovided report is refused with 6, a rate below 0.0166 Hz with 5",
       "Part 3, Code 0009h Confirm Service Connection (response codes)", unless_it_provides_reports, refusals},
      {"sc.too_many", "connections beyond what it can serve are refused with 4; each gets an instance of its own",
       "Part 3, Code 0009h Confirm Service Connection (instance ID, response code 4)", unless_it_provides_reports,
       too_many_refused},
      {"sc.activate_by_inform_requester",
       "Activate from the creator of an inform connection has no effect: a suspended one stays suspended",
       "Part 3, Code 000Ah Activate Service Connection", unless_it_provides_reports,
       activate_from_inform_requester_ignored},
  };
  return list;
}

}  // namespace jaus::conform
