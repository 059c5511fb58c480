// `jausctl discover | status | query | send | control | subscribe | emergency`:
// jausctl as an operator control unit. This file is the command line only:
// it parses and checks every value (bad input: exit 2, one line naming what
// is wrong, before any socket is opened), opens an OcuSession and hands over
// to the command in ocu/. With --dialect jss the same commands speak SAE JAUS
// (AS5669A, JSS IDs S.N.C) on a JssSession (ocu/jss_commands.hpp).
#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>

#include "commands.hpp"
#include "ocu/cli_values.hpp"
#include "jaus/messages/environment_messages.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/must_arrive_options.hpp"
#include "jaus/ocu/operator_identity.hpp"
#include "ocu/jss_commands.hpp"
#include "ocu/ocu_commands.hpp"

namespace jausctl {

namespace {

using ocu::Parsed;

// What every OCU command takes, as written on the command line.
struct CommonOptions {
  std::vector<std::string> to;  // none: ocu::kDefaultPeer, or only the group with --multicast
  std::string multicast;
  std::string bind = "0.0.0.0:0";
  std::string framing = "opc";
  std::string as;  // empty: the kept operator ID (jaus/ocu/operator_identity.hpp)
  std::string timeout = "1";
  std::string dialect = "ra";
  jaus::ocu::MustArriveText must_arrive;
  int verbosity = 0;
};

void add_common_options(CLI::App* cmd, CommonOptions& c) {
  cmd->add_option("--to", c.to, "the node to talk to, HOST[:PORT] (a static peer; repeat for several nodes)")->type_name("HOST[:PORT]")
      ->default_str(std::string(ocu::kDefaultPeer) + ", none with --multicast");
  cmd->add_option("--multicast", c.multicast,
                  "reach nodes through this multicast group too (jausd's transport.multicast, e.g. 224.1.0.1)")
      ->type_name("GROUP[:PORT]");
  cmd->add_option("--bind", c.bind,
                  "local ADDR[:PORT] (port 0: any free port); peers that reply to IP:3794 need <own IP>:3794")->type_name("ADDR[:PORT]")
      ->capture_default_str();
  cmd->add_option("--framing", c.framing, "UDP framing: opc | judp")->type_name("opc|judp")->capture_default_str();
  cmd->add_option("--as", c.as,
                  "this OCU's address (default: your ID, kept in $XDG_STATE_HOME/jaus/operator-id)")
      ->type_name("S.N.C.I|S.N.C");
  cmd->add_option("--timeout", c.timeout, "seconds to wait for a reply")->type_name("SECONDS")->capture_default_str();
  cmd->add_option("--dialect", c.dialect,
                  "ra | openjaus: how RA payloads are read; jss: speak SAE JAUS (AS5669A, IDs S.N.C)")
      ->type_name("ra|openjaus|jss")
      ->capture_default_str();
  cmd->add_flag("-v,--verbose", c.verbosity, "log the runtime: -v warnings, -vv info, -vvv debug");
  // How hard a command that must arrive (ACK requested: emergency, send of a
  // command) is tried: docs/talk-to-your-node.md, "Over a slow or long link".
  jaus::ocu::add_must_arrive_options(cmd, c.must_arrive);
}

struct Common {
  ocu::SessionOptions session;  // session.self: chosen when the command runs (with_session)
  std::optional<jaus::Address> as;  // --as
  jaus::rt::Duration timeout{};
};

// One line on stderr, exit code 2.
int bad_input(std::string_view command, const std::string& why) {
  std::cerr << "jausctl " << command << ": " << why << "\n";
  return kExitBadInput;
}

jaus::rt::LogFn stderr_log(int verbosity) {
  // Default: errors only, so a failing command prints its one line.
  const auto threshold = verbosity >= 3   ? jaus::rt::LogLevel::debug
                         : verbosity == 2 ? jaus::rt::LogLevel::info
                         : verbosity == 1 ? jaus::rt::LogLevel::warn
                                          : jaus::rt::LogLevel::error;
  return [threshold](jaus::rt::LogLevel level, const std::string& text) {
    // A --multicast group that cannot be used is shown anyway: without it,
    // discovery with multicast only finds nothing and would not say why.
    const bool multicast_warning = level == jaus::rt::LogLevel::warn && text.rfind("multicast ", 0) == 0;
    if (level < threshold && !multicast_warning) return;
    static constexpr const char* kNames[] = {"debug", "info", "warn", "error"};
    std::cerr << "jausctl [" << kNames[static_cast<int>(level)] << "] " << text << "\n";
  };
}

Parsed<Common> parse_common(const CommonOptions& c) {
  Common out;
  auto peers = ocu::parse_peers(c.to, c.multicast);
  if (!peers) return jaus::unexpected(peers.error());
  out.session.to = std::move(peers->to);
  out.session.multicast = peers->multicast;
  auto bind = ocu::parse_endpoint_text(c.bind, 0, true);
  if (!bind) return ocu::invalid("--bind: " + bind.error().message());
  auto framing = ocu::parse_framing(c.framing);
  if (!framing) return ocu::invalid("--framing: " + framing.error().message());
  if (!c.as.empty()) {
    auto self = ocu::parse_address(c.as, false);
    if (!self) return ocu::invalid("--as: " + self.error().message());
    if (self->component == 1)
      return ocu::invalid(std::string("--as: component 1 is the OCU's node manager; use another component ID (e.g. 40)"));
    out.as = *self;
  }
  auto timeout = ocu::parse_seconds(c.timeout);
  if (!timeout) return ocu::invalid("--timeout: " + timeout.error().message());
  if (c.dialect != "ra" && c.dialect != "openjaus")
    return ocu::invalid("--dialect: bad dialect '" + c.dialect + "': expected ra, openjaus or jss");
  auto must_arrive = jaus::ocu::parse_must_arrive(c.must_arrive);
  if (!must_arrive) return jaus::unexpected(must_arrive.error());
  out.session.must_arrive = *must_arrive;
  out.session.bind = *bind;
  out.session.framing = *framing;
  out.session.dialect = c.dialect == "openjaus" ? jaus::wire::Dialect::openjaus : jaus::wire::Dialect::ra;
  out.session.log = stderr_log(c.verbosity);
  out.timeout = *timeout;
  return out;
}

// SIGINT and SIGTERM ask `session` to stop (the command then cleans up:
// releases control, terminates its service connections), each time: the
// clean-up only sends (it never waits), so a second Ctrl-C is never needed.
template <class Session>
class StopOnSignals {
 public:
  StopOnSignals(boost::asio::io_context& io, Session& session) : signals_(io, SIGINT, SIGTERM), session_(session) {
    arm();
  }

 private:
  void arm() {
    signals_.async_wait([this](const boost::system::error_code& ec, int) {
      if (ec) return;  // cancelled: the command is over
      session_.request_stop();
      arm();
    });
  }
  boost::asio::signal_set signals_;
  Session& session_;
};

// Chooses the ID (--as, else this user's kept one; operator_identity.hpp
// says what happens while another process acts as it), opens the session and
// runs `command` on it. The ID stays locked until the command returns.
template <class Run>
int with_session(std::string_view name, Common common, ocu::IdUse use, Run run) {
  // A closed stdout (| head) must not kill the process before it has released
  // control or terminated its service connection: writes fail instead.
  std::signal(SIGPIPE, SIG_IGN);
  auto id = ocu::choose_operator_id(common.as, use);
  if (!id) {
    std::cerr << "jausctl " << name << ": " << id.error().message() << "\n";
    return id.error().code == jaus::ErrorCode::invalid_argument ? kExitBadInput : kExitFailure;
  }
  if (!id->note.empty()) std::cerr << "jausctl " << name << ": " << id->note << "\n";
  common.session.self = id->address;
  boost::asio::io_context io;  // the session's, and the signals'
  auto session = ocu::OcuSession::open(common.session, &io);
  if (!session) {
    std::cerr << "jausctl " << name << ": " << session.error().message() << "\n";
    return kExitFailure;
  }
  const StopOnSignals<ocu::OcuSession> signals(io, **session);
  return run(**session, ocu::CommandIo{std::cout, std::cerr, id->shared});
}

bool is_jss(const CommonOptions& c) { return c.dialect == "jss"; }

// --dialect jss: the JSS operator unit's options ("--framing" is the RA's: AS5669A has one).
Parsed<ocu::JssCommon> parse_jss_common(const CommonOptions& c) {
  auto parsed = ocu::parse_jss_common(ocu::JssCommonText{c.to, c.multicast, c.bind, c.as, c.timeout});
  if (!parsed) return parsed;
  auto must_arrive = jaus::ocu::parse_must_arrive(c.must_arrive);
  if (!must_arrive) return jaus::unexpected(must_arrive.error());
  parsed->session.must_arrive = *must_arrive;
  parsed->session.log = stderr_log(c.verbosity);
  return parsed;
}

// The same as with_session, on a JSS session.
template <class Run>
int with_jss_session(std::string_view name, const ocu::JssCommon& common, Run run) {
  std::signal(SIGPIPE, SIG_IGN);
  boost::asio::io_context io;
  auto session = ocu::JssSession::open(common.session, &io);
  if (!session) {
    std::cerr << "jausctl " << name << ": " << session.error().message() << "\n";
    return kExitFailure;
  }
  const StopOnSignals<ocu::JssSession> signals(io, **session);
  return run(**session, ocu::CommandIo{std::cout, std::cerr});
}

}  // namespace

void add_ocu_commands(CLI::App& app, int& exit_code) {
  auto common = std::make_shared<CommonOptions>();
  auto target = std::make_shared<std::string>();
  auto code = std::make_shared<std::string>();
  auto pv = std::make_shared<std::string>();

  // Each handler checks its input first: bad input exits 2 before a socket opens.
  auto checked_common = [common](std::string_view name, int& rc) -> std::optional<Common> {
    auto parsed = parse_common(*common);
    if (!parsed) {
      rc = bad_input(name, parsed.error().message());
      return std::nullopt;
    }
    return *parsed;
  };
  auto checked_jss = [common](std::string_view name, int& rc) -> std::optional<ocu::JssCommon> {
    auto parsed = parse_jss_common(*common);
    if (!parsed) {
      rc = bad_input(name, parsed.error().message());
      return std::nullopt;
    }
    return *parsed;
  };

  // discover
  auto wait = std::make_shared<std::string>("2");
  auto json = std::make_shared<bool>(false);
  auto* discover = app.add_subcommand("discover", "Find subsystems, nodes and components: identification and services");
  discover->add_option("--wait", *wait, "seconds to listen and ask")->type_name("SECONDS")->capture_default_str();
  discover->add_flag("--json", *json, "print JSON instead of a table");
  add_common_options(discover, *common);
  discover->callback([&exit_code, common, checked_common, checked_jss, wait, json] {
    if (is_jss(*common)) {
      auto c = checked_jss("discover", exit_code);
      if (!c) return;
      auto seconds = ocu::parse_seconds(*wait);
      if (!seconds) return void(exit_code = bad_input("discover", "--wait: " + seconds.error().message()));
      exit_code = with_jss_session("discover", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_discover(s, *seconds, *json, io);
      });
      return;
    }
    auto c = checked_common("discover", exit_code);
    if (!c) return;
    auto seconds = ocu::parse_seconds(*wait);
    if (!seconds) return void(exit_code = bad_input("discover", "--wait: " + seconds.error().message()));
    const ocu::DiscoverOptions options{*seconds, *json};
    exit_code = with_session("discover", *c, ocu::IdUse::looks, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_discover(s, options, io);
    });
  });

  // status
  auto* status = app.add_subcommand("status", "Query Component Status of ADDR; prints JSON");
  status->add_option("ADDR", *target, "component address S.N.C.I")->type_name("S.N.C.I")->required();
  add_common_options(status, *common);
  status->callback([&exit_code, common, checked_common, checked_jss, target] {
    if (is_jss(*common)) {
      auto c = checked_jss("status", exit_code);
      if (!c) return;
      auto id = ocu::parse_jss_id(*target, true);
      if (!id) return void(exit_code = bad_input("status", id.error().message()));
      exit_code = with_jss_session("status", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_status(s, *id, c->timeout, io);
      });
      return;
    }
    auto c = checked_common("status", exit_code);
    if (!c) return;
    auto address = ocu::parse_address(*target, true);
    if (!address) return void(exit_code = bad_input("status", address.error().message()));
    exit_code = with_session("status", *c, ocu::IdUse::looks, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_status(s, *address, c->timeout, io);
    });
  });

  // query
  auto fields = std::make_shared<std::string>("{}");
  auto* query = app.add_subcommand("query", "Send the query CODE to ADDR; prints the report as JSON");
  query->add_option("ADDR", *target, "component address S.N.C.I")->type_name("S.N.C.I")->required();
  query->add_option("CODE", *code, "query code (0x2402) or name (\"Query Global Pose\")")->type_name("CODE")->required();
  query->add_option("--pv", *pv, "presence vector of the query, hex (which fields the report should carry)")->type_name("HEX");
  query->add_option("--fields", *fields, "the query's other fields as JSON, e.g. '{\"camera_id\":1}' (default 0)")->type_name("JSON");
  auto save_image = std::make_shared<std::string>();
  query->add_option("--save-image", *save_image, "write the picture of a Report Image to FILE (PNG or JPEG as sent)")
      ->type_name("FILE");
  add_common_options(query, *common);
  query->callback([&exit_code, common, checked_common, checked_jss, target, code, pv, fields, save_image] {
    if (is_jss(*common)) {
      auto c = checked_jss("query", exit_code);
      if (!c) return;
      auto id = ocu::parse_jss_id(*target, true);
      if (!id) return void(exit_code = bad_input("query", id.error().message()));
      auto info = ocu::parse_jss_message(*code);
      if (!info) return void(exit_code = bad_input("query", info.error().message()));
      auto field_json = ocu::Json::parse(*fields, nullptr, false);
      if (field_json.is_discarded()) return void(exit_code = bad_input("query", "--fields is not valid JSON"));
      if (!pv->empty()) {
        auto parsed_pv = ocu::parse_presence_vector(*pv);
        if (!parsed_pv) return void(exit_code = bad_input("query", "--pv: " + parsed_pv.error().message()));
        if (field_json.is_object()) field_json["presence_vector"] = *parsed_pv;
      }
      if (!save_image->empty()) return void(exit_code = bad_input("query", "--save-image is for RA Query Image"));
      auto prepared = ocu::prepare_jss_query(**info, field_json);
      if (!prepared) return void(exit_code = bad_input("query", prepared.error().message()));
      exit_code = with_jss_session("query", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_query(s, *id, *prepared, c->timeout, io);
      });
      return;
    }
    auto c = checked_common("query", exit_code);
    if (!c) return;
    auto address = ocu::parse_address(*target, true);
    if (!address) return void(exit_code = bad_input("query", address.error().message()));
    auto parsed_code = ocu::parse_message_code(*code);
    if (!parsed_code) return void(exit_code = bad_input("query", parsed_code.error().message()));
    std::optional<std::uint32_t> presence;
    if (!pv->empty()) {
      auto parsed_pv = ocu::parse_presence_vector(*pv);
      if (!parsed_pv) return void(exit_code = bad_input("query", "--pv: " + parsed_pv.error().message()));
      presence = *parsed_pv;
    }
    const auto field_json = ocu::Json::parse(*fields, nullptr, false);
    if (field_json.is_discarded()) return void(exit_code = bad_input("query", "--fields is not valid JSON"));
    auto prepared = ocu::prepare_query(*parsed_code, presence, field_json);
    if (!prepared) return void(exit_code = bad_input("query", prepared.error().message()));
    const auto report = ocu::report_code_for(*parsed_code);
    if (!report) return void(exit_code = bad_input("query", "no report is known for " + ocu::code_text(*parsed_code)));
    std::optional<std::string> image_file;
    if (!save_image->empty()) {
      if (*report != jaus::msg::ReportImage::code)
        return void(exit_code = bad_input("query", "--save-image needs Query Image (0x2807)"));
      image_file = *save_image;
    }
    exit_code = with_session("query", *c, ocu::IdUse::looks, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_query(s, *address, *prepared, *report, c->timeout, io, image_file);
    });
  });

  // send
  auto message = std::make_shared<std::string>();
  auto* send = app.add_subcommand("send", "Send a message (JSON as `jausctl msg decode` prints it) to ADDR");
  send->add_option("ADDR", *target, "component address S.N.C.I")->type_name("S.N.C.I")->required();
  send->add_option("JSON", *message, "the message; - reads it from stdin")->type_name("JSON")->required();
  add_common_options(send, *common);
  send->callback([&exit_code, common, checked_common, checked_jss, target, message] {
    if (is_jss(*common)) {
      auto c = checked_jss("send", exit_code);
      if (!c) return;
      auto id = ocu::parse_jss_id(*target, true);
      if (!id) return void(exit_code = bad_input("send", id.error().message()));
      std::string text = *message;
      if (text == "-") text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
      const auto parsed = ocu::Json::parse(text, nullptr, false);
      if (parsed.is_discarded())
        return void(exit_code = bad_input("send", std::string(*message == "-" ? "stdin" : "the message") + " is not valid JSON"));
      auto contents = ocu::prepare_jss_message(parsed);
      if (!contents) return void(exit_code = bad_input("send", contents.error().message()));
      exit_code = with_jss_session("send", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_send(s, *id, *contents, c->timeout, io);
      });
      return;
    }
    auto c = checked_common("send", exit_code);
    if (!c) return;
    auto address = ocu::parse_address(*target, true);
    if (!address) return void(exit_code = bad_input("send", address.error().message()));
    std::string text = *message;
    if (text == "-") text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    const auto parsed = ocu::Json::parse(text, nullptr, false);
    if (parsed.is_discarded())
      return void(exit_code = bad_input("send", std::string(*message == "-" ? "stdin" : "the message") + " is not valid JSON"));
    auto prepared = ocu::prepare_message(parsed, c->session.dialect);
    if (!prepared) return void(exit_code = bad_input("send", prepared.error().message()));
    // What happens while another process acts as the ID: operator_identity.hpp (IdUse).
    const auto use = prepared->header.command_code <= 0x1FFF ? ocu::IdUse::shares : ocu::IdUse::looks;
    exit_code = with_session("send", *c, use, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_send(s, *address, *prepared, c->timeout, io);
    });
  });

  // control
  auto authority = std::make_shared<std::string>();
  auto hold_for = std::make_shared<std::string>();
  auto* control = app.add_subcommand(
      "control", "Take control of ADDR and hold it until Ctrl-C (or --for); release it on exit");
  control->add_option("ADDR", *target, "component address S.N.C.I")->type_name("S.N.C.I")->required();
  control->add_option("--authority", *authority, "authority of the request, 0..255")->type_name("N")->required();
  control->add_option("--for", *hold_for, "release after this many seconds")->type_name("SECONDS");
  auto repeated = std::make_shared<std::string>();
  auto repeat_rate = std::make_shared<std::string>();
  auto resume_when_ready = std::make_shared<bool>(false);
  // Safety: by default a stop someone else caused (Emergency, Standby, ...)
  // ends the stream for good; only the operator starts the motion again.
  control->add_option("--send", *repeated,
                      "repeat this message (JSON as for `send`) to ADDR while it is Ready; else stop, exit 3")
      ->type_name("JSON");
  control->add_option("--rate", *repeat_rate, "how often --send sends, in Hz (default 10)")->type_name("HZ");
  control->add_flag("--resume-when-ready", *resume_when_ready,
                    "resume once Ready. UNSAFE: a Clear Emergency or Resume by anyone restarts the motion");
  add_common_options(control, *common);
  control->callback([&exit_code, common, checked_common, checked_jss, target, authority, hold_for, repeated,
                     repeat_rate, resume_when_ready] {
    if (is_jss(*common)) {
      auto c = checked_jss("control", exit_code);
      if (!c) return;
      ocu::JssControlCommand command;
      auto id = ocu::parse_jss_id(*target, false);
      if (!id) return void(exit_code = bad_input("control", id.error().message()));
      auto level = ocu::parse_authority(*authority);
      if (!level) return void(exit_code = bad_input("control", "--authority: " + level.error().message()));
      if (!hold_for->empty()) {
        auto seconds = ocu::parse_seconds(*hold_for);
        if (!seconds) return void(exit_code = bad_input("control", "--for: " + seconds.error().message()));
        command.hold_for = *seconds;
      }
      if (!repeated->empty() || !repeat_rate->empty() || *resume_when_ready)
        return void(exit_code = bad_input("control", "--send, --rate and --resume-when-ready are RA only"));
      command.target = *id;
      command.authority = *level;
      command.timeout = c->timeout;
      exit_code = with_jss_session("control", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_control(s, command, io);
      });
      return;
    }
    auto c = checked_common("control", exit_code);
    if (!c) return;
    ocu::ControlOptions options;
    auto address = ocu::parse_address(*target, false);
    if (!address) return void(exit_code = bad_input("control", address.error().message()));
    auto level = ocu::parse_authority(*authority);
    if (!level) return void(exit_code = bad_input("control", "--authority: " + level.error().message()));
    if (!hold_for->empty()) {
      auto seconds = ocu::parse_seconds(*hold_for);
      if (!seconds) return void(exit_code = bad_input("control", "--for: " + seconds.error().message()));
      options.hold_for = *seconds;
    }
    if (!repeated->empty()) {
      const auto parsed = ocu::Json::parse(*repeated, nullptr, false);
      if (parsed.is_discarded()) return void(exit_code = bad_input("control", "--send: not valid JSON"));
      auto prepared = ocu::prepare_message(parsed, c->session.dialect);
      if (!prepared) return void(exit_code = bad_input("control", "--send: " + prepared.error().message()));
      options.send = std::move(*prepared);
    } else if (!repeat_rate->empty()) {
      return void(exit_code = bad_input("control", "--rate needs --send"));
    } else if (*resume_when_ready) {
      return void(exit_code = bad_input("control", "--resume-when-ready needs --send"));
    }
    options.resume_when_ready = *resume_when_ready;
    if (!repeat_rate->empty()) {
      auto hz = ocu::parse_rate_hz(*repeat_rate);
      if (!hz) return void(exit_code = bad_input("control", "--rate: " + hz.error().message()));
      options.send_rate_hz = *hz;
    }
    options.target = *address;
    options.authority = *level;
    options.timeout = c->timeout;
    c->session.authority = *level;
    exit_code = with_session("control", *c, ocu::IdUse::holds, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_control(s, options, io);
    });
  });

  // subscribe
  auto rate = std::make_shared<std::string>();
  auto count = std::make_shared<std::string>();
  auto run_for = std::make_shared<std::string>();
  auto* subscribe = app.add_subcommand(
      "subscribe", "Service connection for report CODE from ADDR: one JSON line per report; rate on stderr");
  subscribe->add_option("ADDR", *target, "component address S.N.C.I")->type_name("S.N.C.I")->required();
  subscribe->add_option("CODE", *code, "report code (0x4002) or name (\"Report Component Status\")")->type_name("CODE")->required();
  subscribe->add_option("--rate", *rate, "reports per second (up to 1092); required but with --every-change")
      ->type_name("HZ");
  auto every_change = std::make_shared<bool>(false);
  subscribe->add_flag("--every-change", *every_change, "jss: an event on every change of the report, not periodic");
  subscribe->add_option("--pv", *pv, "presence vector, hex (which fields each report carries)")->type_name("HEX");
  subscribe->add_option("--count", *count, "stop after this many reports")->type_name("N");
  subscribe->add_option("--for", *run_for, "stop after this many seconds")->type_name("SECONDS");
  subscribe->add_option("--save-image", *save_image,
                        "write the picture of each Report Image over FILE (the latest one stays)")
      ->type_name("FILE");
  add_common_options(subscribe, *common);
  subscribe->callback([&exit_code, common, checked_common, checked_jss, target, code, rate, every_change, pv, count,
                       run_for, save_image] {
    if (is_jss(*common)) {
      auto c = checked_jss("subscribe", exit_code);
      if (!c) return;
      ocu::JssSubscribeCommand command;
      auto id = ocu::parse_jss_id(*target, false);
      if (!id) return void(exit_code = bad_input("subscribe", id.error().message()));
      auto info = ocu::parse_jss_message(*code);
      if (!info) return void(exit_code = bad_input("subscribe", info.error().message()));
      // A report names the event by its query (Report X -> Query X); a query is taken as it is.
      const auto* query_info = *info;
      if (query_info->message_class == jaus::msg::MessageClass::inform)
        query_info =
            jaus::msg::find_message(jaus::wire::Dialect::jss, static_cast<std::uint16_t>(query_info->code - 0x2000));
      if (!query_info || query_info->message_class != jaus::msg::MessageClass::query)
        return void(exit_code = bad_input("subscribe", std::string((*info)->name) + " is neither a report nor a query"));
      auto query_fields = ocu::Json::object();
      if (!pv->empty()) {
        auto parsed_pv = ocu::parse_presence_vector(*pv);
        if (!parsed_pv) return void(exit_code = bad_input("subscribe", "--pv: " + parsed_pv.error().message()));
        query_fields["presence_vector"] = *parsed_pv;
      }
      auto prepared = ocu::prepare_jss_query(*query_info, query_fields);
      if (!prepared) return void(exit_code = bad_input("subscribe", prepared.error().message()));
      if (*every_change == !rate->empty())
        return void(exit_code = bad_input("subscribe", "give either --rate HZ or --every-change"));
      if (!rate->empty()) {
        auto hz = ocu::parse_rate_hz(*rate);
        if (!hz) return void(exit_code = bad_input("subscribe", "--rate: " + hz.error().message()));
        command.rate_hz = *hz;
      }
      if (!count->empty()) {
        auto n = ocu::parse_count(*count);
        if (!n) return void(exit_code = bad_input("subscribe", "--count: " + n.error().message()));
        command.count = *n;
      }
      if (!run_for->empty()) {
        auto seconds = ocu::parse_seconds(*run_for);
        if (!seconds) return void(exit_code = bad_input("subscribe", "--for: " + seconds.error().message()));
        command.run_for = *seconds;
      }
      if (!save_image->empty()) return void(exit_code = bad_input("subscribe", "--save-image is for RA Report Image"));
      command.target = *id;
      command.query = std::move(*prepared);
      command.every_change = *every_change;
      command.timeout = c->timeout;
      exit_code = with_jss_session("subscribe", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_subscribe(s, command, io);
      });
      return;
    }
    if (*every_change) return void(exit_code = bad_input("subscribe", "--every-change needs --dialect jss"));
    if (rate->empty()) return void(exit_code = bad_input("subscribe", "--rate is required"));
    auto c = checked_common("subscribe", exit_code);
    if (!c) return;
    ocu::SubscribeOptions options;
    auto address = ocu::parse_address(*target, false);
    if (!address) return void(exit_code = bad_input("subscribe", address.error().message()));
    auto parsed_code = ocu::parse_message_code(*code);
    if (!parsed_code) return void(exit_code = bad_input("subscribe", parsed_code.error().message()));
    if (const auto report = ocu::report_code_for(*parsed_code))
      return void(exit_code = bad_input("subscribe", ocu::code_text(*parsed_code) +
                                                         " is a query: subscribe takes the report's code (" +
                                                         ocu::code_text(*report) + ")"));
    auto hz = ocu::parse_rate_hz(*rate);
    if (!hz) return void(exit_code = bad_input("subscribe", "--rate: " + hz.error().message()));
    if (!pv->empty()) {
      auto parsed_pv = ocu::parse_presence_vector(*pv);
      if (!parsed_pv) return void(exit_code = bad_input("subscribe", "--pv: " + parsed_pv.error().message()));
      options.presence_vector = *parsed_pv;
    }
    if (!count->empty()) {
      auto n = ocu::parse_count(*count);
      if (!n) return void(exit_code = bad_input("subscribe", "--count: " + n.error().message()));
      options.count = *n;
    }
    if (!run_for->empty()) {
      auto seconds = ocu::parse_seconds(*run_for);
      if (!seconds) return void(exit_code = bad_input("subscribe", "--for: " + seconds.error().message()));
      options.run_for = *seconds;
    }
    if (!save_image->empty()) {
      if (*parsed_code != jaus::msg::ReportImage::code)
        return void(exit_code = bad_input("subscribe", "--save-image needs Report Image (0x4807)"));
      options.save_image = *save_image;
    }
    options.target = *address;
    options.report_code = *parsed_code;
    options.rate_hz = *hz;
    options.timeout = c->timeout;
    exit_code = with_session("subscribe", *c, ocu::IdUse::looks, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_subscribe(s, options, io);
    });
  });

  // emergency
  auto action = std::make_shared<std::string>();
  auto* emergency = app.add_subcommand(
      "emergency", "Set or clear the emergency (Stop) condition of ADDR; repeated every 50 ms until ACKed");
  emergency->add_option("ADDR", *target, "component address S.N.C.I (255s: every component it names, each confirming)")->type_name("S.N.C.I")->required();
  emergency
      ->add_option("ACTION", *action,
                   "set: Set Emergency (ADDR stops); clear: Clear Emergency (this OCU's hold; others' stay)")
      ->type_name("set|clear")
      ->required();
  add_common_options(emergency, *common);
  emergency->callback([&exit_code, common, checked_common, checked_jss, target, action] {
    if (is_jss(*common)) {
      auto c = checked_jss("emergency", exit_code);
      if (!c) return;
      auto id = ocu::parse_jss_id(*target, true);
      if (!id) return void(exit_code = bad_input("emergency", id.error().message()));
      if (*action != "set" && *action != "clear")
        return void(exit_code = bad_input("emergency", "bad action '" + *action + "': expected set or clear"));
      exit_code = with_jss_session("emergency", *c, [&](ocu::JssSession& s, ocu::CommandIo io) {
        return ocu::run_jss_emergency(s, *id, *action == "set", c->timeout, io);
      });
      return;
    }
    auto c = checked_common("emergency", exit_code);
    if (!c) return;
    auto address = ocu::parse_address(*target, true);
    if (!address) return void(exit_code = bad_input("emergency", address.error().message()));
    if (*action != "set" && *action != "clear")
      return void(exit_code = bad_input("emergency", "bad action '" + *action + "': expected set or clear"));
    exit_code = with_session("emergency", *c, ocu::IdUse::shares, [&](ocu::OcuSession& s, ocu::CommandIo io) {
      return ocu::run_emergency(s, *address, *action == "set", c->timeout, io);
    });
  });
}

}  // namespace jausctl
