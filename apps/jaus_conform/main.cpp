// jaus-conform: runs the component conformance cases (jaus_conform) against
// a JAUS node on the network, ours or another implementation's: discovers
// it, picks the cases that apply to each component, prints one line per case
// and a summary, and writes JUnit XML and a readable report on request.
// Exit 0: every case that applied passed; 1: failures; 2: bad usage or no node.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <fstream>
#include <iostream>

#include "jaus/base/version.hpp"
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
const jaus::conform::ConformanceCase kAnswers{"runner.answers", "answers Query Identification (component)",
                                              "wire notes: Liveness and discovery (typical OCU sequence)", nullptr,
                                              nullptr};

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
  StopOnSignals(boost::asio::io_context& io, jaus::ocu::OcuSession& session)
      : signals_(io, SIGINT, SIGTERM), session_(session) {
    arm();
  }

 private:
  void arm() {
    signals_.async_wait([this](const boost::system::error_code& ec, int) {
      if (ec) return;  // cancelled: the run is over
      session_.request_stop();
      arm();
    });
  }
  boost::asio::signal_set signals_;
  jaus::ocu::OcuSession& session_;
};

int run(const Options& o) {
  using namespace jaus;
  auto to = transport::parse_endpoint(o.to);
  if (!to) return bad_usage("--to " + o.to + ": " + to.error().message());
  const auto profile = conform::parse_profile(o.profile);
  if (!profile) return bad_usage("--profile " + o.profile + ": expected ra or openjaus");
  if (!(o.timeout_s > 0 && o.timeout_s <= 60)) return bad_usage("--timeout must be more than 0 and at most 60 s");
  if (!(o.wait_s > 0 && o.wait_s <= 60)) return bad_usage("--wait must be more than 0 and at most 60 s");
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
  const StopOnSignals signals(io, **session);
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
  std::cout << conform::summary_line(report) << "\n";
  bool written = true;
  if (!o.junit.empty()) written = write_file(o.junit, conform::junit_xml(report)) && written;
  if (!o.report.empty()) written = write_file(o.report, conform::markdown_report(report)) && written;
  if (report.results.empty())
    return bad_usage(o.skip.empty() ? "no case matches --only " + o.only
                                    : "no case left by --only '" + o.only + "' and --skip '" + o.skip + "'");
  return report.passed() && written ? kExitPassed : kExitFailures;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "jaus-conform: component conformance tests against a JAUS node on the network (ours or any other "
      "RA 3.x implementation). Discovers the node, runs the cases that apply to each component and prints one "
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
  app.add_option("--component", o.components, "test only this component, S.N.C.I (repeatable)")->type_name("S.N.C.I");
  app.add_option("--profile", o.profile,
                 "ra (the RA as written) or openjaus (the common RA 3.3 implementation's "
                 "documented quirks accepted)")
      ->type_name("ra|openjaus")
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
