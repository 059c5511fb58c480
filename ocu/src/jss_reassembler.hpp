// Large JSS messages arriving as first/middle/last packets with consecutive
// sequence numbers (jss-notes.md 1.5), put back together per source. Bounded:
// a message above `max_bytes`, a gap in the sequence, or one whose packets
// stop for `timeout` is dropped; at most `max_sources` in progress (the
// oldest goes).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/jss/judp.hpp"

namespace jaus::ocu::detail {

class JssReassembler {
 public:
  struct Whole {
    jss::JudpHeader header;  // of the first packet
    std::vector<std::uint8_t> contents;
  };
  JssReassembler(std::size_t max_bytes, std::size_t max_sources, rt::Duration timeout)
      : max_bytes_(max_bytes), max_sources_(max_sources), timeout_(timeout) {}

  // One packet with data flag first, middle or last. The whole message when
  // this was its last packet.
  std::optional<Whole> add(const jss::JudpPacket& packet, rt::TimePoint now);
  std::uint64_t dropped() const { return dropped_; }

 private:
  struct Partial {
    Whole whole;
    std::uint16_t next_sequence = 0;
    rt::TimePoint last_heard{};
  };
  void expire(rt::TimePoint now);

  std::size_t max_bytes_;
  std::size_t max_sources_;
  rt::Duration timeout_;
  std::map<jss::JssId, Partial> partial_;
  std::uint64_t dropped_ = 0;
};

}  // namespace jaus::ocu::detail
