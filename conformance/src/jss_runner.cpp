// The JSS profile's runner: learns the components of a JSS node by JSS
// discovery, picks the cases that apply to each (by the services it lists),
// runs them one after another and keeps every result with its exchange, in
// the RA profiles' CaseResult so the reports are the same.
#include <algorithm>

#include "jaus/conform/jss_case.hpp"
#include "case_loop.hpp"
#include "jaus/jss/all.hpp"

namespace jaus::conform {

bool JssComponentUnderTest::has(std::string_view service) const {
  return std::any_of(services.begin(), services.end(), [&](const ocu::JssService& s) {
    if (s.uri == service) return true;
    const auto colon = s.uri.rfind(':');
    return colon != std::string::npos && std::string_view(s.uri).substr(colon + 1) == service;
  });
}

jss::JssId second_jss_client_id(const jss::JssId& runner) {
  return jss::JssId{runner.subsystem, static_cast<std::uint8_t>(runner.node % 254 + 1), runner.component};
}

Expected<ocu::JssSession*> JssCaseContext::second() {
  if (second_client) return second_client;
  if (!open_client)
    return unexpected(make_error(ErrorCode::invalid_argument, "a second client: the run was given no way to open one"));
  auto opened = open_client(second_jss_client_id(session.self()));
  if (!opened) return unexpected(make_error(opened.error().code, "a second client: " + opened.error().message()));
  second_client = *opened;
  second_recorder =
      detail::record_from(*second_client, target(), session.clock(), started, exchange, /*second=*/true);
  // One round trip first: a node verifies a new endpoint (the amplification
  // guard's challenge) before it sends it more than replies, and a case's
  // first exchange may be a Reject Control it must hear.
  (void)second_client->request_contents(target(), jss::encode_contents(jss::msg::QueryHeartbeatPulse{}),
                                        {jss::msg::ReportHeartbeatPulse::code}, reply_timeout);
  second_client->run_for(std::chrono::milliseconds(100));
  return second_client;
}

JssCaseContext::~JssCaseContext() {
  if (second_client) second_client->unlisten(second_recorder);
}

std::vector<const JssConformanceCase*> all_jss_cases() {
  std::vector<const JssConformanceCase*> all;
  for (auto suite : {jss_core_cases(), jss_mobility_cases()})
    for (const auto& c : suite) all.push_back(&c);
  return all;
}

std::vector<JssComponentUnderTest> components_of(const ocu::JssSystem& system) {
  std::vector<JssComponentUnderTest> components;
  for (const auto& subsystem : system.subsystems)
    for (const auto& node : subsystem.nodes)
      for (const auto& component : node.components)
        components.push_back(
            JssComponentUnderTest{component.id, component.name, component.services, subsystem.services_listed});
  std::sort(components.begin(), components.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return components;
}

Expected<std::vector<JssComponentUnderTest>> discover_jss_components(ocu::JssSession& session, rt::Duration wait,
                                                                     rt::Duration reply_timeout) {
  ocu::JssDiscoveryOptions options;
  options.timeout = wait;
  // A node that is up answers at once; a second try within the wait catches a lost datagram.
  options.identification_period = std::min<rt::Duration>(std::chrono::seconds(1), wait);
  options.query_timeout = reply_timeout;
  auto system = ocu::discover_jss(session, options);
  if (!system) return unexpected(system.error());
  return components_of(*system);
}

std::vector<CaseResult> run_jss_cases(ocu::JssSession& session, const JssComponentUnderTest& component,
                                      const std::vector<JssComponentUnderTest>& node_components,
                                      const std::vector<const JssConformanceCase*>& cases, const RunOptions& options,
                                      const JssClientOpener& open_client, const ResultListener& on_result) {
  const CaseResult blank{nullptr, Address{}, component.name, {}, {}, {}, component.id};
  const auto run_case = [&](const JssConformanceCase& test_case, CaseResult& result) {
    JssCaseContext context{session, component, options.reply_timeout, {}, session.clock().now(), open_client};
    context.node_components = &node_components;
    detail::run_recorded(session, context, component.id, test_case, result);
  };
  return detail::run_each_case(session, cases, component, blank, options, on_result, run_case);
}

}  // namespace jaus::conform
