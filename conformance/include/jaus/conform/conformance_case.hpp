// One conformance check: what the RA requires of a component, asked of it
// over the network through an OCU session, with a verdict, why, and the
// messages exchanged. Cases are grouped in suites (core, control, service
// connections, ...); each says which components it applies to, so that the
// runner can test any node, ours or another implementation's.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/core/header.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::conform {

enum class Verdict { pass, fail, skip };
std::string_view to_string(Verdict verdict);

// `ra` checks the RA as written; `openjaus` accepts the documented quirks of
// the common RA 3.3 implementation (docs/conformance.md lists them), so a
// team testing a node built on it sees only real differences; `jss` runs the
// SAE JAUS (AS5710 core, AS6009 mobility) cases over AS5669A instead
// (jss_case.hpp).
enum class Profile { ra, openjaus, jss };
std::string_view to_string(Profile profile);
std::optional<Profile> parse_profile(std::string_view text);

// What the runner knows of a component before testing it: its address, its
// name (Report Identification) and what it says it accepts and provides
// (its own Report Services, or its node manager's entry for it).
struct ComponentUnderTest {
  Address address;
  std::string name;
  std::set<std::uint16_t> inputs;                  // message codes it accepts
  std::map<std::uint16_t, std::uint32_t> outputs;  // report codes it provides on service connections -> presence
  bool services_known = false;                     // it answered Query Services (or its node manager did)

  bool accepts(std::uint16_t code) const { return inputs.count(code) != 0; }
  bool provides(std::uint16_t code) const { return outputs.count(code) != 0; }
};

// One message of a case's exchange with the component, for the report.
struct Exchanged {
  bool sent = false;  // by the runner; else received by it
  Header header;
  std::vector<std::uint8_t> payload;
  rt::Duration at{};  // since the case started
  bool second = false;  // by or to the runner's second OCU (CaseContext::second())
  // Set for a JSS message (--profile jss): the peer's JSS ID (the destination
  // when sent, the source when received); header.command_code holds the JSS
  // message ID and payload the body after it.
  std::optional<jss::JssId> jss_peer{};
};

struct CaseOutcome {
  Verdict verdict = Verdict::fail;
  std::string detail;  // one line: what was seen ("Report Identification type 4, 'communicator'")
};

struct SecondOcu;  // runner.cpp
class OcuFactory;  // ocu_factory.hpp

// The runner's second OCU: its own node (the runner's node ID + 1, so
// 254.2.40.1 beside 254.1.40.1: one node ID on two ports would look like a
// spoofed claim), the same peers and dialect, opened by the run's OcuFactory.
Address second_ocu_address(const Address& runner);

// What a case works with: the session, the component under test, the
// profile, the budget for every reply it waits for, the exchange so far, and
// where other OCUs come from.
struct CaseContext {
  ocu::OcuSession& session;
  const ComponentUnderTest& component;
  Profile profile = Profile::ra;
  rt::Duration reply_timeout = std::chrono::seconds(1);
  std::vector<Exchanged> exchange;
  rt::TimePoint started{};
  OcuFactory* ocus = nullptr;  // null: no second OCU can be opened
  std::shared_ptr<SecondOcu> second_ocu{};  // opened by second(), closed when the case ends

  const Address& target() const { return component.address; }

  // A second requester for the cases that need two (takeover, emergency
  // holders): opened on first use, its messages recorded in the exchange.
  // After silence_second(), the next call opens a fresh one at the same
  // address (to clean up what the silent one left).
  Expected<ocu::OcuSession*> second();
  // The second OCU falls silent: it neither sends (no heartbeats, no
  // answers to liveness queries) nor answers; what still
  // reaches it is heard and recorded (second, received), never answered.
  Expected<void> silence_second();
};

// What a report says of a case: its id, title and where the rule is written.
struct CaseDescription {
  std::string_view id;         // stable, for reports and --only: "core.identification"
  std::string_view title;      // what the RA requires, in one line
  std::string_view reference;  // where it says so: "Part 3 3.2.3 Query Identification", "docs/wire-format.md: Liveness"
};

// One case, of either profile: RA cases run on an OCU session against a
// component known by its address (ConformanceCase), JSS cases on a JSS
// session against one known by its JSS ID and services (JssConformanceCase,
// jss_case.hpp). The runner loop, the recorder and the reports are the same.
template <class Component, class Context>
struct Case : CaseDescription {
  using NotApplicable = std::function<std::string(const Component&)>;
  using Run = std::function<CaseOutcome(Context&)>;
  // (A constructor, not an aggregate: the suites' lists stay flat,
  // {"id", "title", "reference", not_applicable, run}.)
  Case(std::string_view case_id, std::string_view case_title, std::string_view case_reference,
       NotApplicable applies_unless, Run check)
      : CaseDescription{case_id, case_title, case_reference},
        not_applicable(std::move(applies_unless)),
        run(std::move(check)) {}

  // Why the case does not apply to a component (it is then skipped with that
  // reason); empty when it applies. Null: applies to every component.
  NotApplicable not_applicable;
  Run run;
};

using ConformanceCase = Case<ComponentUnderTest, CaseContext>;

// The suites, each in its own file (src/<suite>_cases.cpp).
std::span<const ConformanceCase> core_cases();                // every component: core queries and states
std::span<const ConformanceCase> control_cases();             // the control matrix
std::span<const ConformanceCase> service_connection_cases();  // components that provide reports
std::span<const ConformanceCase> robustness_cases();          // every component: what it cannot use
std::span<const ConformanceCase> discovery_cases();           // node managers: their discovery reports agree
std::span<const ConformanceCase> primitive_driver_cases();    // components that take Set Wrench Effort
std::span<const ConformanceCase> sensor_cases();              // pose and velocity state sensors
std::span<const ConformanceCase> visual_sensor_cases();       // cameras: selection, formats, images
std::span<const ConformanceCase> manipulator_cases();         // joint counts, refusals, hold on stop
std::span<const ConformanceCase> mobility_driver_cases();     // vector, waypoint and path segment drivers
// Every case of every suite, in order.
std::vector<const ConformanceCase*> all_cases();

}  // namespace jaus::conform
