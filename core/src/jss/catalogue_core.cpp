#include "catalogue_entries.hpp"

// The codecs of the core services' bodies (jaus/jss/compiled_codecs.hpp).
namespace jaus {
JAUS_JSS_CORE_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::jss::detail {
std::vector<MessageInfo> core_entries() {
  std::vector<MessageInfo> out;
  append_entries(out, msg::AccessControlMessages{});
  append_entries(out, msg::ManagementMessages{});
  append_entries(out, msg::TimeMessages{});
  append_entries(out, msg::LivenessMessages{});
  append_entries(out, msg::EventsMessages{});
  append_entries(out, msg::DiscoveryMessages{});
  return out;
}
}  // namespace jaus::jss::detail
