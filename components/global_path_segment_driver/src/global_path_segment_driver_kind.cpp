#include "jaus/components/global_path_segment_driver_kind.hpp"

#include "jaus/components/global_path_segment_driver.hpp"
#include "jaus/components/mobility_driver_kind.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& global_path_segment_driver_kind() {
  static const rt::ComponentKind kind = mobility_driver_kind<GlobalPathSegmentDriver>(
      "global_path_segment_driver", component_id::kGlobalPathSegmentDriver, path_segment_driver_option_keys(),
      path_segment_driver_options, DriverFrame::any);
  return kind;
}

}  // namespace jaus::components
