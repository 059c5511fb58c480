#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> manipulator_entries() { return entries_of(ManipulatorMessages{}); }
}  // namespace jaus::msg::detail
