// What the conformance tests share: the network they run on (the nodes, the
// runner's session and its other OCUs on one memory network under virtual
// time, so a case's waits take no real time), a run of the cases on one
// component as jaus-conform runs them, its lines (as jaus-conform prints
// them) for a failed expectation, and one case's result by id.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "memory_ocu.hpp"
#include "memory_ocus.hpp"

namespace jaus::conform::test {

inline std::string describe(const std::vector<CaseResult>& results) {
  std::string out;
  for (const auto& r : results) out += case_line(r) + "\n";
  return out;
}

class VirtualNetwork {
 public:
  // A runner's session (254.1.40.1 unless `self`).
  Expected<std::unique_ptr<ocu::OcuSession>> open_session(std::optional<Address> self = std::nullopt) {
    ocu::SessionOptions options;
    if (self) options.self = *self;
    return test_support::attach_ocu(time, network, options);
  }

  // `options` with the other OCUs on this network.
  RunOptions on_this_network(RunOptions options) {
    options.ocus = &ocus;
    return options;
  }

  // Learns the component at `address` and runs the cases `options` select on
  // it; a component that cannot be learnt is a test failure, with no results.
  std::vector<CaseResult> run_on(ocu::OcuSession& session, const Address& address, RunOptions options = {}) {
    auto component = learn_component(session, address, nullptr, std::chrono::seconds(1));
    if (!component) {
      ADD_FAILURE() << address.to_string() << ": " << component.error().message();
      return {};
    }
    return run_cases(session, *component, all_cases(), on_this_network(std::move(options)));
  }

  // Lets virtual time pass until `done` or `limit` of it.
  bool run_until(const std::function<bool()>& done, rt::Duration limit) {
    return testing::run_until(time, done, limit);
  }

  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time};
  MemoryOcus ocus{time, network};
};

inline const CaseResult* result_of(const std::vector<CaseResult>& results, std::string_view id) {
  for (const auto& r : results)
    if (r.test_case->id == id) return &r;
  return nullptr;
}

}  // namespace jaus::conform::test
