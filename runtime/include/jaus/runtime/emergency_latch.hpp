// Who holds the component in Emergency. Part 3: "all conditions that have
// been set must be specifically cleared". Our rule: every sender that set the
// Stop condition holds it until that same sender clears it; the component
// leaves Emergency only when nobody holds it. A clear from someone who holds
// nothing is refused (and logged by the caller). The latch survives Reset.
// At most kMaxHolders are remembered, so forged senders cannot grow it without
// bound; a holder beyond them is not recorded, and the component stays in
// Emergency, held by the others (the safe side: a flood can keep a vehicle
// stopped, never move it).
#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "jaus/core/address.hpp"

namespace jaus::rt {

class EmergencyLatch {
 public:
  static constexpr std::size_t kMaxHolders = 16;

  // Returns true when this is the first holder (the component enters Emergency).
  // `always`: the component's own hold (its hardware e-stop), recorded even
  // when kMaxHolders others hold it, so that forged clears can never release it.
  bool set(const Address& holder, bool always = false) {
    const bool was_clear = holders_.empty();
    if (always || holders_.size() < kMaxHolders || holders_.contains(holder))
      holders_.insert(holder);
    else
      ++unrecorded_;
    return was_clear;
  }
  // Holders not recorded because kMaxHolders others held the latch.
  std::uint64_t unrecorded() const { return unrecorded_; }

  enum class ClearResult { released_last, still_held, not_a_holder };
  ClearResult clear(const Address& holder) {
    if (holders_.erase(holder) == 0) return ClearResult::not_a_holder;
    return holders_.empty() ? ClearResult::released_last : ClearResult::still_held;
  }

  bool active() const { return !holders_.empty(); }
  std::vector<Address> holders() const { return {holders_.begin(), holders_.end()}; }

 private:
  std::set<Address> holders_;
  std::uint64_t unrecorded_ = 0;
};

}  // namespace jaus::rt
