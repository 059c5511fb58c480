// Outgoing sequence numbers (header bytes 14-15). docs/wire-format.md makes
// the number "per sender"; we keep one u16 stream per (sender, destination) pair, so that
// every receiver sees a gap-free series from each of our components and a gap
// means loss. Numbers wrap from 65535 to 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>

#include "jaus/core/address.hpp"

namespace jaus::node {

struct SequenceStream {
  Address source;       // our component
  Address destination;  // as addressed (a broadcast address is a stream of its own)
  auto operator<=>(const SequenceStream&) const = default;
};

class SequenceCounters {
 public:
  struct Options {
    // Streams remembered at once; past it the least recently used stream is
    // forgotten (and restarts at `first` when used again).
    std::size_t max_streams = 1024;
    // Where every new stream starts. An operator tool that runs again and
    // again under one kept ID starts at a random number: a receiver's
    // duplicate filter would take a new run's first command, numbered like
    // the last run's, for a copy of it (OcuSession::open).
    std::uint16_t first = 0;
  };

  SequenceCounters() : SequenceCounters(Options{}) {}
  explicit SequenceCounters(Options options);

  // Reserves `count` consecutive numbers (a large data set needs one per
  // packet) and returns the first; the next call continues after them.
  std::uint16_t take(const SequenceStream& stream, std::uint16_t count = 1);
  // The number the next take() would return, without reserving it.
  std::uint16_t peek(const SequenceStream& stream) const;

  std::size_t size() const { return streams_.size(); }
  std::uint64_t evicted() const { return evicted_; }

 private:
  // Least recently used first: a flood of new destinations makes every reply
  // evict one, so eviction is O(1) (the list's front), not a scan.
  using Recency = std::list<SequenceStream>;
  struct State {
    std::uint16_t next = 0;
    Recency::iterator in_recency;
  };

  Options options_;
  std::map<SequenceStream, State> streams_;
  Recency recency_;
  std::uint64_t evicted_ = 0;
};

}  // namespace jaus::node
