#include "jaus/conform/runner.hpp"

#include <algorithm>

#include "case_loop.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::conform {

std::string_view to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass:
      return "pass";
    case Verdict::fail:
      return "fail";
    case Verdict::skip:
      return "skip";
  }
  return "?";
}

std::string_view to_string(Profile profile) {
  switch (profile) {
    case Profile::ra:
      return "ra";
    case Profile::openjaus:
      return "openjaus";
    case Profile::jss:
      return "jss";
  }
  return "?";
}

std::optional<Profile> parse_profile(std::string_view text) {
  if (text == "ra") return Profile::ra;
  if (text == "openjaus") return Profile::openjaus;
  if (text == "jss") return Profile::jss;
  return std::nullopt;
}

std::vector<const ConformanceCase*> all_cases() {
  std::vector<const ConformanceCase*> all;
  for (auto suite : {core_cases(), control_cases(), service_connection_cases(), robustness_cases(), discovery_cases(),
                     primitive_driver_cases(), sensor_cases(), visual_sensor_cases(), manipulator_cases(),
                     mobility_driver_cases()})
    for (const auto& c : suite) all.push_back(&c);
  return all;
}

Address second_ocu_address(const Address& runner) {
  return Address{runner.subsystem, static_cast<std::uint8_t>(runner.node % 254 + 1), runner.component, runner.instance};
}

struct SecondOcu {
  std::unique_ptr<ocu::OcuSession> session;
  ocu::OcuSession::ListenerId recorder = 0;
  std::unique_ptr<DeafEndpoint> deaf;  // set when silenced

  ~SecondOcu() {
    deaf.reset();  // before the session it hears for
    if (session) session->unlisten(recorder);
  }
};

Expected<ocu::OcuSession*> CaseContext::second() {
  if (second_ocu && !second_ocu->deaf) return second_ocu->session.get();
  second_ocu.reset();  // a silenced one gives way to a fresh one at its address
  if (!ocus)
    return unexpected(make_error(ErrorCode::invalid_argument, "a second OCU: the run was given no way to open one"));
  ocu::SessionOptions options = session.options();
  options.self = second_ocu_address(session.self());
  auto opened = ocus->open(std::move(options));
  if (!opened) return unexpected(make_error(opened.error().code, "a second OCU: " + opened.error().message()));
  auto second = std::make_shared<SecondOcu>();
  second->session = std::move(*opened);
  second->recorder =
      detail::record_from(*second->session, target(), session.clock(), started, exchange, /*second=*/true);
  second_ocu = std::move(second);
  // One round trip first, as for a JSS client (JssCaseContext::second): a node
  // that verifies endpoints (jausd's transport.verify_endpoints) holds what
  // does not fit a new endpoint's byte budget until it answers a challenge,
  // and challenges it again at most once a second. A case's first exchange
  // may be a Reject Component Control the second OCU must hear within
  // reply_timeout (control.higher_authority_takes_over): held behind a
  // challenge on a loaded machine, it came too late. A reply larger than its
  // query gets the endpoint challenged and verified now; a node that does not
  // answer costs reply_timeout once.
  msg::QueryIdentification query;
  query.query_type = msg::identification::kComponent;
  (void)second_ocu->session->request(target(), query, {msg::ReportIdentification::code}, reply_timeout);
  return second_ocu->session.get();
}

Expected<void> CaseContext::silence_second() {
  if (!second_ocu || second_ocu->deaf)
    return unexpected(make_error(ErrorCode::invalid_argument, "no second OCU to silence"));
  auto deaf = ocus->silence(*second_ocu->session, [this](const PacketView& packet) {
    if (packet.header.source != target()) return;
    exchange.push_back(Exchanged{false,
                                 packet.header,
                                 {packet.payload.begin(), packet.payload.end()},
                                 session.clock().now() - started,
                                 true});
  });
  if (!deaf) return unexpected(deaf.error());
  second_ocu->deaf = std::move(*deaf);
  return {};
}

std::size_t RunReport::count(Verdict verdict) const {
  std::size_t n = 0;
  for (const auto& r : results) n += r.outcome.verdict == verdict;
  return n;
}

namespace {

// A service entry's type is the component ID it describes (0: the core
// service). A node manager answers for its whole node: only its own entries
// describe it. An answer whose types follow no such rule is taken whole.
void take_services(ComponentUnderTest& component, const std::vector<msg::ServiceEntry>& services) {
  component.services_known = true;
  const bool typed = std::any_of(services.begin(), services.end(),
                                 [&](const auto& s) { return s.type == component.address.component; });
  for (const auto& service : services) {
    if (typed && service.type != component.address.component && service.type != 0) continue;
    for (const auto& input : service.inputs) component.inputs.insert(input.command_code);
    for (const auto& output : service.outputs) component.outputs[output.command_code] |= output.presence_vector;
  }
}

const ocu::DiscoveredComponent* find(const ocu::Discovery& discovery, const Address& address,
                                     const ocu::DiscoveredNode** node_out) {
  const auto subsystem = discovery.subsystems().find(address.subsystem);
  if (subsystem == discovery.subsystems().end()) return nullptr;
  const auto node = subsystem->second.nodes.find(address.node);
  if (node == subsystem->second.nodes.end()) return nullptr;
  const auto component = node->second.components.find({address.component, address.instance});
  if (component == node->second.components.end()) return nullptr;
  *node_out = &node->second;
  return &component->second;
}

}  // namespace

Expected<ComponentUnderTest> learn_component(ocu::OcuSession& session, const Address& address,
                                             const ocu::Discovery* discovery, rt::Duration reply_timeout) {
  ComponentUnderTest component;
  component.address = address;
  const auto dialect = session.options().dialect;
  auto identification = session.request(address, msg::QueryIdentification{{msg::identification::kComponent}},
                                        {msg::ReportIdentification::code}, reply_timeout);
  if (!identification) return unexpected(identification.error());
  msg::ReportIdentification id{};
  if (wire::decode_payload_into(identification->payload, id, dialect, kHeaderSize)) component.name = id.identification;
  auto services = session.request(address, msg::QueryServices{}, {msg::ReportServices::code}, reply_timeout);
  msg::ReportServices report{};
  if (services && wire::decode_payload_into(services->payload, report, dialect, kHeaderSize)) {
    take_services(component, report.services);
  } else if (discovery) {
    // Some nodes answer Query Services only at the node manager.
    const ocu::DiscoveredNode* node = nullptr;
    if (const auto* found = find(*discovery, address, &node))
      if (auto listed = ocu::Discovery::services_of(*node, *found); !listed.empty()) take_services(component, listed);
  }
  return component;
}

std::vector<Address> discovered_components(const ocu::Discovery& discovery) {
  std::vector<Address> components;
  for (const auto& [sid, subsystem] : discovery.subsystems())
    for (const auto& [nid, node] : subsystem.nodes)
      for (const auto& [key, component] : node.components) components.push_back(component.address);
  return components;
}

std::vector<CaseResult> run_cases(ocu::OcuSession& session, const ComponentUnderTest& component,
                                  const std::vector<const ConformanceCase*>& cases, const RunOptions& options,
                                  const ResultListener& on_result) {
  // jaus-conform's other OCUs: on UDP beside its session.
  std::unique_ptr<OcuFactory> udp_ocus = !options.ocus && session.on_udp() ? udp_ocu_factory(session) : nullptr;
  OcuFactory* ocus = options.ocus ? options.ocus : udp_ocus.get();
  const CaseResult blank{nullptr, component.address, component.name, {}, {}, {}};
  const auto run_case = [&](const ConformanceCase& test_case, CaseResult& result) {
    CaseContext context{session, component, options.profile, options.reply_timeout, {}, session.clock().now(), ocus};
    detail::run_recorded(session, context, component.address, test_case, result);
  };
  return detail::run_each_case(session, cases, component, blank, options, on_result, run_case);
}

}  // namespace jaus::conform
