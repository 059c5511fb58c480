// Receiver side of commands that must arrive: a sender retransmits an
// ACK-requested message until it hears the ACK, so when an ACK is lost the
// same message arrives again. The copy is ACKed again but not delivered
// again: a late copy of a Resume or Clear Emergency must not act after a
// later Standby or Set Emergency (issue 32).
//
// A copy is the same source, destination, command code and sequence number
// with an identical payload (compared by a 64-bit FNV-1a fingerprint and its
// size), ACK requested, within `window` of the last copy seen. Stops are
// never filtered: Set Emergency, Standby and Shutdown are always delivered
// (stopping twice is safe, and a restarted OCU reusing its ID and sequence 0
// must still stop the vehicle). Bounded: at most `max_entries` messages are
// remembered, the least recently seen forgotten first (a flood of distinct
// messages only makes the filter forget, never drop a first copy; once full
// it reuses the forgotten entry's memory: no allocation per message).
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <span>

#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"

namespace jaus::node {

struct DuplicateKey {
  Address source;
  Address destination;
  std::uint16_t command_code = 0;
  std::uint16_t sequence = 0;
  auto operator<=>(const DuplicateKey&) const = default;
};

enum class DuplicateVerdict : std::uint8_t {
  first_copy,    // remembered: deliver it
  duplicate,     // a retransmission of a message delivered: ACK it again, do not deliver
  not_filtered,  // no ACK requested, a stop, or a packet of a large data set: deliver it
};

struct DuplicateFilterCounters {
  std::uint64_t duplicates = 0;  // copies found
  std::uint64_t forgotten = 0;   // messages evicted by the bound before their window ended
};

class DuplicateFilter {
 public:
  struct Options {
    rt::Duration window = std::chrono::seconds(2);  // the default ACK policy's 3 transmissions span 2 s
    std::size_t max_entries = 512;
  };

  DuplicateFilter() : DuplicateFilter(Options{}) {}
  explicit DuplicateFilter(Options options);

  // The verdict on a message received at `now` (remembered when first_copy).
  DuplicateVerdict check(const Header& header, std::span<const std::uint8_t> payload, rt::TimePoint now);

  // Set Emergency, Standby, Shutdown: delivered however often they arrive.
  static bool always_delivered(std::uint16_t command_code);

  std::size_t size() const { return entries_.size(); }
  const DuplicateFilterCounters& counters() const { return counters_; }

 private:
  using Recency = std::list<DuplicateKey>;  // least recently seen first
  struct Entry {
    std::uint64_t fingerprint = 0;
    std::size_t size = 0;
    rt::TimePoint last_seen{};
    Recency::iterator in_recency;
  };

  Options options_;
  std::map<DuplicateKey, Entry> entries_;
  Recency recency_;
  DuplicateFilterCounters counters_;
};

}  // namespace jaus::node
