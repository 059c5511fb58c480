// A browser test needs Chromium: without it the test is skipped on a
// developer's machine, and fails in CI (CI=true), where setup.sh installs it.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

#include "cdp_client.hpp"

namespace jaus::test::browser {

inline bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string_view(ci) == "true";
}

}  // namespace jaus::test::browser

#define JAUS_REQUIRE_CHROMIUM()                                                                    \
  do {                                                                                             \
    if (!::jaus::test::browser::find_chromium()) {                                                 \
      if (::jaus::test::browser::in_ci()) FAIL() << "Chromium is not installed (scripts/setup.sh)"; \
      GTEST_SKIP() << "Chromium is not installed (apt-get install chromium): skipped outside CI";   \
    }                                                                                              \
  } while (false)
