// Placeholder until the Clearpath codec lands (issue 5): registers nothing.
#include "commands.hpp"

namespace jausctl {
void add_clearpath_commands(CLI::App&, int&) {}
}  // namespace jausctl
