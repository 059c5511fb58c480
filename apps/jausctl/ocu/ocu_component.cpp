#include "ocu_component.hpp"

#include <algorithm>

namespace jausctl::ocu {

bool OcuComponent::consumes(std::uint16_t code) const {
  return std::binary_search(consumed_.begin(), consumed_.end(), code);
}

}  // namespace jausctl::ocu
