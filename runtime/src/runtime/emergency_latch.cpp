#include "jaus/runtime/emergency_latch.hpp"

namespace jaus::rt {

bool EmergencyLatch::set(const Address& holder) {
  const bool was_active = active();
  if (holders_.contains(holder)) return false;
  last_by_ = holder;
  if (holders_.size() < kMaxHolders) {
    holders_.insert(holder);
  } else {
    // Fail safe: a holder we cannot record holds the latch until the local clear.
    ++unrecorded_;
    if (overflowed_) return false;
    overflowed_ = true;
  }
  changed();
  return !was_active;
}

bool EmergencyLatch::hold_unrecorded() {
  const bool was_active = active();
  ++unrecorded_;
  last_by_ = Address{};  // nobody the node can name
  if (overflowed_) return false;
  overflowed_ = true;
  changed();
  return !was_active;
}

EmergencyLatch::ClearResult EmergencyLatch::clear(const Address& holder) {
  if (!holders_.contains(holder)) return ClearResult::not_a_holder;
  if (clears_refused_) return ClearResult::refused;  // the hold stays until it can be persisted
  holders_.erase(holder);
  last_by_ = holder;
  changed();
  return active() ? ClearResult::still_held : ClearResult::released_last;
}

bool EmergencyLatch::hold_local(std::string_view cause) {
  if (local_.contains(cause)) return false;
  local_.emplace(cause);
  last_by_ = Address{};
  changed();
  return true;
}

EmergencyLatch::ClearResult EmergencyLatch::release_local(std::string_view cause) {
  const auto it = local_.find(cause);
  if (it == local_.end()) return ClearResult::not_a_holder;
  local_.erase(it);
  last_by_ = Address{};
  changed();
  return active() ? ClearResult::still_held : ClearResult::released_last;
}

std::size_t EmergencyLatch::clear_jaus_holders() {
  const std::size_t held = holders_.size() + (overflowed_ ? 1 : 0);
  if (held == 0) return 0;
  holders_.clear();
  overflowed_ = false;
  last_by_ = Address{};
  changed();
  return held;
}

void EmergencyLatch::restore(const std::vector<Address>& holders, bool overflowed) {
  for (const auto& h : holders)
    if (holders_.size() < kMaxHolders) holders_.insert(h);
    else overflowed = true;
  overflowed_ = overflowed_ || overflowed;
  changed();
}

bool EmergencyLatch::held_by_any_under(const Address& where) const {
  // The addresses `where` covers share its levels above its first 0 and
  // follow one another in the set's order; the least of them is where it
  // would be with 0 from that level down.
  Address least = where;
  std::uint8_t* levels[] = {&least.subsystem, &least.node, &least.component, &least.instance};
  bool below_zero = false;
  for (std::uint8_t* level : levels) {
    below_zero = below_zero || *level == 0;
    if (below_zero) *level = 0;
  }
  const auto first = holders_.lower_bound(least);
  return first != holders_.end() && where.covers(*first);
}

std::string EmergencyLatch::describe_holders() const {
  std::string text;
  const auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  for (const auto& a : holders_) add(a.to_string());
  if (overflowed_)
    add("senders not recorded (beyond the " + std::to_string(kMaxHolders) +
        " or unknown to the node; cleared only locally)");
  for (const auto& l : local_) add(l);
  return text;
}

EmergencyLatch::MemberId EmergencyLatch::join(Member member) {
  const MemberId id = next_member_++;
  members_.emplace(id, std::move(member));
  return id;
}

void EmergencyLatch::leave(MemberId id) { members_.erase(id); }

void EmergencyLatch::changed() {
  // Observers first: one may add a local hold, so members see the final state.
  for (const auto& observer : observers_) observer(*this);
  // A member may leave while following (a component shut down by it): walk by id.
  for (auto it = members_.begin(); it != members_.end();) {
    const MemberId id = it->first;
    const Member member = it->second;
    member();
    it = members_.upper_bound(id);
  }
}

}  // namespace jaus::rt
