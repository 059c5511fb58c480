#include "jaus/node/large_data_set_assembler.hpp"

#include <algorithm>

#include "jaus/node/large_data_set_splitter.hpp"

namespace jaus::node {

std::string_view to_string(AssemblyIssue issue) {
  switch (issue) {
    case AssemblyIssue::none: return "none";
    case AssemblyIssue::bad_packet: return "data size disagrees with the payload, or unknown data flag";
    case AssemblyIssue::duplicate: return "duplicate packet";
    case AssemblyIssue::inconsistent: return "packet contradicts its large data set";
    case AssemblyIssue::oversize: return "large data set over its size limit, discarded";
    case AssemblyIssue::too_many_sets: return "too many large data sets in progress";
    case AssemblyIssue::unmatched_retransmission: return "retransmitted packet without a set in progress";
    case AssemblyIssue::rest_of_discarded_set: return "packet of a discarded large data set";
    case AssemblyIssue::replaced: return "retransmission replaced a held packet";
    case AssemblyIssue::superseded: return "new large data set discarded the unfinished one";
    case AssemblyIssue::timed_out: return "large data set incomplete at timeout, discarded";
  }
  return "unknown";
}

LargeDataSetAssembler::LargeDataSetAssembler(Options options) : options_(options) {
  options_.max_packets_per_set = std::clamp<std::size_t>(options_.max_packets_per_set, 2, kMaxPacketsPerSet);
  options_.max_concurrent_sets = std::max<std::size_t>(options_.max_concurrent_sets, 1);
}

AssemblyResult LargeDataSetAssembler::feed(const Header& header, std::span<const std::uint8_t> payload,
                                           rt::TimePoint now) {
  if (header.data_size != payload.size() || !detail::is_known_data_flag(static_cast<unsigned>(header.data_flag)))
    return drop(AssemblyIssue::bad_packet);
  if (header.data_flag == DataFlag::single) {
    ++counters_.singles;
    return {AssemblyStatus::single, AssemblyIssue::none, std::nullopt};
  }
  const LargeDataSetKey key{header.source, header.command_code};
  auto it = sets_.find(key);
  if (it != sets_.end() && is_stale(it->second, now)) {
    if (it->second.state == SetState::assembling) ++counters_.timed_out;
    sets_.erase(it);
    it = sets_.end();
  }
  if (it == sets_.end()) {
    if (header.data_flag == DataFlag::retransmitted) return drop(AssemblyIssue::unmatched_retransmission);
    return feed_new_set(key, header, payload, now, AssemblyIssue::none);
  }
  if (it->second.state != SetState::assembling) return feed_finished_set(it, header, payload, now);
  return feed_assembling_set(it, header, payload, now);
}

AssemblyResult LargeDataSetAssembler::feed_new_set(const LargeDataSetKey& key, const Header& header,
                                                   std::span<const std::uint8_t> payload, rt::TimePoint now,
                                                   AssemblyIssue issue) {
  if (!make_room_for_a_set(now)) return drop(AssemblyIssue::too_many_sets);
  const auto it = sets_.insert_or_assign(key, Set{}).first;
  Set& set = it->second;
  if (header.data_flag == DataFlag::first) set.first_header = header;
  if (header.data_flag == DataFlag::last) set.last_sequence = header.sequence;
  return store(it, header.sequence, payload, now, issue);
}

AssemblyResult LargeDataSetAssembler::feed_finished_set(Sets::iterator it, const Header& header,
                                                        std::span<const std::uint8_t> payload, rt::TimePoint now) {
  const Set& set = it->second;
  if (set.state == SetState::completed) {
    // Late copies of its packets are dropped. A first packet always starts a
    // new message, even with a number of the completed range: senders that
    // number every set from 0 reuse the range each time.
    const std::uint16_t first = set.first_header->sequence;
    const auto offset = static_cast<std::uint16_t>(header.sequence - first);
    if (header.data_flag != DataFlag::first && offset <= static_cast<std::uint16_t>(*set.last_sequence - first))
      return drop(AssemblyIssue::duplicate);
  } else if (header.data_flag != DataFlag::first) {
    // Discarding: only a new first packet starts over; the old set's last one ends it.
    if (header.data_flag == DataFlag::last) sets_.erase(it);
    return drop(AssemblyIssue::rest_of_discarded_set);
  }
  if (header.data_flag == DataFlag::retransmitted) return drop(AssemblyIssue::unmatched_retransmission);
  const LargeDataSetKey key = it->first;  // `it` may go while making room
  return feed_new_set(key, header, payload, now, AssemblyIssue::none);
}

AssemblyResult LargeDataSetAssembler::feed_assembling_set(Sets::iterator it, const Header& header,
                                                          std::span<const std::uint8_t> payload,
                                                          rt::TimePoint now) {
  Set& set = it->second;
  const std::uint16_t sequence = header.sequence;
  const auto held = set.packets.find(sequence);
  if (header.data_flag == DataFlag::retransmitted) {
    if (held == set.packets.end()) {
      if (!fits(set, sequence)) return drop(AssemblyIssue::inconsistent);
      return store(it, sequence, payload, now, AssemblyIssue::none);  // fills a gap
    }
    const std::size_t bytes = set.bytes - held->second.size() + payload.size();
    if (bytes > options_.max_message_size) return discard_as_oversize(set, now);
    held->second.assign(payload.begin(), payload.end());
    set.bytes = bytes;
    set.last_activity = now;
    ++counters_.replaced;
    return {AssemblyStatus::pending, AssemblyIssue::replaced, std::nullopt};
  }
  // A number already held with other bytes is no copy: it belongs to a newer
  // message from a sender that numbers every set from 0 (OpenJAUS does).
  // Mixing the two would deliver a corrupt message.
  const bool held_already = held != set.packets.end();
  if (held_already && !std::ranges::equal(held->second, payload)) return supersede(it, header, payload, now);
  switch (header.data_flag) {
    case DataFlag::first: {
      if (set.first_header) {
        if (set.first_header->sequence == sequence) return drop(AssemblyIssue::duplicate);
        return supersede(it, header, payload, now);  // the sender started another message
      }
      if (set.last_sequence &&
          static_cast<std::uint16_t>(*set.last_sequence - sequence) >= options_.max_packets_per_set)
        return supersede(it, header, payload, now);
      set.first_header = header;
      drop_packets_outside_range(set);
      break;
    }
    case DataFlag::last: {
      if (set.last_sequence)
        return drop(*set.last_sequence == sequence ? AssemblyIssue::duplicate : AssemblyIssue::inconsistent);
      if (set.first_header) {
        const auto offset = static_cast<std::uint16_t>(sequence - set.first_header->sequence);
        if (offset == 0 || offset >= options_.max_packets_per_set) return drop(AssemblyIssue::inconsistent);
      }
      set.last_sequence = sequence;
      drop_packets_outside_range(set);
      break;
    }
    default:  // middle
      if (held_already) return drop(AssemblyIssue::duplicate);
      break;
  }
  if (held_already) {
    // A retransmission of this first or last packet came before it: only its role was missing.
    set.last_activity = now;
    return complete_if_whole(it, now, AssemblyIssue::none);
  }
  if (!fits(set, sequence)) return drop(AssemblyIssue::inconsistent);
  return store(it, sequence, payload, now, AssemblyIssue::none);
}

AssemblyResult LargeDataSetAssembler::supersede(Sets::iterator it, const Header& header,
                                                std::span<const std::uint8_t> payload, rt::TimePoint now) {
  ++counters_.superseded;
  const LargeDataSetKey key = it->first;
  sets_.erase(it);
  return feed_new_set(key, header, payload, now, AssemblyIssue::superseded);
}

AssemblyResult LargeDataSetAssembler::store(Sets::iterator it, std::uint16_t sequence,
                                            std::span<const std::uint8_t> payload, rt::TimePoint now,
                                            AssemblyIssue issue) {
  Set& set = it->second;
  if (set.bytes + payload.size() > options_.max_message_size ||
      set.packets.size() + 1 > options_.max_packets_per_set)
    return discard_as_oversize(set, now);
  set.packets[sequence].assign(payload.begin(), payload.end());
  set.bytes += payload.size();
  set.last_activity = now;
  return complete_if_whole(it, now, issue);
}

AssemblyResult LargeDataSetAssembler::complete_if_whole(Sets::iterator it, rt::TimePoint now,
                                                        AssemblyIssue issue) {
  Set& set = it->second;
  if (!set.first_header || !set.last_sequence) return {AssemblyStatus::pending, issue, std::nullopt};
  const std::uint16_t first = set.first_header->sequence;
  const std::size_t count = static_cast<std::uint16_t>(*set.last_sequence - first) + std::size_t{1};
  // Packets outside first..last were dropped when the range became known, so
  // holding `count` packets means holding every one of them.
  if (set.packets.size() != count) return {AssemblyStatus::pending, issue, std::nullopt};
  AssembledMessage message{*set.first_header, {}};
  message.payload.reserve(set.bytes);
  for (std::size_t i = 0; i < count; ++i) {
    const auto& part = set.packets[static_cast<std::uint16_t>(first + i)];
    message.payload.insert(message.payload.end(), part.begin(), part.end());
  }
  set.packets.clear();
  set.bytes = 0;
  set.state = SetState::completed;
  set.last_activity = now;
  ++counters_.completed;
  return {AssemblyStatus::complete, issue, std::move(message)};
}

AssemblyResult LargeDataSetAssembler::discard_as_oversize(Set& set, rt::TimePoint now) {
  set.packets.clear();
  set.bytes = 0;
  set.state = SetState::discarding;
  set.last_activity = now;
  return drop(AssemblyIssue::oversize);
}

bool LargeDataSetAssembler::fits(const Set& set, std::uint16_t sequence) const {
  // Offsets are taken modulo 2^16, so sets that wrap past 65535 fit too.
  if (set.first_header) {
    const auto offset = static_cast<std::uint16_t>(sequence - set.first_header->sequence);
    if (offset >= options_.max_packets_per_set) return false;
    return !set.last_sequence || offset <= static_cast<std::uint16_t>(*set.last_sequence - set.first_header->sequence);
  }
  if (set.last_sequence)
    return static_cast<std::uint16_t>(*set.last_sequence - sequence) < options_.max_packets_per_set;
  return true;
}

void LargeDataSetAssembler::drop_packets_outside_range(Set& set) {
  for (auto it = set.packets.begin(); it != set.packets.end();) {
    if (fits(set, it->first)) {
      ++it;
      continue;
    }
    set.bytes -= it->second.size();
    it = set.packets.erase(it);
    ++counters_.inconsistent;
  }
}

bool LargeDataSetAssembler::make_room_for_a_set(rt::TimePoint now) {
  if (sets_in_progress() >= options_.max_concurrent_sets) {
    expire(now);
    if (sets_in_progress() >= options_.max_concurrent_sets) return false;
  }
  // Finished sets are remembered for late duplicates, but no more than as
  // many as sets in progress: the oldest make way.
  while (sets_.size() >= 2 * options_.max_concurrent_sets) {
    auto oldest = sets_.end();
    for (auto it = sets_.begin(); it != sets_.end(); ++it)
      if (it->second.state != SetState::assembling &&
          (oldest == sets_.end() || it->second.last_activity < oldest->second.last_activity))
        oldest = it;
    if (oldest == sets_.end()) break;
    sets_.erase(oldest);
  }
  return true;
}

std::vector<DiscardedSet> LargeDataSetAssembler::expire(rt::TimePoint now) {
  std::vector<DiscardedSet> discarded;
  for (auto it = sets_.begin(); it != sets_.end();) {
    if (!is_stale(it->second, now)) {
      ++it;
      continue;
    }
    if (it->second.state == SetState::assembling) {
      discarded.push_back({it->first, AssemblyIssue::timed_out, it->second.packets.size(), it->second.bytes});
      ++counters_.timed_out;
    }
    it = sets_.erase(it);
  }
  return discarded;
}

std::optional<rt::TimePoint> LargeDataSetAssembler::next_deadline() const {
  std::optional<rt::TimePoint> earliest;
  for (const auto& [key, set] : sets_)
    if (set.state == SetState::assembling) {
      const auto deadline = set.last_activity + options_.timeout;
      if (!earliest || deadline < *earliest) earliest = deadline;
    }
  return earliest;
}

std::size_t LargeDataSetAssembler::sets_in_progress() const {
  return static_cast<std::size_t>(std::count_if(sets_.begin(), sets_.end(), [](const auto& entry) {
    return entry.second.state == SetState::assembling;
  }));
}

std::size_t LargeDataSetAssembler::buffered_bytes() const {
  std::size_t bytes = 0;
  for (const auto& [key, set] : sets_) bytes += set.bytes;
  return bytes;
}

AssemblyResult LargeDataSetAssembler::drop(AssemblyIssue issue) {
  switch (issue) {
    case AssemblyIssue::bad_packet: ++counters_.bad_packets; break;
    case AssemblyIssue::duplicate: ++counters_.duplicates; break;
    case AssemblyIssue::inconsistent: ++counters_.inconsistent; break;
    case AssemblyIssue::oversize: ++counters_.oversize; break;
    case AssemblyIssue::too_many_sets: ++counters_.too_many_sets; break;
    case AssemblyIssue::unmatched_retransmission: ++counters_.unmatched_retransmissions; break;
    case AssemblyIssue::rest_of_discarded_set: ++counters_.rest_of_discarded_sets; break;
    default: break;
  }
  return {AssemblyStatus::dropped, issue, std::nullopt};
}

}  // namespace jaus::node
