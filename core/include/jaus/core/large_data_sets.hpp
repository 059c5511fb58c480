// RA large data sets (docs/wire-format.md, "Large data sets") as a dialect of
// the one assembler (jaus/core/large_message_assembler.hpp): a set is its
// source, destination and command code (every packet carries it); data flags
// 1 first, 2 middle, 8 last, 4 retransmitted. The reassembled header is the
// first packet's as received (flag 1, its own data size and sequence number):
// a 16-bit header cannot state the full size, so the payload carries it.
#pragma once

#include "jaus/core/header.hpp"
#include "jaus/core/large_message_assembler.hpp"

namespace jaus {

struct RaLargeDataSets {
  using Header = jaus::Header;
  using Address = jaus::Address;

  static constexpr AssemblyLimits kDefaultLimits{};
  // OpenJAUS numbers every set from 0: a first piece always starts a new message.
  static constexpr bool kSendersMayRestartNumbering = true;

  static LargeMessageKey<Address> key_of(const Header& h) { return {h.source, h.destination, h.command_code}; }
  static PieceRole role_of(const Header& h) {
    switch (h.data_flag) {
      case DataFlag::single: return PieceRole::single;
      case DataFlag::first: return PieceRole::first;
      case DataFlag::middle: return PieceRole::middle;
      case DataFlag::last: return PieceRole::last;
      case DataFlag::retransmitted: return PieceRole::retransmitted;
    }
    return PieceRole::unknown;
  }
  static std::uint16_t sequence_of(const Header& h) { return h.sequence; }
  static AssemblyIssue check(const Header& h, std::span<const std::uint8_t> payload) {
    return h.data_size == payload.size() ? AssemblyIssue::none : AssemblyIssue::bad_packet;
  }
  static Header whole_header(const Header& first) { return first; }
};

using RaLargeMessageAssembler = LargeMessageAssembler<RaLargeDataSets>;
extern template class LargeMessageAssembler<RaLargeDataSets>;

}  // namespace jaus
