#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> core_entries() { return entries_of(CoreMessages{}); }
}  // namespace jaus::msg::detail
