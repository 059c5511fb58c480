#include "jaus/components/local_path_segment_driver_kind.hpp"

#include "jaus/components/local_path_segment_driver.hpp"
#include "jaus/components/mobility_driver_kind.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

// Its elements are in the vehicle's local frame: a pose source without one is refused.
const rt::ComponentKind& local_path_segment_driver_kind() {
  static const rt::ComponentKind kind = mobility_driver_kind<LocalPathSegmentDriver>(
      "local_path_segment_driver", component_id::kLocalPathSegmentDriver, path_segment_driver_option_keys(),
      path_segment_driver_options, DriverFrame::local);
  return kind;
}

}  // namespace jaus::components
