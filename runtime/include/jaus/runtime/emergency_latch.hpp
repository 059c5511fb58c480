// Who holds the component in Emergency. Part 3: "all conditions that have
// been set must be specifically cleared". Our rule: every sender that set the
// Stop condition holds it until that same sender clears it; the component
// leaves Emergency only when nobody holds it. A clear from someone who holds
// nothing is refused (and logged by the caller). The latch survives Reset.
#pragma once

#include <set>
#include <vector>

#include "jaus/core/address.hpp"

namespace jaus::rt {

class EmergencyLatch {
 public:
  // Returns true when this is the first holder (the component enters Emergency).
  bool set(const Address& holder) {
    const bool was_clear = holders_.empty();
    holders_.insert(holder);
    return was_clear;
  }

  enum class ClearResult { released_last, still_held, not_a_holder };
  ClearResult clear(const Address& holder) {
    if (holders_.erase(holder) == 0) return ClearResult::not_a_holder;
    return holders_.empty() ? ClearResult::released_last : ClearResult::still_held;
  }

  bool active() const { return !holders_.empty(); }
  std::vector<Address> holders() const { return {holders_.begin(), holders_.end()}; }

 private:
  std::set<Address> holders_;
};

}  // namespace jaus::rt
