#include "jaus/conform/conformance_case.hpp"

namespace jaus::conform {

std::string_view to_string(Verdict verdict) { return verdict == Verdict::pass ? "pass" : "fail"; }

std::vector<CaseResult> run_cases(ocu::OcuSession& session, const Address& target,
                                  std::span<const ConformanceCase> cases, rt::Duration reply_timeout) {
  std::vector<CaseResult> results;
  results.reserve(cases.size());
  for (const auto& c : cases) {
    if (session.interrupted()) {
      results.push_back({&c, CaseOutcome{Verdict::fail, "interrupted before it ran"}});
      continue;
    }
    CaseContext context{session, target, reply_timeout};
    results.push_back({&c, c.run(context)});
  }
  return results;
}

}  // namespace jaus::conform
