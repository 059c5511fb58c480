// What the conformance tests share: the runner's session on loopback, a run
// of the cases on one component as jaus-conform runs them, its lines (as
// jaus-conform prints them) for a failed expectation, and one case's result
// by id.
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
#include "target_node.hpp"

namespace jaus::conform::test {

inline std::string describe(const std::vector<CaseResult>& results) {
  std::string out;
  for (const auto& r : results) out += case_line(r) + "\n";
  return out;
}

// The runner's session: on loopback (an ephemeral port), to the nodes at `to`.
inline Expected<std::unique_ptr<ocu::OcuSession>> open_session(boost::asio::io_context& io,
                                                               std::vector<transport::Ipv4Endpoint> to,
                                                               std::optional<Address> self = std::nullopt) {
  ocu::SessionOptions options;
  if (self) options.self = *self;
  options.to = std::move(to);
  options.bind = transport::Ipv4Endpoint{jausctl::test::kLoopback, 0};
  return ocu::OcuSession::open(options, &io);
}

// Learns the component at `address` and runs the cases `options` select on
// it; a component that cannot be learnt is a test failure, with no results.
inline std::vector<CaseResult> run_on(ocu::OcuSession& session, const Address& address, RunOptions options = {}) {
  auto component = learn_component(session, address, nullptr, std::chrono::seconds(1));
  if (!component) {
    ADD_FAILURE() << address.to_string() << ": " << component.error().message();
    return {};
  }
  return run_cases(session, *component, all_cases(), options);
}

inline const CaseResult* result_of(const std::vector<CaseResult>& results, std::string_view id) {
  for (const auto& r : results)
    if (r.test_case->id == id) return &r;
  return nullptr;
}

}  // namespace jaus::conform::test
