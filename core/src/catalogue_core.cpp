#include "catalogue_entries.hpp"
#include "jaus/messages/all.hpp"

// The codec of the bodies listed for this file (jaus/messages/compiled_codecs.hpp).
namespace jaus {
JAUS_CORE_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::msg::detail {
std::vector<MessageInfo> core_entries() { return entries_of<wire::Dialect::ra>(CoreMessages{}); }
}  // namespace jaus::msg::detail
