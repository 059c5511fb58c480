// jaus-console: the operator console in a browser (docs/console.md). An OCU
// with its own JAUS ID (an ocu::OcuSession on UDP) that serves the page and
// its WebSocket (jaus_console's WebServer) on 127.0.0.1:8080 by default, on
// one io_context. Thin: options, logging, signals, plugins; the console
// itself is jaus_console. SIGINT/SIGTERM: zero effort where driving, control released,
// pages closed, then exit.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <iostream>

#include "jaus/base/version.hpp"
#include "jaus/console/operator_console.hpp"
#include "jaus/console/web_server.hpp"
#include "jaus/host/component_plugins.hpp"
#include "jaus/ocu/must_arrive_options.hpp"
#include "jaus/ocu/operator_identity.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/ipv4.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadUsage = 2;

struct Options {
  std::string listen = "127.0.0.1:8080";
  std::vector<std::string> to;
  std::string bind;
  std::string as;
  int authority = 0;
  std::string token;
  std::vector<std::string> plugins;
  jaus::ocu::MustArriveText must_arrive;
  int verbosity = 0;
};

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

int bad_usage(const std::string& what) {
  std::cerr << "jaus-console: " << what << " (--help for usage)\n";
  return kExitBadUsage;
}

jaus::rt::LogFn stderr_log(int verbosity) {
  // Default: warnings and errors; -v the console's events; -vv the runtime's debug lines.
  const auto threshold = verbosity >= 2   ? jaus::rt::LogLevel::debug
                         : verbosity == 1 ? jaus::rt::LogLevel::info
                                          : jaus::rt::LogLevel::warn;
  return [threshold](jaus::rt::LogLevel level, const std::string& text) {
    if (level < threshold) return;
    static constexpr const char* kNames[] = {"debug", "info", "warn", "error"};
    std::cerr << "jaus-console [" << kNames[static_cast<int>(level)] << "] " << text << "\n";
  };
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"jaus-console: the operator console in a browser. Serves a page and its WebSocket "
               "(http://127.0.0.1:8080/ by default) and talks JAUS to the nodes as an OCU: the system tree, "
               "control, driving with a deadman, emergency, camera, arm, waypoints (docs/console.md)."};
  app.set_version_flag("--version", "jaus-console " + std::string(jaus::kVersion));
  app.add_option("--listen", o.listen,
                 "where the page is served, ADDR:PORT (beyond loopback only with a token; reach a robot's console "
                 "with an SSH port forward instead)")
      ->type_name("ADDR:PORT")
      ->capture_default_str();
  app.add_option("--to", o.to, "a node to talk to, HOST[:PORT] (a static peer; repeat for several nodes; default 127.0.0.1)")
      ->type_name("HOST[:PORT]");
  app.add_option("--bind", o.bind, "the OCU's own UDP address, ADDR[:PORT] (default: any, any port)")
      ->type_name("ADDR[:PORT]");
  app.add_option("--as", o.as, "this OCU's JAUS address (default: this user's 254.N.40.1, kept in $XDG_STATE_HOME/jaus/operator-id, "
                 "as jausctl's)")->type_name("S.N.C.I");
  app.add_option("--authority", o.authority, "the OCU component's own authority, 0..255")
      ->type_name("N")
      ->capture_default_str();
  app.add_option("--token", o.token,
                 "the token pages must give (?token=); with --listen beyond loopback and no --token, one is "
                 "generated and printed")
      ->type_name("TEXT");
  app.add_option("--plugin", o.plugins,
                 "a component plugin (.so), as listed under jausd's `plugins:`: the console then knows its kinds and "
                 "shows what each says an operator unit shows of it (repeat for several)")
      ->type_name("PATH");
  app.add_flag("-v,--verbose", o.verbosity, "log more: -v the console's events, -vv the runtime's debug lines");
  // How hard the emergency buttons' commands are tried (as jausctl's).
  jaus::ocu::add_must_arrive_options(&app, o.must_arrive);
  CLI11_PARSE(app, argc, argv);

  auto listen = jaus::transport::parse_endpoint(o.listen, jaus::console::kDefaultConsolePort);
  if (!listen) return bad_usage("--listen: " + listen.error().message());
  jaus::ocu::SessionOptions session_options;
  if (!o.to.empty()) {
    session_options.to.clear();
    for (const auto& peer : o.to) {
      auto endpoint = jaus::transport::parse_endpoint(peer);
      if (!endpoint) return bad_usage("--to: " + endpoint.error().message());
      session_options.to.push_back(*endpoint);
    }
  }
  if (!o.bind.empty()) {
    auto bind = jaus::transport::parse_endpoint(o.bind, 0);
    if (!bind) return bad_usage("--bind: " + bind.error().message());
    session_options.bind = *bind;
  }
  std::optional<jaus::Address> as;
  if (!o.as.empty()) {
    as = jaus::Address::parse(o.as);
    if (!as || !as->is_valid() || as->is_broadcast() || as->component == 1)
      return bad_usage("--as: '" + o.as + "' is not an OCU address S.N.C.I (1..254 each, component not 1)");
  }
  if (o.authority < 0 || o.authority > 255) return bad_usage("--authority: 0..255");
  auto must_arrive = jaus::ocu::parse_must_arrive(o.must_arrive);
  if (!must_arrive) return bad_usage(must_arrive.error().message());
  session_options.must_arrive = *must_arrive;
  // Before the console looks any kind up (the kinds' operator views, kind_views.hpp).
  for (const auto& path : o.plugins) {
    auto plugin = jaus::host::load_component_plugin(path);
    if (!plugin) return bad_usage("--plugin: " + plugin.error().message());
    std::cout << "jaus-console: plugin '" << plugin->name << "' (" << plugin->path.string() << "): "
              << (plugin->kinds.empty() ? std::string("no component kinds") : "component kinds " + join(plugin->kinds))
              << std::endl;
  }
  // The user's kept ID, as jausctl's (an emergency set here is cleared by
  // `jausctl emergency ... clear`); refused while another process acts as
  // it (the console takes control: IdUse::holds). Locked
  // until the console ends.
  auto id = jaus::ocu::choose_operator_id(as, jaus::ocu::IdUse::holds);
  if (!id) {
    std::cerr << "jaus-console: " << id.error().message() << "\n";
    return id.error().code == jaus::ErrorCode::invalid_argument ? kExitBadUsage : kExitFailure;
  }
  if (!id->note.empty()) std::cerr << "jaus-console: " << id->note << "\n";
  session_options.self = id->address;
  session_options.authority = static_cast<std::uint8_t>(o.authority);
  const auto log = stderr_log(o.verbosity);
  session_options.log = log;

  std::string token = o.token;
  if (token.empty() && !jaus::console::is_loopback(listen->address)) token = jaus::console::generate_token();

  std::signal(SIGPIPE, SIG_IGN);
  boost::asio::io_context io;  // the session's, the web server's and the signals'
  auto session = jaus::ocu::OcuSession::open(session_options, &io);
  if (!session) {
    std::cerr << "jaus-console: " << session.error().message() << "\n";
    return kExitFailure;
  }
  jaus::transport::AsioRuntime runtime(io);

  std::unique_ptr<jaus::console::WebServer> server;
  jaus::console::ConsoleOptions console_options;
  console_options.version = std::string(jaus::kVersion);
  console_options.log = log;
  jaus::console::OperatorConsole console(**session, runtime, runtime, console_options,
                                         [&server](jaus::console::PageId to, const std::string& frame) {
                                           if (server) server->send(to, frame);
                                         });

  jaus::console::WebServerOptions web;
  web.listen = *listen;
  web.token = token;
  web.log = log;
  auto started = jaus::console::WebServer::start(
      io, web,
      jaus::console::PageEvents{[&](jaus::console::PageId page) { console.page_opened(page); },
                                [&](jaus::console::PageId page) { console.page_closed(page); },
                                [&](jaus::console::PageId page, std::string_view frame) {
                                  console.page_frame(page, frame);
                                }});
  if (!started) {
    std::cerr << "jaus-console: " << started.error().message() << "\n";
    return kExitFailure;
  }
  server = std::move(*started);

  const std::string address = jaus::transport::ipv4_to_string(listen->address) + ":" + std::to_string(server->port());
  std::cout << "jaus-console " << jaus::kVersion << ": OCU " << (*session)->self().to_string() << ", page at http://"
            << address << "/" << (token.empty() ? "" : "?token=" + token) << std::endl;

  bool stopping = false;
  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code& ec, int) {
    if (ec) return;
    stopping = true;
    // Zero effort and Release Component Control go out here, before the pages close.
    console.shutdown();
    server->stop();
    (*session)->request_stop();
  });

  console.start();
  while (!stopping && !(*session)->interrupted()) (*session)->run_until([&] { return stopping; }, std::chrono::hours(1));
  console.shutdown();
  server->stop();
  // Let the closes and the last datagrams leave.
  (*session)->run_cleanup_until([] { return false; }, std::chrono::milliseconds(200));
  std::cout << "jaus-console: stopped" << std::endl;
  return kExitOk;
}
