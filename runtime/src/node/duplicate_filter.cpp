#include "jaus/node/duplicate_filter.hpp"

#include <algorithm>

#include "jaus/core/stop_commands.hpp"

namespace jaus::node {

namespace {

// Where senders number from after a start: Jr from 1, JRM (and our nodes) from 0.
constexpr std::uint16_t kHighestFirstSequence = 1;

std::uint64_t packed(const Address& a) {
  return std::uint64_t{a.subsystem} << 24 | std::uint64_t{a.node} << 16 | std::uint64_t{a.component} << 8 | a.instance;
}

// Whether `sequence` comes before `last` (modulo 2^16, as the numbers wrap).
bool behind(std::uint16_t sequence, std::uint16_t last) {
  const auto distance = static_cast<std::uint16_t>(last - sequence);
  return distance != 0 && distance < 0x8000;
}

}  // namespace

std::uint64_t fingerprint_of(std::span<const std::uint8_t> bytes, std::uint64_t hash) {
  for (const std::uint8_t byte : bytes) {
    hash ^= byte;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

PacketIdentity identity_of(const Header& h, std::span<const std::uint8_t> payload) {
  // Its code and data flag (a packet of a large data set is not the whole message), then the payload.
  const std::uint8_t code[3] = {static_cast<std::uint8_t>(h.command_code), static_cast<std::uint8_t>(h.command_code >> 8),
                                static_cast<std::uint8_t>(h.data_flag)};
  PacketIdentity packet;
  packet.source = packed(h.source);
  packet.destination = packed(h.destination);
  packet.sequence = h.sequence;
  packet.ack_requested = h.ack_nak == AckNak::ack_requested;
  packet.piece = h.data_flag != DataFlag::single;
  packet.stop = !packet.piece && DuplicateFilter::always_delivered(h.command_code);
  // Only what the filter may remember is fingerprinted (not every query).
  if (packet.ack_requested && !packet.stop) packet.fingerprint = fingerprint_of(payload, fingerprint_of(code));
  packet.size = payload.size();
  return packet;
}

DuplicateFilter::DuplicateFilter(Options options) : options_(options) {
  options_.max_entries = std::max<std::size_t>(options_.max_entries, 1);
}

bool DuplicateFilter::always_delivered(std::uint16_t code) { return is_stop_command(code); }

DuplicateVerdict DuplicateFilter::check(const PacketIdentity& p, rt::TimePoint now) {
  if (p.piece && !options_.pieces_filtered) return DuplicateVerdict::not_filtered;
  expire(now);
  const StreamKey stream_key{p.source, p.destination};
  auto stream = streams_.find(stream_key);
  // The sender numbers again from its start: it restarted (a copy that a
  // stop followed is judged below, before this counts).
  const bool restarted = stream != streams_.end() && p.sequence <= kHighestFirstSequence &&
                         behind(p.sequence, stream->second.last_sequence);
  if (p.stop || !p.ack_requested) {
    // Never filtered. What the stream remembers learns of it: a stop makes
    // every copy of what came before it a late one.
    if (stream == streams_.end()) return DuplicateVerdict::not_filtered;
    if (restarted && !p.stop) {
      forget_session(stream_key);
      if (const auto kept = streams_.find(stream_key); kept != streams_.end()) kept->second.last_sequence = p.sequence;
      ++counters_.new_sessions;
      return DuplicateVerdict::new_session;
    }
    stream->second.last_sequence = p.sequence;
    if (p.stop) stream->second.last_stop = ++arrivals_;
    return DuplicateVerdict::not_filtered;
  }
  const Key key{p.source, p.destination, p.sequence};
  const Entry entry{p.fingerprint, p.size, now, ++arrivals_};
  if (const auto it = entries_.find(key); it != entries_.end()) {
    // (An entry's stream exists while the entry does.)
    const std::uint64_t last_stop = stream != streams_.end() ? stream->second.last_stop : 0;
    const bool superseded = last_stop > it->second.arrival;  // a stop came after it
    const bool same = it->second.fingerprint == entry.fingerprint && it->second.size == entry.size;
    if (same && superseded) {
      ++counters_.duplicates;
      ++counters_.late_copies;
      return DuplicateVerdict::late_copy;
    }
    if (same && !restarted) {
      remember(key, entry);  // seen again: its window starts again
      ++counters_.duplicates;
      return DuplicateVerdict::duplicate;
    }
    if (!same && superseded && !restarted) {
      // Another message under a number used before a stop: new (what a
      // stop followed is never acted on again anyway).
      remember(key, entry);
      return DuplicateVerdict::first_copy;
    }
    // Its number reused for another message, or numbering again from the
    // start: a new session of the sender.
    forget_session(stream_key);
    remember(key, entry);
    ++counters_.new_sessions;
    return DuplicateVerdict::new_session;
  }
  if (restarted) {
    forget_session(stream_key);
    remember(key, entry);
    ++counters_.new_sessions;
    return DuplicateVerdict::new_session;
  }
  remember(key, entry);
  return DuplicateVerdict::first_copy;
}

bool DuplicateFilter::current(const Seen& seen) const {
  const auto it = entries_.find(seen.key);
  return it != entries_.end() && it->second.arrival == seen.arrival;
}

void DuplicateFilter::remember(const Key& key, const Entry& entry) {
  auto& stream = streams_[{std::get<0>(key), std::get<1>(key)}];
  stream.last_sequence = std::get<2>(key);
  if (entries_.insert_or_assign(key, entry).second) ++stream.entries;
  order_.push_back(Seen{entry.seen, entry.arrival, key});
  // Bounded: the least recently seen make room.
  while (entries_.size() > options_.max_entries) {
    const Seen oldest = order_.front();
    order_.pop_front();
    if (const auto found = entries_.find(oldest.key); found != entries_.end() && found->second.arrival == oldest.arrival) {
      if (entry.seen - found->second.seen <= options_.window) ++counters_.forgotten;
      erase_entry(found);
    }
  }
  // Items of entries seen again or forgotten pile up under copies: drop them now and then.
  if (order_.size() > 2 * options_.max_entries + 16) {
    std::erase_if(order_, [this](const Seen& seen) { return !current(seen); });
  }
}

void DuplicateFilter::erase_entry(std::map<Key, Entry>::iterator it) {
  const StreamKey stream_key{std::get<0>(it->first), std::get<1>(it->first)};
  entries_.erase(it);
  if (const auto stream = streams_.find(stream_key); stream != streams_.end() && --stream->second.entries == 0)
    streams_.erase(stream);
}

void DuplicateFilter::forget_session(const StreamKey& stream_key) {
  const auto stream = streams_.find(stream_key);
  if (stream == streams_.end()) return;
  // What a stop followed stays: its copies never act, restart or not.
  const std::uint64_t last_stop = stream->second.last_stop;
  auto it = entries_.lower_bound(Key{stream_key.first, stream_key.second, 0});
  const auto end = entries_.upper_bound(Key{stream_key.first, stream_key.second, 0xFFFF});
  while (it != end) {
    if (it->second.arrival > last_stop) {
      it = entries_.erase(it);  // its item in order_ is stale now
      --stream->second.entries;
    } else {
      ++it;
    }
  }
  if (stream->second.entries == 0) streams_.erase(stream);
}

void DuplicateFilter::expire(rt::TimePoint now) {
  // An entry lives `window` after it was last seen (a copy exactly then is still one).
  while (!order_.empty() && now - order_.front().at > options_.window) {
    const Seen oldest = order_.front();
    order_.pop_front();
    if (const auto it = entries_.find(oldest.key); it != entries_.end() && it->second.arrival == oldest.arrival)
      erase_entry(it);
  }
}

}  // namespace jaus::node
