// Sub-command groups of jausctl. Each group registers its commands on the
// application; handlers run after parsing and set the process exit code.
#pragma once

#include <CLI/CLI.hpp>

namespace jausctl {

// Exit codes shared by every command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  // the command ran but its target did not answer / failed
inline constexpr int kExitBadInput = 2; // bad arguments or malformed input

// `jausctl msg ...`: JAUS message codec (decode, encode, list).
void add_msg_commands(CLI::App& app, int& exit_code);

// `jausctl clearpath ...`: Clearpath protocol codec (decode, encode, list).
void add_clearpath_commands(CLI::App& app, int& exit_code);

}  // namespace jausctl
