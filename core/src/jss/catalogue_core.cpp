#include "../catalogue_entries.hpp"
#include "jaus/jss/all.hpp"

// The codecs of the core services' bodies (jaus/jss/compiled_codecs.hpp).
namespace jaus {
JAUS_JSS_ALL_BODIES(JAUS_DECLARE_JSON_CODEC)
JAUS_JSS_CORE_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::msg::detail {
std::vector<MessageInfo> jss_core_entries() {
  namespace m = jss::msg;
  constexpr auto kJss = wire::Dialect::jss;
  std::vector<MessageInfo> out;
  for (auto part : {entries_of<kJss>(m::AccessControlMessages{}), entries_of<kJss>(m::ManagementMessages{}),
                    entries_of<kJss>(m::TimeMessages{}), entries_of<kJss>(m::LivenessMessages{}),
                    entries_of<kJss>(m::EventsMessages{}), entries_of<kJss>(m::DiscoveryMessages{})})
    out.insert(out.end(), part.begin(), part.end());
  return out;
}
}  // namespace jaus::msg::detail
