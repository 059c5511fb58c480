// Sub-command groups of jausctl. Each group registers its commands on the
// application; handlers run after parsing and set the process exit code.
#pragma once

#include <CLI/CLI.hpp>

#include "ocu/exit_codes.hpp"  // kExitOk 0, kExitFailure 1, kExitBadInput 2

namespace jausctl {

// `jausctl msg ...`: JAUS message codec (decode, encode, list).
void add_msg_commands(CLI::App& app, int& exit_code);

// `jausctl clearpath ...`: Clearpath protocol codec (decode, encode, list).
void add_clearpath_commands(CLI::App& app, int& exit_code);

// `jausctl discover | status | query | send | control | subscribe | emergency`:
// jausctl as an operator control unit talking to a JAUS node over UDP.
void add_ocu_commands(CLI::App& app, int& exit_code);

}  // namespace jausctl
