// What the conformance tests say of a run: its lines (as jaus-conform prints
// them) for a failed expectation, and one case's result by id.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"

namespace jaus::conform::test {

inline std::string describe(const std::vector<CaseResult>& results) {
  std::string out;
  for (const auto& r : results) out += case_line(r) + "\n";
  return out;
}

inline const CaseResult* result_of(const std::vector<CaseResult>& results, std::string_view id) {
  for (const auto& r : results)
    if (r.test_case->id == id) return &r;
  return nullptr;
}

}  // namespace jaus::conform::test
