// Puts large messages back together from their pieces, in either dialect:
// RA large data sets (docs/wire-format.md, "Large data sets") and AS5669A
// large messages (docs/jss.md, "The bytes on the wire"). A dialect is a small
// adapter (RaLargeDataSets in jaus/core/large_data_sets.hpp,
// jss::JudpLargeMessages in jaus/jss/large_message.hpp) that says which set a
// piece belongs to, its role and its sequence number.
//
// Pieces may arrive in any order; a duplicate is ignored, an RA retransmitted
// piece (flag 4) replaces the one with its sequence number. Senders may number
// sets continuously or restart every set at 0 (OpenJAUS does): a piece whose
// number is held with other bytes starts a new message rather than being mixed
// into the old one. A set finishes when its first and last pieces and every
// number between them are held. Everything is bounded: bytes and pieces per
// set, bytes of all sets, sets in progress (in all and per source), and time
// (a set that receives nothing new for `timeout` is discarded). There is no
// clock: the caller passes the time. Every dropped piece and discarded set is
// counted by reason, and feed() says what it did with each piece so the
// caller can log where and why. A single piece is answered at once and
// nothing is copied or allocated for it.
//
// Each piece may carry a doubt, a number the caller gives it (0: none; the
// node and the JSS face give a piece its sender's standing,
// rt::doubt_of): a whole message carries the most of its pieces', so it is
// trusted only as far as its least trusted piece, whichever piece completes
// it. A set started anew (superseded) starts from the doubt of its new piece.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/core/large_message_pieces.hpp"

namespace jaus {

// The pieces of one message share it. `message` tells apart messages of one
// source to one destination where every piece names it (the RA command
// code); AS5669A names the message in its first piece only, so it is 0 there
// and a sender's messages are told apart by their sequence numbers.
template <class Address>
struct LargeMessageKey {
  Address source;
  Address destination;
  std::uint16_t message = 0;
  auto operator<=>(const LargeMessageKey&) const = default;
};

struct AssemblyLimits {
  std::size_t max_message_size = 1024 * 1024;  // payload bytes of one set
  // Pieces of one set; above 1 MiB / 4080 so that peers that cut sets into
  // smaller pieces still fit.
  std::size_t max_pieces_per_set = 4096;
  std::size_t max_sets = 8;             // sets in progress, all sources together: a new one beyond is refused
  std::size_t max_sets_per_source = 4;  // a source's new set beyond this discards its own oldest
  std::size_t max_total_bytes = 4 * 1024 * 1024;   // payload bytes of all sets in progress
  rt::Duration timeout = std::chrono::seconds(5);  // since the set last received a new piece
};

enum class AssemblyStatus : std::uint8_t {
  single,    // a whole message in one piece: use it as it is
  pending,   // kept; its set is not complete yet
  complete,  // this piece completed its set (see `message`)
  dropped,   // not kept (see `issue`)
};

enum class AssemblyIssue : std::uint8_t {
  none,
  // The piece was dropped:
  bad_packet,                // data size disagrees with the payload, or unknown data flag
  bad_first,                 // a first piece too short to carry the message ID
  duplicate,                 // same number and bytes as a held piece, or a late copy from a set just completed
  inconsistent,              // contradicts its set (a second last piece, a number outside first..last)
  too_large,                 // its set outgrew the byte or piece limit: the whole set was discarded
  refused,                   // it would start a set while max_sets are in progress
  unmatched_retransmission,  // RA flag 4 but no set in progress to put it in
  rest_of_discarded_set,     // belongs to a set already discarded as too large
  // The piece was kept, and:
  replaced,    // as a retransmission, it replaced the piece held under its number
  superseded,  // it starts a newer message (a first piece with another number, a number held with other
               // bytes, or one set too many of its source): an unfinished set was discarded
  // A whole set was discarded:
  timed_out,  // nothing new arrived for `timeout`
};
std::string_view to_string(AssemblyIssue issue);

struct AssemblyCounters {
  std::uint64_t singles = 0;
  std::uint64_t completed = 0;  // whole messages put back together
  std::uint64_t replaced = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t stray = 0;       // pieces no set can take: inconsistent, unmatched retransmissions, rest of discarded sets
  std::uint64_t too_large = 0;   // sets discarded over max_message_size, max_pieces_per_set or max_total_bytes
  std::uint64_t refused = 0;     // sets not started: max_sets in progress
  std::uint64_t superseded = 0;  // sets discarded for a newer one
  std::uint64_t timed_out = 0;   // sets discarded after `timeout` without a new piece
  std::uint64_t bad_first = 0;   // first pieces shorter than a message ID
  std::uint64_t bad_packets = 0;
};

// A reassembled message: the dialect's whole-message header made from the
// first piece's (its sequence number), and the payload of all pieces.
template <class Header>
struct AssembledMessage {
  Header header;
  std::vector<std::uint8_t> payload;
  std::uint8_t doubt = 0;  // the most of its pieces'
};

template <class Header>
struct AssemblyResult {
  AssemblyStatus status = AssemblyStatus::dropped;
  AssemblyIssue issue = AssemblyIssue::none;
  std::optional<AssembledMessage<Header>> message;  // when status == complete
};

// A set given up without being completed (returned by expire()).
template <class Key>
struct DiscardedSet {
  Key key;
  AssemblyIssue reason = AssemblyIssue::timed_out;
  std::size_t pieces = 0;  // held when it was discarded
  std::size_t bytes = 0;
};

// `Dialect` provides: Header, Address, kDefaultLimits, kSendersMayRestartNumbering, key_of(header),
// role_of(header), sequence_of(header), check(header, payload) (an issue that
// drops the piece, or none) and whole_header(first piece's header).
template <class Dialect>
class LargeMessageAssembler {
 public:
  using Header = typename Dialect::Header;
  using Key = LargeMessageKey<typename Dialect::Address>;
  using Result = AssemblyResult<Header>;
  using Message = AssembledMessage<Header>;
  using Discarded = DiscardedSet<Key>;

  LargeMessageAssembler() : LargeMessageAssembler(Dialect::kDefaultLimits) {}
  explicit LargeMessageAssembler(AssemblyLimits limits);

  // Takes one received piece (the payload is copied if kept) with its
  // doubt. Stale sets met on the way are discarded and counted as timed out.
  Result feed(const Header& header, std::span<const std::uint8_t> payload, rt::TimePoint now,
              std::uint8_t doubt = 0);

  // Discards the sets that received nothing new for `timeout` up to `now`.
  std::vector<Discarded> expire(rt::TimePoint now);
  // When the next set in progress would time out, for scheduling expire().
  std::optional<rt::TimePoint> next_deadline() const;

  std::size_t sets_in_progress() const;
  std::size_t buffered_bytes() const { return total_bytes_; }
  const AssemblyLimits& limits() const { return limits_; }
  const AssemblyCounters& counters() const { return counters_; }

 private:
  enum class SetState : std::uint8_t {
    assembling,
    discarding,  // outgrew the limits: its remaining pieces are dropped until its last one
    completed,   // delivered: kept briefly so that late duplicates are recognised
  };
  struct Set {
    SetState state = SetState::assembling;
    std::optional<Header> first_header;
    std::optional<std::uint16_t> last_sequence;
    std::map<std::uint16_t, std::vector<std::uint8_t>> pieces;  // by sequence number
    std::size_t bytes = 0;
    std::uint8_t doubt = 0;  // the most of the pieces it took
    rt::TimePoint last_activity{};
    std::uint64_t started = 0;  // order of arrival, for the per-source bound
  };
  using Sets = std::map<Key, Set>;

  std::optional<std::uint16_t> first_sequence(const Set& set) const;
  Result feed_new_set(const Key& key, const Header& header, PieceRole role, std::span<const std::uint8_t> payload,
                      rt::TimePoint now, AssemblyIssue issue);
  Result feed_finished_set(typename Sets::iterator it, const Header& header, PieceRole role,
                           std::span<const std::uint8_t> payload, rt::TimePoint now);
  Result feed_assembling_set(typename Sets::iterator it, const Header& header, PieceRole role,
                             std::span<const std::uint8_t> payload, rt::TimePoint now);
  Result supersede(typename Sets::iterator it, const Header& header, PieceRole role,
                   std::span<const std::uint8_t> payload, rt::TimePoint now);
  Result store(typename Sets::iterator it, std::uint16_t sequence, std::span<const std::uint8_t> payload,
               rt::TimePoint now, AssemblyIssue issue);
  Result replace(Set& set, std::vector<std::uint8_t>& held, std::span<const std::uint8_t> payload, rt::TimePoint now);
  Result complete_if_whole(typename Sets::iterator it, rt::TimePoint now, AssemblyIssue issue);
  Result discard_as_too_large(Set& set, rt::TimePoint now);
  bool fits(const Set& set, std::uint16_t sequence) const;
  bool room_for_bytes(std::size_t more, rt::TimePoint now);
  void drop_pieces_outside_range(Set& set);
  void release(Set& set);
  void erase(typename Sets::iterator it);
  bool is_stale(const Set& set, rt::TimePoint now) const { return now >= set.last_activity + limits_.timeout; }
  bool make_room_for_a_set(const Key& key, rt::TimePoint now);
  Result drop(AssemblyIssue issue);

  AssemblyLimits limits_;
  Sets sets_;
  AssemblyCounters counters_;
  std::size_t total_bytes_ = 0;
  std::uint64_t next_started_ = 0;
  std::uint8_t piece_doubt_ = 0;  // of the piece feed() is taking
};

}  // namespace jaus
