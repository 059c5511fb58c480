// A plugin that needs a function nothing defines: it cannot be loaded.
#include "broken_plugins.hpp"

void jaus_test_defined_nowhere();

namespace {
std::vector<jaus::rt::ComponentKind> kinds() {
  jaus_test_defined_nowhere();
  return broken::one_kind();
}
}  // namespace

JAUS_COMPONENT_PLUGIN("undefined_symbol", kinds)
