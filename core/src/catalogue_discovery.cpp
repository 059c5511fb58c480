#include "catalogue_entries.hpp"
#include "jaus/messages/all.hpp"

// The codec of the bodies listed for this file (jaus/messages/compiled_codecs.hpp).
namespace jaus {
JAUS_DISCOVERY_AND_EVENT_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::msg::detail {
std::vector<MessageInfo> discovery_and_event_entries() {
  auto entries = entries_of<wire::Dialect::ra>(DiscoveryMessages{});
  auto events = entries_of<wire::Dialect::ra>(EventMessages{});
  entries.insert(entries.end(), events.begin(), events.end());
  return entries;
}
}  // namespace jaus::msg::detail
