// The options of a component kind, checked from a ComponentSpec's text
// values (a configuration file's `options:` map) by the kind itself
// (rt::ComponentKind::check), for configuration readers that check a file
// before anything is built.
#pragma once

#include <optional>
#include <string>

#include "jaus/host/component_kinds.hpp"

namespace jaus::host {

// The spec's options are good, or the first problem with them; `line` is the
// option's line when the spec came from a file and knows it. A kind nobody
// knows has no problem here (configuration readers refuse the kind itself).
struct OptionProblem {
  std::string what;
  int line = 0;
};
Expected<void, OptionProblem> check_component_options(const ComponentSpec& spec);

}  // namespace jaus::host
