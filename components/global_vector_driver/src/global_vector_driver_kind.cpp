#include "jaus/components/global_vector_driver_kind.hpp"

#include "jaus/components/global_vector_driver.hpp"
#include "jaus/components/mobility_driver_kind.hpp"
#include "jaus/core/component_ids.hpp"

namespace jaus::components {

const rt::ComponentKind& global_vector_driver_kind() {
  static const rt::ComponentKind kind =
      mobility_driver_kind<GlobalVectorDriver>("global_vector_driver", component_id::kGlobalVectorDriver,
                                               vector_driver_option_keys(), vector_driver_options, DriverFrame::any);
  return kind;
}

}  // namespace jaus::components
