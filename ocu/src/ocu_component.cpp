#include "jaus/ocu/ocu_component.hpp"

#include <algorithm>

namespace jaus::ocu {

bool OcuComponent::consumes(std::uint16_t code) const {
  return std::binary_search(consumed_.begin(), consumed_.end(), code);
}

}  // namespace jaus::ocu
