#include "../catalogue_entries.hpp"
#include "jaus/jss/all.hpp"

// The codecs of the mobility services' bodies (jaus/jss/compiled_codecs.hpp).
namespace jaus {
JAUS_JSS_ALL_BODIES(JAUS_DECLARE_JSON_CODEC)
JAUS_JSS_MOBILITY_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::msg::detail {
std::vector<MessageInfo> jss_mobility_entries() {
  auto out = entries_of<wire::Dialect::jss>(jss::msg::SensorDriverMessages{});
  auto waypoints = entries_of<wire::Dialect::jss>(jss::msg::WaypointMessages{});
  out.insert(out.end(), waypoints.begin(), waypoints.end());
  return out;
}
}  // namespace jaus::msg::detail
