#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> communications_entries() { return entries_of(CommunicationsMessages{}); }
}  // namespace jaus::msg::detail
