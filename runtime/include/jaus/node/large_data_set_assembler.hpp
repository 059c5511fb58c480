// Reassembles large data sets (docs/wire-format.md, "Large data sets") from
// received packets, by (source, command code) and sequence number.
//
// Packets may arrive in any order; a duplicate is ignored, a retransmitted
// packet (flag 4) replaces the one with its sequence number. Senders may
// number sets continuously or restart every set at 0 (OpenJAUS does): a
// packet whose number is held with other bytes starts a new message rather
// than being mixed into the old one. A set finishes
// when its first (1) and last (8) packets and every number between them are
// held. Everything is bounded: bytes and packets per set, sets in progress,
// and time (a set that receives nothing new for `timeout` is discarded).
// Every dropped packet and discarded set is counted by reason, and feed()
// says what it did with each packet so the caller can log where and why.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "jaus/core/header.hpp"
#include "jaus/base/time.hpp"

namespace jaus::node {

struct LargeDataSetKey {
  Address source;
  std::uint16_t command_code = 0;
  auto operator<=>(const LargeDataSetKey&) const = default;
};

// A reassembled message. The header is the first packet's as received (flag
// 1, its own data size and sequence number): a 16-bit header cannot state
// the full size, so the payload carries it.
struct AssembledMessage {
  Header first_header;
  std::vector<std::uint8_t> payload;
};

enum class AssemblyStatus : std::uint8_t {
  single,    // data flag 0: not part of a set, use the packet as it is
  pending,   // kept; its set is not complete yet
  complete,  // this packet completed its set (see `message`)
  dropped,   // not kept (see `issue`)
};

enum class AssemblyIssue : std::uint8_t {
  none,
  // The packet was dropped:
  bad_packet,                // data size disagrees with the payload, or unknown data flag
  duplicate,                 // same number and bytes as a held packet, or a late copy from a set just completed
  inconsistent,              // contradicts its set (a second last packet, a number outside first..last)
  oversize,                  // its set outgrew the byte or packet limit: the whole set was discarded
  too_many_sets,             // it would start a set while max_concurrent_sets are in progress
  unmatched_retransmission,  // flag 4 but no set in progress to put it in
  rest_of_discarded_set,     // belongs to a set already discarded as oversize
  // The packet was kept, and:
  replaced,    // as a retransmission, it replaced the packet held under its number
  superseded,  // it starts a newer message (a first packet with another number, or a number held
               // with other bytes): the unfinished set before it was discarded
  // A whole set was discarded:
  timed_out,  // nothing new arrived for `timeout`
};
std::string_view to_string(AssemblyIssue issue);

struct AssemblyResult {
  AssemblyStatus status = AssemblyStatus::dropped;
  AssemblyIssue issue = AssemblyIssue::none;
  std::optional<AssembledMessage> message;  // when status == complete
};

// A set given up without being completed (returned by expire()).
struct DiscardedSet {
  LargeDataSetKey key;
  AssemblyIssue reason = AssemblyIssue::timed_out;
  std::size_t packets = 0;  // packets held when it was discarded
  std::size_t bytes = 0;
};

struct AssemblerCounters {
  std::uint64_t singles = 0;
  std::uint64_t completed = 0;
  std::uint64_t replaced = 0;
  std::uint64_t bad_packets = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t inconsistent = 0;
  std::uint64_t oversize = 0;  // sets discarded
  std::uint64_t too_many_sets = 0;
  std::uint64_t unmatched_retransmissions = 0;
  std::uint64_t rest_of_discarded_sets = 0;
  std::uint64_t superseded = 0;  // sets discarded
  std::uint64_t timed_out = 0;   // sets discarded
};

class LargeDataSetAssembler {
 public:
  struct Options {
    std::size_t max_message_size = 1024 * 1024;  // payload bytes of one set
    // Packets of one set; above 1 MiB / 4080 so that peers that cut sets
    // into smaller packets still fit.
    std::size_t max_packets_per_set = 4096;
    std::size_t max_concurrent_sets = 8;  // sets in progress at once
    rt::Duration timeout = std::chrono::seconds(5);  // since the set last received a new packet
  };

  LargeDataSetAssembler() : LargeDataSetAssembler(Options{}) {}
  explicit LargeDataSetAssembler(Options options);

  // Takes one received packet (the payload is copied if kept). Sets found
  // stale on the way are discarded and counted as timed out.
  AssemblyResult feed(const Header& header, std::span<const std::uint8_t> payload, rt::TimePoint now);

  // Discards the sets that received nothing new for `timeout` up to `now`.
  std::vector<DiscardedSet> expire(rt::TimePoint now);
  // When the next set in progress would time out, for scheduling expire().
  std::optional<rt::TimePoint> next_deadline() const;

  std::size_t sets_in_progress() const;
  std::size_t buffered_bytes() const;
  const AssemblerCounters& counters() const { return counters_; }

 private:
  enum class SetState : std::uint8_t {
    assembling,
    discarding,  // outgrew the limits: its remaining packets are dropped until its last one
    completed,   // delivered: kept briefly so that late duplicates are recognised
  };
  struct Set {
    SetState state = SetState::assembling;
    std::optional<Header> first_header;
    std::optional<std::uint16_t> last_sequence;
    std::map<std::uint16_t, std::vector<std::uint8_t>> packets;  // by sequence number
    std::size_t bytes = 0;
    rt::TimePoint last_activity{};
  };
  using Sets = std::map<LargeDataSetKey, Set>;

  AssemblyResult feed_new_set(const LargeDataSetKey& key, const Header& header,
                              std::span<const std::uint8_t> payload, rt::TimePoint now, AssemblyIssue issue);
  AssemblyResult feed_finished_set(Sets::iterator it, const Header& header, std::span<const std::uint8_t> payload,
                                   rt::TimePoint now);
  AssemblyResult feed_assembling_set(Sets::iterator it, const Header& header, std::span<const std::uint8_t> payload,
                                     rt::TimePoint now);
  AssemblyResult supersede(Sets::iterator it, const Header& header, std::span<const std::uint8_t> payload,
                           rt::TimePoint now);
  AssemblyResult store(Sets::iterator it, std::uint16_t sequence, std::span<const std::uint8_t> payload,
                       rt::TimePoint now, AssemblyIssue issue);
  AssemblyResult complete_if_whole(Sets::iterator it, rt::TimePoint now, AssemblyIssue issue);
  AssemblyResult discard_as_oversize(Set& set, rt::TimePoint now);
  bool fits(const Set& set, std::uint16_t sequence) const;
  void drop_packets_outside_range(Set& set);
  bool is_stale(const Set& set, rt::TimePoint now) const { return now >= set.last_activity + options_.timeout; }
  bool make_room_for_a_set(rt::TimePoint now);
  AssemblyResult drop(AssemblyIssue issue);

  Options options_;
  Sets sets_;
  AssemblerCounters counters_;
};

}  // namespace jaus::node
