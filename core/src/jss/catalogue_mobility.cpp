#include "catalogue_entries.hpp"

// The codecs of the mobility services' bodies (jaus/jss/compiled_codecs.hpp).
namespace jaus {
JAUS_JSS_MOBILITY_BODIES(JAUS_DEFINE_CODEC)
}  // namespace jaus

namespace jaus::jss::detail {
std::vector<MessageInfo> mobility_entries() {
  std::vector<MessageInfo> out;
  append_entries(out, msg::SensorDriverMessages{});
  append_entries(out, msg::WaypointMessages{});
  return out;
}
}  // namespace jaus::jss::detail
