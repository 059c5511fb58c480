#include "jaus/node/sequence_counters.hpp"

#include <algorithm>

namespace jaus::node {

SequenceCounters::SequenceCounters(Options options) : options_(options) {
  options_.max_streams = std::max<std::size_t>(options_.max_streams, 1);
}

std::uint16_t SequenceCounters::take(const SequenceStream& stream, std::uint16_t count) {
  auto it = streams_.find(stream);
  if (it == streams_.end()) {
    if (streams_.size() >= options_.max_streams) evict_least_recently_used();
    it = streams_.emplace(stream, State{}).first;
  }
  const std::uint16_t first = it->second.next;
  it->second.next = static_cast<std::uint16_t>(first + count);  // u16 arithmetic: wraps at 65535
  it->second.last_used = ++uses_;
  return first;
}

std::uint16_t SequenceCounters::peek(const SequenceStream& stream) const {
  const auto it = streams_.find(stream);
  return it == streams_.end() ? 0 : it->second.next;
}

void SequenceCounters::evict_least_recently_used() {
  // Linear scan: runs only when the table is full, which a node with a sane
  // limit reaches rarely.
  const auto oldest = std::min_element(streams_.begin(), streams_.end(), [](const auto& a, const auto& b) {
    return a.second.last_used < b.second.last_used;
  });
  if (oldest == streams_.end()) return;
  streams_.erase(oldest);
  ++evicted_;
}

}  // namespace jaus::node
