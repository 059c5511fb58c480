// One conformance check: what the RA requires of a component, asked of it
// over the network through an OCU session, with a verdict and why.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::conform {

enum class Verdict { pass, fail };
std::string_view to_string(Verdict verdict);

struct CaseOutcome {
  Verdict verdict = Verdict::fail;
  std::string detail;  // one line: what was seen ("Report Identification type 4, 'communicator'")
};

// Each case gets the session and the component under test, and this budget
// for every reply it waits for.
struct CaseContext {
  ocu::OcuSession& session;
  Address target;
  rt::Duration reply_timeout = std::chrono::seconds(1);
};

struct ConformanceCase {
  std::string_view id;     // stable, for reports and filters: "core.identification"
  std::string_view title;  // what the RA requires, in one line
  std::function<CaseOutcome(CaseContext&)> run;
};

// Cases every RA 3.x component must pass (core messages and discovery).
std::span<const ConformanceCase> core_cases();

struct CaseResult {
  const ConformanceCase* test_case = nullptr;
  CaseOutcome outcome;
};

// Runs `cases` in order against `target`; a case that cannot run (no reply,
// interrupted) fails with the reason.
std::vector<CaseResult> run_cases(ocu::OcuSession& session, const Address& target,
                                  std::span<const ConformanceCase> cases,
                                  rt::Duration reply_timeout = std::chrono::seconds(1));

}  // namespace jaus::conform
