// jaus-conform: runs the component conformance cases (jaus_conform) against
// a JAUS node on the network, ours or another implementation's: discovers
// it, picks the cases that apply to each component, prints one line per case
// and a summary, and writes JUnit XML and a readable report on request.
// Exit 0: every case that applied passed; 1: failures; 2: bad usage or no node.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <algorithm>
#include <csignal>
#include <functional>
#include <fstream>
#include <iostream>

#include "jaus/base/version.hpp"
#include "jaus/conform/jss_case.hpp"
#include "jaus/conform/reports.hpp"
#include "jaus/conform/runner.hpp"
#include "jaus/ocu/discover.hpp"
#include "jaus/transport/ipv4.hpp"

namespace {

constexpr int kExitPassed = 0;
constexpr int kExitFailures = 1;
constexpr int kExitBadUsage = 2;

struct Options {
  std::string to;
  std::vector<std::string> components;
  std::string profile = "ra";
  std::string junit;
  std::string report;
  std::string only;
  std::string skip;
  double timeout_s = 1.0;
  double wait_s = 2.0;
  std::string bind;
};

// What every component is asked first (its identification, its services):
// one that does not answer fails this and is tested no further.
const jaus::conform::CaseDescription kAnswers{"runner.answers", "answers Query Identification (component)",
                                              "docs/wire-format.md: Typical OCU sequence"};

int bad_usage(const std::string& what) {
  std::cerr << "jaus-conform: " << what << " (--help for usage)\n";
  return kExitBadUsage;
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (out) return true;
  std::cerr << "jaus-conform: cannot write " << path << "\n";
  return false;
}

// SIGINT and SIGTERM ask the session to stop, each time: the case under way
// cleans up (releases control, terminates its service connections; that only
// sends, it never waits), the cases left fail as interrupted, and the summary
// and reports are written as usual.
class StopOnSignals {
 public:
  StopOnSignals(boost::asio::io_context& io, std::function<void()> request_stop)
      : signals_(io, SIGINT, SIGTERM), request_stop_(std::move(request_stop)) {
    arm();
  }

 private:
  void arm() {
    signals_.async_wait([this](const boost::system::error_code& ec, int) {
      if (ec) return;  // cancelled: the run is over
      request_stop_();
      arm();
    });
  }
  boost::asio::signal_set signals_;
  std::function<void()> request_stop_;
};

bool write_reports(const Options& o, const jaus::conform::RunReport& report) {
  bool written = true;
  if (!o.junit.empty()) written = write_file(o.junit, jaus::conform::junit_xml(report)) && written;
  if (!o.report.empty()) written = write_file(o.report, jaus::conform::markdown_report(report)) && written;
  return written;
}

int finish(const Options& o, const jaus::conform::RunReport& report) {
  std::cout << jaus::conform::summary_line(report) << "\n";
  const bool written = write_reports(o, report);
  if (report.results.empty())
    return bad_usage(o.skip.empty() ? "no case matches --only " + o.only
                                    : "no case left by --only '" + o.only + "' and --skip '" + o.skip + "'");
  return report.passed() && written ? kExitPassed : kExitFailures;
}

// --profile jss: a JSS client (ocu::JssSession, AS5669A) discovers the node
// the JSS way and runs the JSS cases on each component it lists.
int run_jss(const Options& o, const jaus::transport::Ipv4Endpoint& to, jaus::rt::Duration reply_timeout,
            jaus::rt::Duration wait) {
  using namespace jaus;
  std::vector<jss::JssId> requested;
  for (const auto& text : o.components) {
    const auto id = jss::JssId::parse(text);
    if (!id || !id->is_valid() || id->is_broadcast())
      return bad_usage("--component " + text + ": expected a JSS ID S.N.C (subsystem 1..65534, node and component 1..254)");
    requested.push_back(*id);
  }
  ocu::JssSessionOptions session_options;
  session_options.self = conform::kJssRunnerId;
  session_options.to = {to};
  session_options.name = "jaus-conform";
  if (!o.bind.empty()) {
    auto bind = transport::parse_endpoint(o.bind, 0);
    if (!bind) return bad_usage("--bind " + o.bind + ": " + bind.error().message());
    session_options.bind = *bind;
  }
  boost::asio::io_context io;  // the runner's, its second client's and the signals'
  auto session = ocu::JssSession::open(session_options, &io);
  if (!session) return bad_usage(session.error().message());
  const StopOnSignals signals(io, [&s = **session] { s.request_stop(); });
  auto found = conform::discover_jss_components(**session, wait, reply_timeout);
  if (!found || found->empty()) {
    std::cerr << "jaus-conform: no JSS node answered at " << transport::to_string(to) << " within " << o.wait_s
              << " s\n";
    return kExitBadUsage;
  }
  std::vector<conform::JssComponentUnderTest> components;
  for (const auto& component : *found)
    if (requested.empty() || std::find(requested.begin(), requested.end(), component.id) != requested.end())
      components.push_back(component);
  for (const auto& id : requested)
    if (std::none_of(found->begin(), found->end(), [&](const auto& c) { return c.id == id; }))
      components.push_back(conform::JssComponentUnderTest{id, "", {}, false});
  // The second client: beside the runner, on its io_context, a port of its own, one for the whole run.
  std::unique_ptr<ocu::JssSession> second_client;
  const conform::JssClientOpener open_client = [&](const jss::JssId& self) -> Expected<ocu::JssSession*> {
    if (second_client) return second_client.get();
    ocu::JssSessionOptions options = session_options;
    options.self = self;
    options.bind.port = 0;
    options.name = "jaus-conform (second client)";
    auto opened = ocu::JssSession::open(std::move(options), &io);
    if (!opened) return unexpected(opened.error());
    second_client = std::move(*opened);
    return second_client.get();
  };
  conform::RunReport report;
  report.node = transport::to_string(to);
  report.profile = conform::Profile::jss;
  conform::RunOptions run_options;
  run_options.profile = conform::Profile::jss;
  run_options.reply_timeout = reply_timeout;
  run_options.only = o.only;
  run_options.skip = o.skip;
  const auto cases = conform::all_jss_cases();
  for (const auto& component : components) {
    std::cout << "== " << component.id.to_string() << (component.name.empty() ? "" : " " + component.name) << "\n";
    auto results = conform::run_jss_cases(**session, component, *found, cases, run_options, open_client,
                                          [](const conform::CaseResult& r) {
                                            std::cout << conform::case_line(r) << std::endl;
                                          });
    for (auto& r : results) report.results.push_back(std::move(r));
    if ((*session)->interrupted()) break;
  }
  return finish(o, report);
}

int run(const Options& o) {
  using namespace jaus;
  auto to = transport::parse_endpoint(o.to);
  if (!to) return bad_usage("--to " + o.to + ": " + to.error().message());
  const auto profile = conform::parse_profile(o.profile);
  if (!profile) return bad_usage("--profile " + o.profile + ": expected ra, openjaus or jss");
  if (!(o.timeout_s > 0 && o.timeout_s <= 60)) return bad_usage("--timeout must be more than 0 and at most 60 s");
  if (!(o.wait_s > 0 && o.wait_s <= 60)) return bad_usage("--wait must be more than 0 and at most 60 s");
  if (*profile == conform::Profile::jss)
    return run_jss(o, *to, std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(o.timeout_s)),
                   std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(o.wait_s)));
  std::vector<Address> requested;
  for (const auto& text : o.components) {
    const auto address = Address::parse(text);
    if (!address || !address->is_valid() || address->is_broadcast())
      return bad_usage("--component " + text + ": expected S.N.C.I, each 1..254");
    requested.push_back(*address);
  }
  ocu::SessionOptions session_options;
  session_options.to = {*to};
  session_options.dialect = *profile == conform::Profile::openjaus ? wire::Dialect::openjaus : wire::Dialect::ra;
  if (!o.bind.empty()) {
    auto bind = transport::parse_endpoint(o.bind, 0);
    if (!bind) return bad_usage("--bind " + o.bind + ": " + bind.error().message());
    session_options.bind = *bind;
  }
  boost::asio::io_context io;  // the session's, and the signals'
  auto session = ocu::OcuSession::open(session_options, &io);
  if (!session) return bad_usage(session.error().message());
  const StopOnSignals signals(io, [&s = **session] { s.request_stop(); });
  const auto reply_timeout = std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(o.timeout_s));
  const auto wait = std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(o.wait_s));

  // What is there: every component discovery finds, unless named.
  const ocu::Discovery discovery = ocu::discover(**session, wait);
  std::vector<Address> components = requested.empty() ? conform::discovered_components(discovery) : requested;
  if (components.empty()) {
    std::cerr << "jaus-conform: no JAUS node heard at " << transport::to_string(*to) << " within " << o.wait_s
              << " s\n";
    return kExitBadUsage;
  }

  conform::RunReport report;
  report.node = transport::to_string(*to);
  report.profile = *profile;
  conform::RunOptions run_options;
  run_options.profile = *profile;
  run_options.reply_timeout = reply_timeout;
  run_options.only = o.only;
  run_options.skip = o.skip;
  const auto cases = conform::all_cases();
  for (const Address& address : components) {
    auto component = conform::learn_component(**session, address, &discovery, reply_timeout);
    if (!component) {
      // A component that does not answer is a failure of its own; the others are still tested.
      conform::CaseResult unreachable;
      unreachable.test_case = &kAnswers;
      unreachable.component = address;
      unreachable.outcome = {conform::Verdict::fail, component.error().message()};
      std::cout << "== " << address.to_string() << "\n" << conform::case_line(unreachable) << std::endl;
      report.results.push_back(std::move(unreachable));
      continue;
    }
    std::cout << "== " << address.to_string() << (component->name.empty() ? "" : " " + component->name) << "\n";
    auto results = conform::run_cases(**session, *component, cases, run_options, [](const conform::CaseResult& r) {
      std::cout << conform::case_line(r) << std::endl;
    });
    for (auto& r : results) report.results.push_back(std::move(r));
    if ((*session)->interrupted()) break;
  }
  return finish(o, report);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "jaus-conform: component conformance tests against a JAUS node on the network (ours or any other "
      "RA 3.x implementation, or a SAE JAUS node with --profile jss). Discovers the node, runs the cases that apply to each component and prints one "
      "line per case (pass, fail with the reason, skip with why) and a summary. Exit 0 when every applicable case "
      "passes, 1 on failures, 2 on bad usage or when no node answers. docs/conformance.md lists the cases."};
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "jaus-conform: " + std::string(e.what()) + " (--help for usage)\n";
  });
  app.set_version_flag("--version", "jaus-conform " + std::string(jaus::kVersion));
  Options o;
  app.add_option("--to", o.to, "the node to test: A.B.C.D[:PORT] (port 3794 when left out)")
      ->type_name("ADDR[:PORT]")
      ->required();
  app.add_option("--component", o.components,
                 "test only this component, S.N.C.I (repeatable; a JSS ID S.N.C with --profile jss)")
      ->type_name("S.N.C.I");
  app.add_option("--profile", o.profile,
                 "ra (the RA as written), openjaus (the common RA 3.3 implementation's "
                 "documented quirks accepted) or jss (SAE JAUS core and mobility services over AS5669A)")
      ->type_name("ra|openjaus|jss")
      ->capture_default_str();
  app.add_option("--junit", o.junit, "write JUnit XML to FILE")->type_name("FILE");
  app.add_option("--report", o.report, "write a readable Markdown report to FILE")->type_name("FILE");
  app.add_option("--only", o.only, "run only the cases whose id contains PATTERN (e.g. control. or sc.rate)")
      ->type_name("PATTERN");
  app.add_option("--skip", o.skip, "leave out the cases whose id contains PATTERN (e.g. control.silent_requester)")
      ->type_name("PATTERN");
  app.add_option("--timeout", o.timeout_s, "seconds to wait for each reply")
      ->type_name("SECONDS")
      ->capture_default_str();
  app.add_option("--wait", o.wait_s, "seconds of discovery before the cases")
      ->type_name("SECONDS")
      ->capture_default_str();
  app.add_option("--bind", o.bind,
                 "the runner's own address A.B.C.D[:PORT] (peers that answer to IP:3794 need it bound to port 3794)")
      ->type_name("ADDR[:PORT]");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitPassed : kExitBadUsage;
  }
  return run(o);
}
