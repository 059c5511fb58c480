#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> environment_entries() { return entries_of(EnvironmentMessages{}); }
}  // namespace jaus::msg::detail
