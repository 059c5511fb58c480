// jausctl: the project's command-line tool (message codecs now; OCU commands
// arrive with the transport issue).
#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"jausctl: JAUS node command-line tool"};
  app.require_subcommand(1);
  int exit_code = jausctl::kExitOk;
  jausctl::add_msg_commands(app, exit_code);
  jausctl::add_clearpath_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : jausctl::kExitBadInput;
  }
  return exit_code;
}
