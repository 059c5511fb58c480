#include "jaus/node/sequence_counters.hpp"

#include <algorithm>

namespace jaus::node {

SequenceCounters::SequenceCounters(Options options) : options_(options) {
  options_.max_streams = std::max<std::size_t>(options_.max_streams, 1);
}

std::uint16_t SequenceCounters::take(const SequenceStream& stream, std::uint16_t count) {
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

std::uint16_t SequenceCounters::peek(const SequenceStream& stream) const {
  const auto it = streams_.find(stream);
  return it == streams_.end() ? options_.first : it->second.next;
}

}  // namespace jaus::node
