#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> platform_entries() { return entries_of(PlatformMessages{}); }
}  // namespace jaus::msg::detail
