// The one large-message assembler, built for both dialects (their adapters:
// jaus/core/large_data_sets.hpp, jaus/jss/large_message.hpp).
#include "jaus/core/large_message_assembler.hpp"

#include <algorithm>

#include "jaus/core/large_data_sets.hpp"
#include "jaus/jss/large_message.hpp"

namespace jaus {

std::string_view to_string(AssemblyIssue issue) {
  switch (issue) {
    case AssemblyIssue::none: return "none";
    case AssemblyIssue::bad_packet: return "data size disagrees with the payload, or unknown data flag";
    case AssemblyIssue::bad_first: return "a first piece too short to carry the message ID";
    case AssemblyIssue::duplicate: return "duplicate piece";
    case AssemblyIssue::inconsistent: return "piece contradicts its large message";
    case AssemblyIssue::too_large: return "large message over its size limit, discarded";
    case AssemblyIssue::refused: return "too many large messages in progress";
    case AssemblyIssue::unmatched_retransmission: return "retransmitted piece without a set in progress";
    case AssemblyIssue::rest_of_discarded_set: return "piece of a discarded large message";
    case AssemblyIssue::replaced: return "retransmission replaced a held piece";
    case AssemblyIssue::superseded: return "new large message discarded an unfinished one";
    case AssemblyIssue::timed_out: return "large message incomplete at timeout, discarded";
  }
  return "unknown";
}

template <class Dialect>
LargeMessageAssembler<Dialect>::LargeMessageAssembler(AssemblyLimits limits) : limits_(limits) {
  limits_.max_pieces_per_set = std::clamp<std::size_t>(limits_.max_pieces_per_set, 2, kMaxPiecesPerMessage);
  limits_.max_sets = std::max<std::size_t>(limits_.max_sets, 1);
  limits_.max_sets_per_source = std::max<std::size_t>(limits_.max_sets_per_source, 1);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::feed(const Header& header, std::span<const std::uint8_t> payload,
                                          rt::TimePoint now, std::uint8_t doubt) -> Result {
  piece_doubt_ = doubt;  // taken into its set where the piece is (store, replace, a role filled in)
  const PieceRole role = Dialect::role_of(header);
  if (role == PieceRole::unknown) return drop(AssemblyIssue::bad_packet);
  if (const AssemblyIssue issue = Dialect::check(header, payload); issue != AssemblyIssue::none) return drop(issue);
  if (role == PieceRole::single) {
    ++counters_.singles;
    return {AssemblyStatus::single, AssemblyIssue::none, std::nullopt};
  }
  const Key key = Dialect::key_of(header);
  auto it = sets_.find(key);
  if (it != sets_.end() && is_stale(it->second, now)) {
    if (it->second.state == SetState::assembling) ++counters_.timed_out;
    erase(it);
    it = sets_.end();
  }
  if (it == sets_.end()) {
    if (role == PieceRole::retransmitted) return drop(AssemblyIssue::unmatched_retransmission);
    return feed_new_set(key, header, role, payload, now, AssemblyIssue::none);
  }
  if (it->second.state != SetState::assembling) return feed_finished_set(it, header, role, payload, now);
  return feed_assembling_set(it, header, role, payload, now);
}

template <class Dialect>
std::optional<std::uint16_t> LargeMessageAssembler<Dialect>::first_sequence(const Set& set) const {
  if (!set.first_header) return std::nullopt;
  return Dialect::sequence_of(*set.first_header);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::feed_new_set(const Key& key, const Header& header, PieceRole role,
                                                  std::span<const std::uint8_t> payload, rt::TimePoint now,
                                                  AssemblyIssue issue) -> Result {
  if (!make_room_for_a_set(key, now)) return drop(AssemblyIssue::refused);
  const auto it = sets_.insert_or_assign(key, Set{}).first;
  Set& set = it->second;
  set.started = next_started_++;
  set.last_activity = now;  // never stale while it is being fed
  if (role == PieceRole::first) set.first_header = header;
  if (role == PieceRole::last) set.last_sequence = Dialect::sequence_of(header);
  return store(it, Dialect::sequence_of(header), payload, now, issue);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::feed_finished_set(typename Sets::iterator it, const Header& header, PieceRole role,
                                                       std::span<const std::uint8_t> payload, rt::TimePoint now)
    -> Result {
  const Set& set = it->second;
  if (set.state == SetState::completed) {
    // Late copies of its pieces are dropped. Where senders may number every
    // set from 0 (RA), a first piece always starts a new message, even with a
    // number of the completed range: they reuse the range each time.
    const std::uint16_t first = *first_sequence(set);
    const auto offset = static_cast<std::uint16_t>(Dialect::sequence_of(header) - first);
    const bool starts_anew = role == PieceRole::first && Dialect::kSendersMayRestartNumbering;
    if (!starts_anew && offset <= static_cast<std::uint16_t>(*set.last_sequence - first))
      return drop(AssemblyIssue::duplicate);
  } else if (role != PieceRole::first) {
    // Discarding: only a new first piece starts over; the old set's last one ends it.
    if (role == PieceRole::last) erase(it);
    return drop(AssemblyIssue::rest_of_discarded_set);
  }
  if (role == PieceRole::retransmitted) return drop(AssemblyIssue::unmatched_retransmission);
  const Key key = it->first;  // `it` may go while making room
  return feed_new_set(key, header, role, payload, now, AssemblyIssue::none);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::feed_assembling_set(typename Sets::iterator it, const Header& header,
                                                         PieceRole role, std::span<const std::uint8_t> payload,
                                                         rt::TimePoint now) -> Result {
  Set& set = it->second;
  const std::uint16_t sequence = Dialect::sequence_of(header);
  const auto held = set.pieces.find(sequence);
  if (role == PieceRole::retransmitted) {
    if (held != set.pieces.end()) return replace(set, held->second, payload, now);
    if (!fits(set, sequence)) return drop(AssemblyIssue::inconsistent);
    return store(it, sequence, payload, now, AssemblyIssue::none);  // fills a gap
  }
  // A number already held with other bytes is no copy: it belongs to a newer
  // message from a sender that numbers every set from 0 (OpenJAUS does).
  // Mixing the two would deliver a corrupt message.
  const bool held_already = held != set.pieces.end();
  if (held_already && !std::ranges::equal(held->second, payload)) return supersede(it, header, role, payload, now);
  switch (role) {
    case PieceRole::first: {
      if (const auto first = first_sequence(set)) {
        if (*first == sequence) return drop(AssemblyIssue::duplicate);
        return supersede(it, header, role, payload, now);  // the sender started another message
      }
      if (set.last_sequence &&
          static_cast<std::uint16_t>(*set.last_sequence - sequence) >= limits_.max_pieces_per_set)
        return supersede(it, header, role, payload, now);
      set.first_header = header;
      drop_pieces_outside_range(set);
      break;
    }
    case PieceRole::last: {
      if (set.last_sequence)
        return drop(*set.last_sequence == sequence ? AssemblyIssue::duplicate : AssemblyIssue::inconsistent);
      if (const auto first = first_sequence(set)) {
        const auto offset = static_cast<std::uint16_t>(sequence - *first);
        if (offset == 0 || offset >= limits_.max_pieces_per_set) return drop(AssemblyIssue::inconsistent);
      }
      set.last_sequence = sequence;
      drop_pieces_outside_range(set);
      break;
    }
    default:  // middle
      if (held_already) return drop(AssemblyIssue::duplicate);
      break;
  }
  if (held_already) {
    // A retransmission of this first or last piece came before it: only its role was missing.
    set.doubt = std::max(set.doubt, piece_doubt_);
    set.last_activity = now;
    return complete_if_whole(it, now, AssemblyIssue::none);
  }
  if (!fits(set, sequence)) return drop(AssemblyIssue::inconsistent);
  return store(it, sequence, payload, now, AssemblyIssue::none);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::replace(Set& set, std::vector<std::uint8_t>& held,
                                             std::span<const std::uint8_t> payload, rt::TimePoint now) -> Result {
  const std::size_t bytes = set.bytes - held.size() + payload.size();
  if (bytes > limits_.max_message_size) return discard_as_too_large(set, now);
  if (payload.size() > held.size() && !room_for_bytes(payload.size() - held.size(), now))
    return discard_as_too_large(set, now);
  total_bytes_ = total_bytes_ - held.size() + payload.size();
  held.assign(payload.begin(), payload.end());
  set.bytes = bytes;
  set.doubt = std::max(set.doubt, piece_doubt_);
  set.last_activity = now;
  ++counters_.replaced;
  return {AssemblyStatus::pending, AssemblyIssue::replaced, std::nullopt};
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::supersede(typename Sets::iterator it, const Header& header, PieceRole role,
                                               std::span<const std::uint8_t> payload, rt::TimePoint now) -> Result {
  ++counters_.superseded;
  const Key key = it->first;
  erase(it);
  return feed_new_set(key, header, role, payload, now, AssemblyIssue::superseded);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::store(typename Sets::iterator it, std::uint16_t sequence,
                                           std::span<const std::uint8_t> payload, rt::TimePoint now,
                                           AssemblyIssue issue) -> Result {
  Set& set = it->second;
  if (set.bytes + payload.size() > limits_.max_message_size || set.pieces.size() + 1 > limits_.max_pieces_per_set ||
      !room_for_bytes(payload.size(), now))
    return discard_as_too_large(set, now);
  set.pieces[sequence].assign(payload.begin(), payload.end());
  set.bytes += payload.size();
  set.doubt = std::max(set.doubt, piece_doubt_);
  total_bytes_ += payload.size();
  set.last_activity = now;
  return complete_if_whole(it, now, issue);
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::complete_if_whole(typename Sets::iterator it, rt::TimePoint now,
                                                       AssemblyIssue issue) -> Result {
  Set& set = it->second;
  if (!set.first_header || !set.last_sequence) return {AssemblyStatus::pending, issue, std::nullopt};
  const std::uint16_t first = *first_sequence(set);
  const std::size_t count = static_cast<std::uint16_t>(*set.last_sequence - first) + std::size_t{1};
  // Pieces outside first..last were dropped when the range became known, so
  // holding `count` pieces means holding every one of them.
  if (set.pieces.size() != count) return {AssemblyStatus::pending, issue, std::nullopt};
  Message message{Dialect::whole_header(*set.first_header), {}, set.doubt};
  message.payload.reserve(set.bytes);
  for (std::size_t i = 0; i < count; ++i) {
    const auto& piece = set.pieces[static_cast<std::uint16_t>(first + i)];
    message.payload.insert(message.payload.end(), piece.begin(), piece.end());
  }
  release(set);
  set.state = SetState::completed;
  set.last_activity = now;
  ++counters_.completed;
  return {AssemblyStatus::complete, issue, std::move(message)};
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::discard_as_too_large(Set& set, rt::TimePoint now) -> Result {
  release(set);
  set.state = SetState::discarding;
  set.last_activity = now;
  return drop(AssemblyIssue::too_large);
}

template <class Dialect>
bool LargeMessageAssembler<Dialect>::fits(const Set& set, std::uint16_t sequence) const {
  // Offsets are taken modulo 2^16, so sets that wrap past 65535 fit too.
  if (const auto first = first_sequence(set)) {
    const auto offset = static_cast<std::uint16_t>(sequence - *first);
    if (offset >= limits_.max_pieces_per_set) return false;
    return !set.last_sequence || offset <= static_cast<std::uint16_t>(*set.last_sequence - *first);
  }
  if (set.last_sequence)
    return static_cast<std::uint16_t>(*set.last_sequence - sequence) < limits_.max_pieces_per_set;
  return true;
}

template <class Dialect>
bool LargeMessageAssembler<Dialect>::room_for_bytes(std::size_t more, rt::TimePoint now) {
  if (total_bytes_ + more <= limits_.max_total_bytes) return true;
  expire(now);  // stale sets make room first (the set being fed is not stale: feed() checked)
  return total_bytes_ + more <= limits_.max_total_bytes;
}

template <class Dialect>
void LargeMessageAssembler<Dialect>::drop_pieces_outside_range(Set& set) {
  for (auto it = set.pieces.begin(); it != set.pieces.end();) {
    if (fits(set, it->first)) {
      ++it;
      continue;
    }
    set.bytes -= it->second.size();
    total_bytes_ -= it->second.size();
    it = set.pieces.erase(it);
    ++counters_.stray;
  }
}

template <class Dialect>
void LargeMessageAssembler<Dialect>::release(Set& set) {
  total_bytes_ -= set.bytes;
  set.pieces.clear();
  set.bytes = 0;
}

template <class Dialect>
void LargeMessageAssembler<Dialect>::erase(typename Sets::iterator it) {
  total_bytes_ -= it->second.bytes;
  sets_.erase(it);
}

template <class Dialect>
bool LargeMessageAssembler<Dialect>::make_room_for_a_set(const Key& key, rt::TimePoint now) {
  // A source with too many sets in progress gives up its own oldest.
  std::size_t own = 0;
  auto oldest = sets_.end();
  for (auto it = sets_.begin(); it != sets_.end(); ++it) {
    if (it->second.state != SetState::assembling || it->first.source != key.source) continue;
    ++own;
    if (oldest == sets_.end() || it->second.started < oldest->second.started) oldest = it;
  }
  if (own >= limits_.max_sets_per_source) {
    ++counters_.superseded;
    erase(oldest);
  }
  if (sets_in_progress() >= limits_.max_sets) {
    expire(now);
    if (sets_in_progress() >= limits_.max_sets) return false;
  }
  // Finished sets are remembered for late duplicates, but no more than as
  // many as sets in progress: the oldest make way.
  while (sets_.size() >= 2 * limits_.max_sets) {
    auto finished = sets_.end();
    for (auto it = sets_.begin(); it != sets_.end(); ++it)
      if (it->second.state != SetState::assembling &&
          (finished == sets_.end() || it->second.last_activity < finished->second.last_activity))
        finished = it;
    if (finished == sets_.end()) break;
    erase(finished);
  }
  return true;
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::expire(rt::TimePoint now) -> std::vector<Discarded> {
  std::vector<Discarded> discarded;
  for (auto it = sets_.begin(); it != sets_.end();) {
    if (!is_stale(it->second, now)) {
      ++it;
      continue;
    }
    if (it->second.state == SetState::assembling) {
      discarded.push_back({it->first, AssemblyIssue::timed_out, it->second.pieces.size(), it->second.bytes});
      ++counters_.timed_out;
    }
    total_bytes_ -= it->second.bytes;
    it = sets_.erase(it);
  }
  return discarded;
}

template <class Dialect>
std::optional<rt::TimePoint> LargeMessageAssembler<Dialect>::next_deadline() const {
  std::optional<rt::TimePoint> earliest;
  for (const auto& entry : sets_)
    if (entry.second.state == SetState::assembling) {
      const auto deadline = entry.second.last_activity + limits_.timeout;
      if (!earliest || deadline < *earliest) earliest = deadline;
    }
  return earliest;
}

template <class Dialect>
std::size_t LargeMessageAssembler<Dialect>::sets_in_progress() const {
  return static_cast<std::size_t>(std::count_if(sets_.begin(), sets_.end(), [](const auto& entry) {
    return entry.second.state == SetState::assembling;
  }));
}

template <class Dialect>
auto LargeMessageAssembler<Dialect>::drop(AssemblyIssue issue) -> Result {
  switch (issue) {
    case AssemblyIssue::bad_packet: ++counters_.bad_packets; break;
    case AssemblyIssue::bad_first: ++counters_.bad_first; break;
    case AssemblyIssue::duplicate: ++counters_.duplicates; break;
    case AssemblyIssue::inconsistent:
    case AssemblyIssue::unmatched_retransmission:
    case AssemblyIssue::rest_of_discarded_set: ++counters_.stray; break;
    case AssemblyIssue::too_large: ++counters_.too_large; break;
    case AssemblyIssue::refused: ++counters_.refused; break;
    default: break;
  }
  return {AssemblyStatus::dropped, issue, std::nullopt};
}

template class LargeMessageAssembler<RaLargeDataSets>;
template class LargeMessageAssembler<jss::JudpLargeMessages>;

}  // namespace jaus
