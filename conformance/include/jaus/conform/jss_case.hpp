// The JSS profile (`jaus-conform --profile jss`): SAE JAUS conformance cases
// (AS5710 core services, AS6009 mobility services) asked of a JSS node over
// AS5669A through ocu::JssSession. A JSS component is known by its JSS ID and
// the service URIs discovery reports for it; each case says which service it
// applies to, so the runner tests any JSS node. Results are the RA profiles'
// (CaseResult, reports.hpp), named by JSS ID.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/conform/conformance_case.hpp"
#include "jaus/conform/runner.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/ocu/jss_discovery.hpp"
#include "jaus/ocu/jss_session.hpp"

namespace jaus::conform {

// What the runner knows of a JSS component before testing it.
struct JssComponentUnderTest {
  jss::JssId id;
  std::string name;                 // Report Identification type 4 ("" when it gave none)
  std::vector<ocu::JssService> services;  // its entry in Report Service List (or Report Services)
  bool services_known = false;

  // "urn:jaus:jss:core:AccessControl" or its last part, "AccessControl".
  bool has(std::string_view service) const;
};

// Where a case's second JSS client comes from (a second requester for
// preemption and emergencies held by two clients): on UDP beside the
// runner's session for jaus-conform, attached to a face in tests. One for
// the whole run, owned by the opener (a node learns a JSS ID's endpoint:
// a fresh port for every case would be a JSS ID moving between ports).
using JssClientOpener = std::function<Expected<ocu::JssSession*>(const jss::JssId& self)>;

// The runner's JSS ID: an operator subsystem beside jausctl's (200.1.1), so
// both can talk to one node at once.
inline constexpr jss::JssId kJssRunnerId{201, 1, 1};

// The runner's second client: its own JSS ID (the runner's node + 1).
jss::JssId second_jss_client_id(const jss::JssId& runner);

struct JssCaseContext {
  ocu::JssSession& session;
  const JssComponentUnderTest& component;
  rt::Duration reply_timeout = std::chrono::seconds(1);
  std::vector<Exchanged> exchange;
  rt::TimePoint started{};
  JssClientOpener open_client;  // empty: no second client can be opened
  ocu::JssSession* second_client = nullptr;
  ocu::JssSession::ListenerId second_recorder = 0;
  // Every component the runner knows on the node (to find, e.g., the local
  // pose sensor beside a waypoint driver).
  const std::vector<JssComponentUnderTest>* node_components = nullptr;

  const jss::JssId& target() const { return component.id; }
  // Opened on first use, its messages from the target recorded.
  Expected<ocu::JssSession*> second();
  ~JssCaseContext();
};

using JssConformanceCase = Case<JssComponentUnderTest, JssCaseContext>;

// The suites (src/jss_<suite>_cases.cpp).
std::span<const JssConformanceCase> jss_core_cases();      // discovery, access control, management, liveness, events
std::span<const JssConformanceCase> jss_mobility_cases();  // the mobility services a component lists
std::vector<const JssConformanceCase*> all_jss_cases();

// The components of every JSS subsystem that answers (ocu::discover_jss:
// Query Identification, then its configuration, service list and names),
// in ID order. Errors: no subsystem answered within `wait`, interrupted.
Expected<std::vector<JssComponentUnderTest>> discover_jss_components(ocu::JssSession& session, rt::Duration wait,
                                                                     rt::Duration reply_timeout);
// The same, of a system already discovered.
std::vector<JssComponentUnderTest> components_of(const ocu::JssSystem& system);

std::vector<CaseResult> run_jss_cases(ocu::JssSession& session, const JssComponentUnderTest& component,
                                      const std::vector<JssComponentUnderTest>& node_components,
                                      const std::vector<const JssConformanceCase*>& cases, const RunOptions& options,
                                      const JssClientOpener& open_client, const ResultListener& on_result = {});

}  // namespace jaus::conform
