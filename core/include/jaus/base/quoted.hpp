// A value quoted for an error message: on one line, control characters
// replaced, cut after 60 characters. User input (configuration values,
// command-line arguments) is echoed through this, never raw.
#pragma once

#include <string>
#include <string_view>

namespace jaus {

std::string quoted(std::string_view text);

}  // namespace jaus
