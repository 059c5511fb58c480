// Receiver side of commands that must arrive, for both dialects (the RA
// node's receive path and the JSS face's): a sender retransmits an
// ACK-requested message until it hears the ACK, so when an ACK is lost the
// same message arrives again. The copy is ACKed again but not acted on again:
// a late copy of a Resume or Clear Emergency must not act after a later
// Standby or Set Emergency (issue 32).
//
// The rules (a packet is described by its PacketIdentity, whatever its header):
//  - only a packet with ACK requested can be a copy (nobody retransmits
//    anything else), and a packet of a large message only where the dialect
//    filters them (`pieces_filtered`: JSS; RA's large data set assembler
//    handles its packets' copies itself);
//  - a stop (Set Emergency, Standby, Shutdown) is never one: stopping twice
//    is safe, and a restarted operator unit's stop must always act;
//  - a copy is the same source, destination and sequence number with the
//    same bytes (a 64-bit FNV-1a fingerprint of the code or ID and the
//    payload, and the size) within `window` of the last copy seen;
//  - a restarted sender is a new session, never a copy (issue 43: Jr numbers
//    from 1 on every start, and so do RA peers that keep no state): its
//    numbers going back to where senders start (0 or 1), or a number it used
//    within the window carrying another message, forget what it sent before
//    (except what a stop followed);
//  - except that a copy of a message its sender has since followed with a
//    stop to the same component is never acted on (a late copy, whatever its
//    number: safety before the restart rule).
// Bounded: at most `max_entries` messages remembered, the least recently
// seen forgotten first (a flood of distinct messages only makes the filter
// forget, never drop a first copy).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <tuple>
#include <utility>

#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"

namespace jaus::node {

// What the filter needs of a received packet, whatever its dialect's header.
struct PacketIdentity {
  std::uint64_t source = 0;       // the sender (its ID, packed)
  std::uint64_t destination = 0;  // our component, as addressed
  std::uint16_t sequence = 0;
  bool ack_requested = false;
  bool piece = false;  // a packet of a large message, not a whole message
  bool stop = false;   // Set Emergency, Standby or Shutdown (a whole message)
  std::uint64_t fingerprint = 0;  // of what makes it this message (fingerprint_of)
  std::size_t size = 0;
};

inline constexpr std::uint64_t kFingerprintStart = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bits
// Continues `hash` over `bytes`.
std::uint64_t fingerprint_of(std::span<const std::uint8_t> bytes, std::uint64_t hash = kFingerprintStart);

// An RA packet: its command code and payload make it this message.
PacketIdentity identity_of(const Header& header, std::span<const std::uint8_t> payload);

enum class DuplicateVerdict : std::uint8_t {
  first_copy,    // new (remembered when ACK requested): deliver it
  not_filtered,  // no ACK requested, a stop, or a packet the dialect does not filter: deliver it
  new_session,   // its sender restarted: deliver it; what the sender sent before is forgotten
  duplicate,     // a retransmission of a message delivered: ACK it again, do not deliver
  late_copy,     // a copy of a message its sender has since followed with a stop: ACK, never deliver
};

constexpr bool is_dropped(DuplicateVerdict v) {
  return v == DuplicateVerdict::duplicate || v == DuplicateVerdict::late_copy;
}

struct DuplicateFilterCounters {
  std::uint64_t duplicates = 0;    // copies found (late copies included)
  std::uint64_t late_copies = 0;   // of which a stop had followed the message
  std::uint64_t new_sessions = 0;  // senders that restarted
  std::uint64_t forgotten = 0;     // messages evicted by the bound before their window ended
};

class DuplicateFilter {
 public:
  struct Options {
    rt::Duration window = std::chrono::seconds(2);  // the RA ACK policy's 3 transmissions span 2 s; JSS: 3 s (Jr's own)
    std::size_t max_entries = 512;
    bool pieces_filtered = false;  // whether a large message's packets can be copies (JSS: yes)
  };

  DuplicateFilter() : DuplicateFilter(Options{}) {}
  explicit DuplicateFilter(Options options);

  // The verdict on a packet received at `now`.
  DuplicateVerdict check(const PacketIdentity& packet, rt::TimePoint now);
  DuplicateVerdict check(const Header& header, std::span<const std::uint8_t> payload, rt::TimePoint now) {
    return check(identity_of(header, payload), now);
  }

  // Set Emergency, Standby, Shutdown (the same codes in RA and JSS): acted on however often they arrive.
  static bool always_delivered(std::uint16_t code);

  std::size_t size() const { return entries_.size(); }
  const DuplicateFilterCounters& counters() const { return counters_; }

 private:
  // (source, destination): one sender's messages to one of our components.
  using StreamKey = std::pair<std::uint64_t, std::uint64_t>;
  using Key = std::tuple<std::uint64_t, std::uint64_t, std::uint16_t>;  // stream, sequence number
  struct Entry {
    std::uint64_t fingerprint = 0;
    std::size_t size = 0;
    rt::TimePoint seen{};       // when last seen (its window runs from there)
    std::uint64_t arrival = 0;  // order of arrival (1, 2, ...), renewed with each copy
  };
  struct Stream {
    std::uint16_t last_sequence = 0;  // of the last message received
    std::uint64_t last_stop = 0;      // arrival of the last stop (0: none since the stream began)
    std::size_t entries = 0;          // remembered messages (the stream ends with the last)
  };
  struct Seen {
    rt::TimePoint at{};
    std::uint64_t arrival = 0;
    Key key;
  };
  // Remembers `entry` under `key` (new, or seen again) and makes room.
  void remember(const Key& key, const Entry& entry);
  bool current(const Seen& seen) const;
  void erase_entry(std::map<Key, Entry>::iterator it);
  // A new session of the stream's sender: what it sent before is forgotten,
  // except what a stop followed.
  void forget_session(const StreamKey& stream);
  void expire(rt::TimePoint now);

  Options options_;
  std::uint64_t arrivals_ = 0;
  std::map<Key, Entry> entries_;
  std::map<StreamKey, Stream> streams_;
  // By arrival, for expiry and the bound; an item whose entry was seen again
  // or forgotten since is stale and skipped (compacted when they pile up).
  std::deque<Seen> order_;
  DuplicateFilterCounters counters_;
};

}  // namespace jaus::node
