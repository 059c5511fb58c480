// Who holds a component (or a whole vehicle) in Emergency. Part 3: "all
// conditions that have been set must be specifically cleared". Our rule:
// every sender that set the Stop condition holds it until that same sender
// clears it; the latch is clear only when nobody holds it. A clear from
// someone who holds nothing is refused (and logged by the caller).
//
// Two kinds of holds:
//   - JAUS holders (Set Emergency), one per source address, cleared only by
//     the same address (Clear Emergency) or by a local command on the vehicle
//     (clear_jaus_holders: `jausd --clear-emergency-holds`, logged);
//   - local holds by name (the platform's e-stop or pause, the platform's
//     emergency flag not yet confirmed clear), held and released by the host.
//
// Safety, bounded without forgetting anyone: at most kMaxHolders JAUS holders
// are recorded by address. A holder beyond them cannot be recorded, so it
// could never clear its own hold by address; instead the latch becomes
// `overflowed`, which holds it like a holder that never clears (a flood of
// forged senders can keep a vehicle stopped, never move it). An overflowed
// latch is cleared only by the local command. Nothing is ever dropped.
// A Set Emergency from a sender the node could not record at all (its
// liveness table or the transport's routes were full: hold_unrecorded) is
// held the same way: its ID is not tied to anyone the node can tell apart,
// so no Clear Emergency can be trusted to be its own (issue 28).
//
// A latch may be shared by several components (emergency_scope: vehicle):
// each component is a member and follows active(). Observers hear every
// change (the host persists the holders and mirrors them onto the platform)
// before the members follow it, so an observer may add a local hold in
// response and the members never leave Emergency in between.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/core/address.hpp"

namespace jaus::rt {

class EmergencyLatch {
 public:
  static constexpr std::size_t kMaxHolders = 64;

  // What a member is told: follow active() now (enter or leave Emergency).
  using Member = std::function<void()>;
  using MemberId = std::uint64_t;
  // Hears every change of the holders, local holds or overflow.
  using Observer = std::function<void(const EmergencyLatch&)>;

  EmergencyLatch() = default;
  EmergencyLatch(const EmergencyLatch&) = delete;
  EmergencyLatch& operator=(const EmergencyLatch&) = delete;

  // A JAUS holder sets the Stop condition. Returns true when this made the
  // latch active (it was clear before).
  bool set(const Address& holder);
  // A Set Emergency from a sender the node could not record: held like the
  // overflow (until the local clear), its address never recorded. Returns
  // true when this made the latch active.
  bool hold_unrecorded();
  // refused: the holder's clear is refused while clears are held back
  // (refuse_clears): its hold stays.
  enum class ClearResult { released_last, still_held, not_a_holder, refused };
  ClearResult clear(const Address& holder);
  // While set, clear() of a JAUS holder is refused and the hold stays: the
  // host cannot persist the holds, and a clear it cannot write could come
  // back as a different hold after a restart, or a Set it could not write be
  // lost with the clear (issue 42). The local clear still works.
  void refuse_clears(bool refuse) { clears_refused_ = refuse; }
  bool clears_refused() const { return clears_refused_; }

  // A local hold by name; returns true when it is new.
  bool hold_local(std::string_view cause);
  ClearResult release_local(std::string_view cause);

  // The local command for holders gone for good: every JAUS holder and the
  // overflow are cleared (local holds stay). Returns how many were held.
  std::size_t clear_jaus_holders();
  // Holders restored from a persisted state (before any member joins).
  void restore(const std::vector<Address>& holders, bool overflowed);

  bool active() const { return held_by_jaus() || !local_.empty(); }
  // Held by Set Emergency (recorded or not): what the platform's emergency flag mirrors.
  bool held_by_jaus() const { return !holders_.empty() || overflowed_; }
  // Held by senders not recorded by address (beyond kMaxHolders, or
  // unrecorded by the node): cleared only by the local command.
  bool overflowed() const { return overflowed_; }
  std::vector<Address> holders() const { return {holders_.begin(), holders_.end()}; }
  // A recorded holder at `where` (0 at a level: anything from there down, as
  // Address::covers). The node asks it of each route a flood touches: a
  // lookup in the ordered holders, no walk and no copy.
  bool held_by_any_under(const Address& where) const;
  std::vector<std::string> local_holds() const { return {local_.begin(), local_.end()}; }
  // Set Emergency from senders that could not be recorded (counted, never
  // forgotten): beyond kMaxHolders, or unrecorded by the node.
  std::uint64_t unrecorded() const { return unrecorded_; }
  // "3.1.40.1, 4.1.40.1, the platform's e-stop", for log lines.
  std::string describe_holders() const;
  // The JAUS holder of the last set or clear (invalid after a local change), for log lines.
  const Address& last_changed_by() const { return last_by_; }

  MemberId join(Member member);
  void leave(MemberId id);
  void observe(Observer observer) { observers_.push_back(std::move(observer)); }

 private:
  void changed();

  std::set<Address> holders_;
  std::set<std::string, std::less<>> local_;
  bool overflowed_ = false;
  bool clears_refused_ = false;
  std::uint64_t unrecorded_ = 0;
  Address last_by_{};
  std::map<MemberId, Member> members_;
  MemberId next_member_ = 1;
  std::vector<Observer> observers_;
};

}  // namespace jaus::rt
