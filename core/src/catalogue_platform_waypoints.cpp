#include "catalogue_entries.hpp"
#include "jaus/messages/all.hpp"

// The codec of the bodies listed for this file (jaus/messages/compiled_codecs.hpp).
namespace jaus {
JAUS_PLATFORM_WAYPOINT_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::msg::detail {
std::vector<MessageInfo> platform_waypoint_entries() {
  return entries_of<wire::Dialect::ra, is_platform_waypoint>(PlatformMessages{});
}
}  // namespace jaus::msg::detail
