// What a run says: one line per case for the terminal, JUnit XML for CI
// systems, and a readable Markdown report with each case, its reference and,
// for failures, the messages exchanged.
#pragma once

#include <string>

#include "jaus/conform/runner.hpp"

namespace jaus::conform {

// "pass  1.1.33.1 core.status: primary status Ready"
std::string case_line(const CaseResult& result);
// "42 cases: 40 passed, 0 failed, 2 skipped"
std::string summary_line(const RunReport& report);

std::string junit_xml(const RunReport& report);
std::string markdown_report(const RunReport& report);

}  // namespace jaus::conform
