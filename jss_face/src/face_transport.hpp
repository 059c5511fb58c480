// The face's part of AS5669A transport (jss-notes.md 1.4): sequence numbers
// per destination, and the duplicate filter of received messages (JRM's rule:
// the same source and sequence number within 10 s is a copy).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <utility>

#include "jaus/base/time.hpp"
#include "jaus/jss/jss_id.hpp"

namespace jaus::jss_face {

// Sequence numbers per destination, bounded: beyond `max_destinations` the
// destination least recently sent to starts again at 0 (a peer that still
// remembers our old numbers within its 10 s window may drop one copy).
class SequenceNumbers {
 public:
  explicit SequenceNumbers(std::size_t max_destinations = 4096) : max_(max_destinations) {}
  // The next `count` consecutive numbers to `to` (a large message's packets): the first of them.
  std::uint16_t take(const jss::JssId& to, std::uint16_t count = 1);
  std::size_t size() const { return next_.size(); }

 private:
  struct Entry {
    std::uint16_t next = 0;
    std::uint64_t used = 0;  // when last taken (a counter, for the bound)
  };
  std::size_t max_;
  std::uint64_t uses_ = 0;
  std::map<jss::JssId, Entry> next_;
};

// Received (source, sequence number) pairs of the last `window`, bounded:
// beyond `max_entries` the oldest is forgotten (a copy of it is then acted
// on again, as it would be after the window).
class JssDuplicateFilter {
 public:
  explicit JssDuplicateFilter(rt::Duration window = std::chrono::seconds(10), std::size_t max_entries = 4096)
      : window_(window), max_(max_entries) {}
  // Whether this pair was seen within the window; records it if not.
  bool seen_before(const jss::JssId& source, std::uint16_t sequence, rt::TimePoint now);
  std::size_t size() const { return seen_.size(); }

 private:
  using Key = std::pair<std::uint32_t, std::uint16_t>;
  void expire(rt::TimePoint now);
  rt::Duration window_;
  std::size_t max_;
  std::map<Key, rt::TimePoint> seen_;
  std::deque<std::pair<rt::TimePoint, Key>> order_;  // by arrival, for expiry
};

}  // namespace jaus::jss_face
