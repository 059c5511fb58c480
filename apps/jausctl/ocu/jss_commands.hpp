// jausctl's commands with --dialect jss: the same commands as an SAE JAUS
// (JSS) operator unit on a jaus::ocu::JssSession (AS5669A, JSS IDs S.N.C,
// JSS messages by the JSS catalogue). Inputs are parsed and checked first
// (bad input: exit 2, one line); each command returns its exit code and
// prints what the RA command prints, in the JSS's terms.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli_values.hpp"
#include "exit_codes.hpp"
#include "jaus/jss/catalogue.hpp"
#include "jaus/ocu/jss_session.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

// The options every command shares, as written on the command line.
struct JssCommonText {
  std::vector<std::string> to;
  std::string multicast;
  std::string bind = "0.0.0.0:0";
  std::string as;  // empty: a fresh 200.N.1 each run
  std::string timeout = "1";
};
struct JssCommon {
  JssSessionOptions session;
  jaus::rt::Duration timeout{};
};
Parsed<JssCommon> parse_jss_common(const JssCommonText& text);

// "S.N.C": subsystem 1..65534 (65535 all), node and component 1..254 (255 all where `allow_broadcast`).
Parsed<jaus::jss::JssId> parse_jss_id(std::string_view text, bool allow_broadcast);
// "0x2404", "2404" (hex), or a JSS message name ("Query Velocity State", "QueryVelocityState").
Parsed<const jaus::msg::MessageInfo*> parse_jss_message(std::string_view text);
// The contents of a query with its fields (JSON object; fields left out are 0), and its report's ID.
struct JssPreparedQuery {
  std::vector<std::uint8_t> contents;
  std::uint16_t report_id = 0;
};
Parsed<JssPreparedQuery> prepare_jss_query(const jaus::msg::MessageInfo& query, const Json& fields);
// A message as `jausctl msg decode --dialect jss` prints its contents ({"id" or "name", "fields"}).
Parsed<std::vector<std::uint8_t>> prepare_jss_message(const Json& message);

int run_jss_discover(JssSession& session, jaus::rt::Duration wait, bool json, CommandIo io);
// Query Status -> {"component":"1.1.33","primary_status":"ready","primary_status_code":1,"emergency":false}
int run_jss_status(JssSession& session, const jaus::jss::JssId& target, jaus::rt::Duration timeout, CommandIo io);
int run_jss_query(JssSession& session, const jaus::jss::JssId& target, const JssPreparedQuery& query,
                  jaus::rt::Duration timeout, CommandIo io);
// Commands (IDs below 0x2000) go with an ACK request, resent until ACKed.
int run_jss_send(JssSession& session, const jaus::jss::JssId& target, const std::vector<std::uint8_t>& message,
                 jaus::rt::Duration timeout, CommandIo io);
int run_jss_emergency(JssSession& session, const jaus::jss::JssId& target, bool set, jaus::rt::Duration timeout,
                      CommandIo io);

struct JssControlCommand {
  jaus::jss::JssId target;
  std::uint8_t authority = 0;
  std::optional<jaus::rt::Duration> hold_for;  // none: until SIGINT/SIGTERM
  jaus::rt::Duration timeout = std::chrono::seconds(1);
};
int run_jss_control(JssSession& session, const JssControlCommand& command, CommandIo io);

struct JssSubscribeCommand {
  jaus::jss::JssId target;
  JssPreparedQuery query;     // the event's query (a report given on the command line: its query)
  bool every_change = false;  // else periodic at rate_hz
  double rate_hz = 1;
  std::optional<std::uint64_t> count;
  std::optional<jaus::rt::Duration> run_for;
  jaus::rt::Duration timeout = std::chrono::seconds(1);
};
int run_jss_subscribe(JssSession& session, const JssSubscribeCommand& command, CommandIo io);

// `jausctl msg ... --dialect jss`.
int jss_msg_decode(const std::string& hex, CommandIo io);
int jss_msg_encode(const std::string& json_text, CommandIo io);

}  // namespace jausctl::ocu
