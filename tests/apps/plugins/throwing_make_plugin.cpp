// A plugin whose kind checks and makes by throwing: its check throws for
// `explode: true`, its make always.
#include <stdexcept>

#include "broken_plugins.hpp"

namespace {
std::vector<jaus::rt::ComponentKind> kinds() {
  auto kind = broken::kind("throwing_maker");
  kind.options = {"explode"};
  kind.check = [](const jaus::rt::KindOptions& options) -> jaus::Expected<void> {
    if (options.values.contains("explode")) throw std::runtime_error("options exploded");
    return {};
  };
  kind.make = [](const jaus::rt::KindContext&) -> jaus::Expected<std::unique_ptr<jaus::rt::Component>> {
    throw std::runtime_error("device busy");
  };
  return {kind};
}
}  // namespace

JAUS_COMPONENT_PLUGIN("throwing_maker", kinds)
