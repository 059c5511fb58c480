#include "catalogue_entries.hpp"

namespace jaus::msg::detail {
std::vector<MessageInfo> discovery_and_event_entries() {
  auto entries = entries_of(DiscoveryMessages{});
  auto events = entries_of(EventMessages{});
  entries.insert(entries.end(), events.begin(), events.end());
  return entries;
}
}  // namespace jaus::msg::detail
