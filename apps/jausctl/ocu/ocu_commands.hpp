// The OCU commands of jausctl, each on an open session. Inputs are already
// parsed and checked (bad input never gets this far); each returns the exit
// code (kExitOk, or kExitFailure with one line on `err`) and prints its
// results on `out`.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "cli_values.hpp"
#include "exit_codes.hpp"
#include "jaus/ocu/control_hold.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/session.hpp"

namespace jausctl::ocu {

struct CommandIo {
  CommandIo(std::ostream& out_stream, std::ostream& err_stream, bool shared = false)
      : out(out_stream), err(err_stream), id_shared(shared) {}
  std::ostream& out;
  std::ostream& err;
  // Another process acts as this OCU's ID too (operator_identity.hpp,
  // IdUse::shares): a message addressed to it may be that process's reply,
  // so a command reads no reply as its own, only its own ACKs.
  bool id_shared;
};

struct DiscoverOptions {
  jaus::rt::Duration wait = std::chrono::seconds(2);
  bool json = false;
};
int run_discover(OcuSession& session, const DiscoverOptions& options, CommandIo io);

// Query Component Status -> {"component":"1.1.35.1","primary_status":"Ready",...}
int run_status(OcuSession& session, const jaus::Address& target, jaus::rt::Duration timeout, CommandIo io);

// Sends a prepared query and prints the report (`jausctl msg decode` form);
// with `save_image`, a Report Image's picture goes to that file
// (image_file.hpp) and the printed line says so.
int run_query(OcuSession& session, const jaus::Address& target, const PreparedMessage& query,
              std::uint16_t report_code, jaus::rt::Duration timeout, CommandIo io,
              const std::optional<std::string>& save_image = std::nullopt);

// Sends any message; prints the first message the target sends back within
// the timeout, if any.
int run_send(OcuSession& session, const jaus::Address& target, const PreparedMessage& message,
             jaus::rt::Duration timeout, CommandIo io);

// Set or Clear Emergency, then Query Component Status to show the result.
int run_emergency(OcuSession& session, const jaus::Address& target, bool set, jaus::rt::Duration timeout,
                  CommandIo io);

struct ControlOptions {
  jaus::Address target;
  std::uint8_t authority = 0;
  std::optional<jaus::rt::Duration> hold_for;  // none: until SIGINT/SIGTERM
  jaus::rt::Duration timeout = std::chrono::seconds(1);
  // No Report Component Status (5 Hz service connection) for this long: control is lost.
  jaus::rt::Duration status_silence = std::chrono::seconds(5);
  // A command sent to the target at `send_rate_hz` while control is held (--send, --rate).
  // Sent only while the component is Ready: by default the first other state
  // stops it for good (control released, kExitLeftReady); --resume-when-ready
  // pauses it instead and sends again once the component is Ready.
  std::optional<PreparedMessage> send;
  double send_rate_hz = 10;
  bool resume_when_ready = false;
};
int run_control(OcuSession& session, const ControlOptions& options, CommandIo io);
// What run_control says of a request: "control of 1.1.35.1 granted to
// 254.7.40.1 (authority 5)" (`self`, the ID that holds it), "control of
// 1.1.35.1 refused: not available (response 2)", the error's line, ...
std::string control_request_text(const ControlHold::RequestResult& result, const jaus::Address& target,
                                 std::uint8_t authority, const jaus::Address& self);

struct SubscribeOptions {
  jaus::Address target;
  std::uint16_t report_code = 0;
  double rate_hz = 1;
  std::uint32_t presence_vector = 0;
  std::optional<std::uint64_t> count;          // stop after this many reports
  std::optional<jaus::rt::Duration> run_for;   // stop after this long
  jaus::rt::Duration timeout = std::chrono::seconds(1);
  jaus::rt::Duration rate_every = std::chrono::seconds(5);  // measured rate on `err` this often
  std::optional<std::string> save_image;  // each Report Image's picture written over this file
};
int run_subscribe(OcuSession& session, const SubscribeOptions& options, CommandIo io);

}  // namespace jausctl::ocu
