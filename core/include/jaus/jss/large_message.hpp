// Large JSS messages (docs/jss.md, "The bytes on the wire"): contents above the per-packet limit
// travel as a first packet (data flag 1, starting with the message ID),
// middle packets (2) and a last packet (3) with consecutive sequence numbers.
// Splitting is a pure function (the cut is both dialects': jaus/core/large_message_pieces.hpp);
// reassembly is the one assembler's, with this dialect's adapter.
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/core/large_message_assembler.hpp"
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

// AS5669A large messages as a dialect of the one assembler
// (jaus/core/large_message_assembler.hpp): a set is its source and
// destination (only the first piece names the message; the sender numbers
// its pieces consecutively); data flags 1 first, 2 middle, 3 last. The
// reassembled header is the first piece's (its sequence number), data flag
// single.
struct JudpLargeMessages {
  using Header = JudpHeader;
  using Address = JssId;

  static constexpr AssemblyLimits kDefaultLimits{.max_message_size = 64 * 1024,
                                                 .max_sets = 32,
                                                 .max_sets_per_source = 4,
                                                 .max_total_bytes = 512 * 1024,
                                                 .timeout = std::chrono::seconds(2)};
  // A sender numbers its pieces on (as the JSS face and the OCU session do): a first
  // piece of a message just completed is a copy.
  static constexpr bool kSendersMayRestartNumbering = false;

  static LargeMessageKey<Address> key_of(const Header& h) { return {h.source, h.destination, 0}; }
  static PieceRole role_of(const Header& h) {
    switch (h.data_flag) {
      case JudpDataFlag::single: return PieceRole::single;
      case JudpDataFlag::first: return PieceRole::first;
      case JudpDataFlag::middle: return PieceRole::middle;
      case JudpDataFlag::last: return PieceRole::last;
    }
    return PieceRole::unknown;
  }
  static std::uint16_t sequence_of(const Header& h) { return h.sequence; }
  static AssemblyIssue check(const Header& h, std::span<const std::uint8_t> contents) {
    return h.data_flag == JudpDataFlag::first && contents.size() < 2 ? AssemblyIssue::bad_first : AssemblyIssue::none;
  }
  static Header whole_header(const Header& first) {
    Header whole = first;
    whole.data_flag = JudpDataFlag::single;
    return whole;
  }
};

using JssLargeMessageAssembler = LargeMessageAssembler<JudpLargeMessages>;

}  // namespace jaus::jss

namespace jaus {
extern template class LargeMessageAssembler<jss::JudpLargeMessages>;
}  // namespace jaus
