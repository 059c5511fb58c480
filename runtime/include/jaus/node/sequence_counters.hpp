// Outgoing sequence numbers, one u16 series per stream, for both dialects:
// the RA node numbers per (sender, destination) pair (header bytes 14-15;
// docs/wire-format.md makes the number "per sender", we keep a series per
// pair so that every receiver sees a gap-free series from each of our
// components and a gap means loss); the JSS face per destination JSS ID.
// Numbers wrap from 65535 to 0.
#pragma once

#include <algorithm>
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

struct SequenceCounterOptions {
  // Streams remembered at once; past it the least recently used stream is
  // forgotten (and restarts at `first` when used again: a peer that still
  // remembers our old numbers within its duplicate window may drop one copy).
  std::size_t max_streams = 1024;
  // Where every new stream starts. An operator tool that runs again and
  // again under one kept ID starts at a random number: a receiver's
  // duplicate filter would take a new run's first command, numbered like
  // the last run's, for a copy of it (OcuSession::open).
  std::uint16_t first = 0;
};

// `Stream`: anything ordered that names a series (SequenceStream, jss::JssId).
template <class Stream>
class BasicSequenceCounters {
 public:
  using Options = SequenceCounterOptions;

  BasicSequenceCounters() : BasicSequenceCounters(Options{}) {}
  explicit BasicSequenceCounters(Options options) : options_(options) {
    options_.max_streams = std::max<std::size_t>(options_.max_streams, 1);
  }

  // Reserves `count` consecutive numbers (a large message needs one per
  // packet) and returns the first; the next call continues after them.
  std::uint16_t take(const Stream& stream, std::uint16_t count = 1) {
    auto it = streams_.find(stream);
    if (it == streams_.end()) {
      if (streams_.size() >= options_.max_streams) {
        streams_.erase(recency_.front());
        recency_.pop_front();
        ++evicted_;
      }
      it = streams_.emplace(stream, State{options_.first, recency_.insert(recency_.end(), stream)}).first;
    } else {
      recency_.splice(recency_.end(), recency_, it->second.in_recency);  // now the most recent
    }
    const std::uint16_t first = it->second.next;
    it->second.next = static_cast<std::uint16_t>(first + count);  // u16 arithmetic: wraps at 65535
    return first;
  }

  // The number the next take() would return, without reserving it.
  std::uint16_t peek(const Stream& stream) const {
    const auto it = streams_.find(stream);
    return it == streams_.end() ? options_.first : it->second.next;
  }

  std::size_t size() const { return streams_.size(); }
  std::uint64_t evicted() const { return evicted_; }

 private:
  // Least recently used first: a flood of new destinations makes every reply
  // evict one, so eviction is O(1) (the list's front), not a scan.
  using Recency = std::list<Stream>;
  struct State {
    std::uint16_t next = 0;
    typename Recency::iterator in_recency;
  };

  Options options_;
  std::map<Stream, State> streams_;
  Recency recency_;
  std::uint64_t evicted_ = 0;
};

using SequenceCounters = BasicSequenceCounters<SequenceStream>;

}  // namespace jaus::node
