// What both profiles' runners share (runner.cpp for RA, jss_runner.cpp for
// JSS). The loop: the cases --only and --skip leave, in order; a case is
// failed as interrupted once the session is, skipped with its reason when it
// does not apply, else run by `run_case(test_case, result)` (which fills the
// outcome, the time it took and the exchange); each result is heard as soon
// as its case ends. The recorder: what the component under test sends the
// runner (or its second OCU or client), in the case's exchange.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "jaus/conform/jss_case.hpp"
#include "jaus/conform/runner.hpp"

namespace jaus::conform::detail {

// A message received from the component, as the report shows it: a JSS one
// with its message ID as the code and the body after it as the payload.
inline Exchanged received_record(const ocu::Received& r, rt::Duration at, bool second) {
  return Exchanged{false, r.header, r.payload, at, second};
}
inline Exchanged received_record(const ocu::JssReceived& r, rt::Duration at, bool second) {
  Exchanged e;
  e.header.command_code = r.message_id();
  if (r.contents.size() > 2) e.payload.assign(r.contents.begin() + 2, r.contents.end());
  e.at = at;
  e.second = second;
  e.jss_peer = r.source();
  return e;
}

// Records into `exchange` what `listening` (the runner's session, or its
// second OCU or client) hears from `component`, timed on `clock` since
// `started`. The listener's id, for unlisten().
template <class Session, class Peer>
auto record_from(Session& listening, const Peer& component, rt::Clock& clock, rt::TimePoint started,
                 std::vector<Exchanged>& exchange, bool second = false) {
  return listening.listen([&clock, &exchange, component, started, second](const auto& r) {
    if (r.source() == component) exchange.push_back(received_record(r, clock.now() - started, second));
  });
}

// Runs one case in `context` (a CaseContext or JssCaseContext, its clock
// started) and fills `result`: the outcome, the time it took and what was
// exchanged, with what `component` sent the runner meanwhile recorded.
template <class Session, class Context, class Peer, class Case>
void run_recorded(Session& session, Context& context, const Peer& component, const Case& test_case,
                  CaseResult& result) {
  const auto recorder = record_from(session, component, session.clock(), context.started, context.exchange);
  result.outcome = test_case.run(context);
  session.unlisten(recorder);
  result.took = session.clock().now() - context.started;
  result.exchange = std::move(context.exchange);
}

template <class Session, class Case, class Component, class RunCase>
std::vector<CaseResult> run_each_case(Session& session, const std::vector<const Case*>& cases,
                                      const Component& component, const CaseResult& blank, const RunOptions& options,
                                      const ResultListener& on_result, RunCase run_case) {
  std::vector<CaseResult> results;
  for (const Case* test_case : cases) {
    const std::string_view id = test_case->id;
    if (!options.only.empty() && id.find(options.only) == std::string_view::npos) continue;
    if (!options.skip.empty() && id.find(options.skip) != std::string_view::npos) continue;
    CaseResult result = blank;
    result.test_case = test_case;
    if (session.interrupted()) {
      result.outcome = {Verdict::fail, "interrupted before it ran"};
    } else if (std::string why = test_case->not_applicable ? test_case->not_applicable(component) : std::string();
               !why.empty()) {
      result.outcome = {Verdict::skip, "does not apply: " + why};
    } else {
      run_case(*test_case, result);
    }
    if (on_result) on_result(result);
    results.push_back(std::move(result));
  }
  return results;
}

}  // namespace jaus::conform::detail
