// Runs conformance cases against components on the network: learns each
// component (identification, services), picks the cases that apply, runs
// them one after another and keeps every result with its exchange.
#pragma once

#include <string>
#include <vector>

#include "jaus/conform/conformance_case.hpp"
#include "jaus/conform/ocu_factory.hpp"
#include "jaus/ocu/discovery.hpp"

namespace jaus::conform {

struct RunOptions {
  Profile profile = Profile::ra;
  rt::Duration reply_timeout = std::chrono::seconds(1);
  // Runs only the cases whose id contains this text ("control.", "core.status");
  // empty: every case.
  std::string only;
  // Leaves out the cases whose id contains this text (a slow case already
  // run elsewhere); empty: none.
  std::string skip;
  // Where the cases' other OCUs come from. Null: on UDP beside the session
  // (jaus-conform's); an attached session then has none, and the cases that
  // need a second requester fail saying so.
  OcuFactory* ocus = nullptr;
};

struct CaseResult;
// Hears each result as soon as its case ends (the terminal's lines).
using ResultListener = std::function<void(const CaseResult&)>;

struct CaseResult {
  const CaseDescription* test_case = nullptr;
  Address component;
  std::string component_name;
  CaseOutcome outcome;
  rt::Duration took{};
  std::vector<Exchanged> exchange;
  // A JSS component (--profile jss): its JSS ID names it instead of `component`.
  std::optional<jss::JssId> jss_component{};

  // "1.1.33.1" (RA) or "1.1.33" (JSS).
  std::string component_text() const { return jss_component ? jss_component->to_string() : component.to_string(); }
};

struct RunReport {
  std::string node;  // what was tested, as the user named it ("127.0.0.1:3794")
  Profile profile = Profile::ra;
  std::vector<CaseResult> results;

  std::size_t count(Verdict verdict) const;
  // Every case that applied passed (and at least one ran).
  bool passed() const { return count(Verdict::fail) == 0 && count(Verdict::pass) > 0; }
};

// Asks `address` for its identification and services (falling back on what
// `discovery` learnt from its node manager). Fails when it answers nothing.
Expected<ComponentUnderTest> learn_component(ocu::OcuSession& session, const Address& address,
                                             const ocu::Discovery* discovery, rt::Duration reply_timeout);

// The components discovery found, in address order (the OCU's own left out).
std::vector<Address> discovered_components(const ocu::Discovery& discovery);

// Runs `cases` against `component`: a case that does not apply is skipped
// with its reason; one filtered out by `options.only` or `options.skip` is left out.
std::vector<CaseResult> run_cases(ocu::OcuSession& session, const ComponentUnderTest& component,
                                  const std::vector<const ConformanceCase*>& cases, const RunOptions& options,
                                  const ResultListener& on_result = {});

}  // namespace jaus::conform
