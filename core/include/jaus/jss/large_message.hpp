// Large JSS messages (docs/jss.md, "The bytes on the wire"): contents above the per-packet limit
// travel as a first packet (data flag 1, starting with the message ID),
// middle packets (2) and a last packet (3) with consecutive sequence numbers.
// Splitting is a pure function; the reassembler keeps, per source, the sets
// in progress, bounded in number, bytes and time, and counts what it drops.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/jss/judp.hpp"

namespace jaus::jss {

// Contents per packet that fit every peer seen without IP fragmentation (JAUS++
// splits above 1437, JRM above 4079).
inline constexpr std::size_t kDefaultMaxPacketContents = 1400;

struct ContentsPiece {
  JudpDataFlag data_flag = JudpDataFlag::single;
  std::span<const std::uint8_t> bytes;  // views the contents given to split_contents
};

// One piece (flag single) when the contents fit `max_contents`, else first,
// middle..., last. invalid_argument when max_contents < 2 (the first piece
// carries the whole message ID).
Expected<std::vector<ContentsPiece>> split_contents(std::span<const std::uint8_t> contents, std::size_t max_contents);

// The datagrams of a whole message: `header` for each, data flags set, sequence
// numbers header.sequence, +1, ... (wrapping). Broadcasts are never split
// (docs/jss.md, "The bytes on the wire"): contents above max_contents to a broadcast destination
// are payload_too_large.
Expected<std::vector<std::vector<std::uint8_t>>> make_judp_datagrams(const JudpHeader& header,
                                                                     std::span<const std::uint8_t> contents,
                                                                     std::size_t max_contents = kDefaultMaxPacketContents);

struct ReassemblyLimits {
  std::size_t max_sets = 32;             // sets in progress, all sources together
  std::size_t max_sets_per_source = 4;   // a source's new set beyond this drops its own oldest
  std::size_t max_set_bytes = 64 * 1024;  // contents of one message
  std::size_t max_total_bytes = 512 * 1024;
  rt::Duration timeout = std::chrono::seconds(2);  // since the set's last packet
};

struct ReassemblyCounters {
  std::uint64_t completed = 0;   // whole messages put back together
  std::uint64_t stray = 0;       // middle/last packets no set expects (lost first, gap, duplicate)
  std::uint64_t too_large = 0;   // sets dropped for max_set_bytes or max_total_bytes
  std::uint64_t refused = 0;     // first packets refused: max_sets in progress
  std::uint64_t superseded = 0;  // sets dropped for a newer one of the same source (max_sets_per_source)
  std::uint64_t timed_out = 0;   // sets dropped after `timeout` without a packet
  std::uint64_t bad_first = 0;   // first packets shorter than a message ID
};

struct WholeMessage {
  JudpHeader header;  // the first packet's (sequence: the first packet's), data flag single
  std::vector<std::uint8_t> contents;
};

class LargeMessageReassembler {
 public:
  explicit LargeMessageReassembler(ReassemblyLimits limits = {}) : limits_(limits) {}

  // A packet of any data flag: a single packet is whole at once; a first packet
  // starts a set; middle and last packets extend the set of the same source
  // and destination whose next sequence number they carry. The whole message
  // when complete, nullopt while incomplete; an error (counted) when the
  // packet is dropped, saying why.
  Expected<std::optional<WholeMessage>> add(const JudpPacket& packet, rt::TimePoint now);

  // Drops sets silent for longer than the timeout (add() does it too).
  void expire(rt::TimePoint now);

  const ReassemblyCounters& counters() const { return counters_; }
  std::size_t sets_in_progress() const { return sets_.size(); }
  std::size_t bytes_in_progress() const { return total_bytes_; }

 private:
  struct Key {
    JssId source;
    JssId destination;
    std::uint16_t first_sequence = 0;
    auto operator<=>(const Key&) const = default;
  };
  struct Set {
    JudpHeader header;
    std::vector<std::uint8_t> contents;
    std::uint16_t next_sequence = 0;
    rt::TimePoint last_heard{};
    std::uint64_t started = 0;  // order of arrival, for the per-source bound
  };
  void drop(std::map<Key, Set>::iterator it);

  ReassemblyLimits limits_;
  ReassemblyCounters counters_;
  std::map<Key, Set> sets_;
  std::size_t total_bytes_ = 0;
  std::uint64_t next_started_ = 0;
};

}  // namespace jaus::jss
