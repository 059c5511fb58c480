// jausctl: the project's command-line tool: the message codecs (msg,
// clearpath) and an operator control unit (discover, status, query, send,
// control, subscribe, emergency).
#include "commands.hpp"
#include "jaus/base/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"jausctl: JAUS node command-line tool"};
  app.set_version_flag("--version", "jausctl " + std::string(jaus::kVersion));
  app.require_subcommand(1);
  // Bad command lines are one line on stderr (exit 2), like every other bad input.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "jausctl: " + std::string(e.what()) + " (--help for usage)\n";
  });
  int exit_code = jausctl::kExitOk;
  jausctl::add_msg_commands(app, exit_code);
  jausctl::add_clearpath_commands(app, exit_code);
  jausctl::add_ocu_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : jausctl::kExitBadInput;
  }
  return exit_code;
}
