// The face's part of AS5669A transport (docs/jss.md, "Transport (AS5669A), done by the face"): the duplicate
// filter of received messages (its sequence numbers are the node's counters, node/sequence_counters.hpp).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <tuple>
#include <utility>

#include "jaus/base/time.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss/judp.hpp"

namespace jaus::jss_face {

// Received messages a sender retransmitted (AS5669A: a message with ACK
// requested is sent again until its ACK arrives, so when the ACK is lost the
// same message arrives again). A copy is ACKed again but not acted on again:
// a late copy of a Resume must not act after a later Standby. The rules are
// the RA node's (runtime DuplicateFilter, issue 32) where they fit JSS, plus
// what JSS peers that restart need (issue 43: Jr numbers from 1 on every
// start, and its own duplicate window is 3 s):
//  - only a single-packet message or a large message's packet with ACK
//    requested can be a copy (nobody retransmits anything else);
//  - a stop (Set Emergency, Standby, Shutdown) is never one: stopping twice
//    is safe, and a restarted client's stop must always act;
//  - a copy is the same source, destination and sequence number with the
//    same contents (a 64-bit FNV-1a fingerprint and the size) within
//    `window` (3 s) of the first;
//  - a restarted sender is a new session, never a copy: its numbers going
//    back to where senders start (0 or 1), or a number it used within the
//    window carrying another message, forget what it sent before (except
//    what a stop followed);
//  - except that a copy of a message its sender has since followed with a
//    stop to the same component is never acted on (a late copy, whatever
//    its number: safety before the restart rule).
// Bounded: at most `max_entries` messages remembered, the oldest forgotten
// first (a flood of distinct messages only makes the filter forget).

enum class JssCopyVerdict : std::uint8_t {
  first,         // new (remembered when ACK requested): deliver it
  not_filtered,  // no ACK requested, or a stop: deliver it
  new_session,   // its sender restarted: deliver it; what the sender sent before is forgotten
  copy,          // a retransmission of a message delivered: ACK again, do not deliver
  late_copy,     // a copy of a message its sender has since followed with a stop: ACK, never deliver
};

constexpr bool is_dropped(JssCopyVerdict v) { return v == JssCopyVerdict::copy || v == JssCopyVerdict::late_copy; }

class JssDuplicateFilter {
 public:
  struct Options {
    rt::Duration window = std::chrono::seconds(3);  // no longer than a JSS peer's own (Jr: 3 s)
    std::size_t max_entries = 4096;
  };
  JssDuplicateFilter() : JssDuplicateFilter(Options{}) {}
  explicit JssDuplicateFilter(Options options);

  // The verdict on a packet received at `now` (remembered when first or new_session).
  JssCopyVerdict check(const jss::JudpHeader& header, std::span<const std::uint8_t> contents, rt::TimePoint now);
  // Set Emergency, Standby, Shutdown: acted on however often they arrive.
  static bool is_stop(std::uint16_t message_id);
  std::size_t size() const { return entries_.size(); }

 private:
  // (source, destination): one sender's messages to one of our components.
  using StreamKey = std::pair<std::uint32_t, std::uint32_t>;
  using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint16_t>;  // stream, sequence number
  struct Entry {
    std::uint64_t fingerprint = 0;
    std::size_t size = 0;
    rt::TimePoint at{};
    std::uint64_t arrival = 0;  // order of arrival (1, 2, ...)
  };
  struct Stream {
    std::uint16_t last_sequence = 0;  // of the last message received
    std::uint64_t last_stop = 0;      // arrival of the last stop (0: none since the stream began)
    std::size_t entries = 0;          // remembered messages (the stream ends with the last)
  };
  struct Arrival {
    rt::TimePoint at{};
    std::uint64_t arrival = 0;
    Key key;
  };
  void remember(const Key& key, const Entry& entry);
  void erase_entry(std::map<Key, Entry>::iterator it);
  // A new session of the stream's sender: what it sent before is forgotten,
  // except what a stop followed.
  void forget_session(const StreamKey& stream);
  void expire(rt::TimePoint now);

  Options options_;
  std::uint64_t arrivals_ = 0;
  std::map<Key, Entry> entries_;
  std::map<StreamKey, Stream> streams_;
  std::deque<Arrival> order_;  // by arrival, for expiry and the bound (items of forgotten entries skipped)
};

}  // namespace jaus::jss_face
