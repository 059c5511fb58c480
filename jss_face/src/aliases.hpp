// The RA aliases of JSS clients (face.hpp): a JSS client node (subsystem,
// node) gets a slot 1..N; its component C reaches our RA components as
// `alias_subsystem.slot.C.1`, and its event k's queries as
// `alias_subsystem.slot.C.(2 + k)`. So the RA components see each JSS client
// as one more RA peer node: control, authority, emergency holds, liveness.
//
// Bounded: at most `max_clients` slots (and never beyond 253). A new client
// takes a free slot, else the least recently heard slot the caller says may
// be reused (its alias node holds no state in the node and it has no
// events); when none may, the client is refused. Slot 254 is never given to
// a client: it is the alias of Set Emergency from a refused client, which is
// obeyed anyway (as from an unrecorded RA sender: a hold only the local clear
// releases).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/core/address.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss_face/translator.hpp"

namespace jaus::jss_face {

inline constexpr std::uint8_t kOwnChannel = 1;        // the client's own messages
inline constexpr std::uint8_t kFirstEventChannel = 2; // event k: channel 2 + k
inline constexpr std::uint8_t kMaxAliasEventId = 252; // 2 + 252 = 254, the last valid instance
inline constexpr std::uint8_t kMaxClientSlots = 253;
inline constexpr std::uint8_t kRefusedClientSlot = 254;

// A client node: the JSS ID with component 255 (all its components).
inline jss::JssId client_node_of(const jss::JssId& client) {
  return jss::JssId{client.subsystem, client.node, jss::JssId::kAll};
}

class AliasTable {
 public:
  AliasTable(std::uint8_t alias_subsystem, std::size_t max_clients);

  // May this slot be given to another client (nothing keeps state for it)?
  using Reusable = std::function<bool(std::uint8_t slot, const jss::JssId& client_node)>;
  // The slot of the client's node, made if needed: a free one, else the least
  // recently heard reusable one, whose client `forgotten` names. nullopt:
  // every slot is taken by a client that holds state. (Only heard() and a new
  // slot count as hearing from the client.)
  struct Assigned {
    std::uint8_t slot = 0;
    std::optional<jss::JssId> forgotten;  // a client node that lost its slot to this one
  };
  std::optional<Assigned> assign(const jss::JssId& client, rt::TimePoint now, const Reusable& reusable);
  // The slot of a client node, if it has one (no new slot).
  std::optional<std::uint8_t> find(const jss::JssId& client) const;
  // Puts a client node in a given slot (a hold restored at start: the slot
  // its alias held before). false: the slot is out of range or another
  // client node's. Counts as hearing from it (not forgotten before its time).
  bool reserve(std::uint8_t slot, const jss::JssId& client, rt::TimePoint now);
  // The client heard from: its slot is the last to be reused.
  void heard(const jss::JssId& client, rt::TimePoint now);
  // Ends a slot (its client node forgotten).
  void release(std::uint8_t slot);

  Address alias(std::uint8_t slot, const ReplyTo& origin) const;
  // The client (and event) an alias stands for; nullopt when it is no
  // client's alias (another subsystem, an empty slot, a broadcast).
  std::optional<ReplyTo> client_of(const Address& alias) const;
  bool is_alias(const Address& address) const {
    return address.subsystem == alias_subsystem_ && !address.is_broadcast();
  }
  // The client node in a slot.
  std::optional<jss::JssId> client_in(std::uint8_t slot) const;
  std::uint8_t alias_subsystem() const { return alias_subsystem_; }
  std::size_t capacity() const { return slots_.size(); }
  std::size_t in_use() const;
  // Each slot in use, for housekeeping.
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t i = 0; i < slots_.size(); ++i)
      if (slots_[i].client) f(static_cast<std::uint8_t>(i + 1), *slots_[i].client, slots_[i].last_heard);
  }

 private:
  struct Slot {
    std::optional<jss::JssId> client;  // component 255: the client's node
    rt::TimePoint last_heard{};
  };
  std::uint8_t alias_subsystem_;
  std::vector<Slot> slots_;  // slot s at index s - 1
};

}  // namespace jaus::jss_face
