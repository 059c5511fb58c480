#include "face_transport.hpp"

#include <algorithm>

namespace jaus::jss_face {

namespace {

// Where senders number from after a start: Jr from 1, JRM (and this face) from 0.
constexpr std::uint16_t kHighestFirstSequence = 1;

std::uint64_t fingerprint_of(jss::JudpDataFlag data_flag, std::span<const std::uint8_t> contents) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bits
  const auto add = [&](std::uint8_t byte) {
    hash ^= byte;
    hash *= 0x100000001b3ULL;
  };
  add(static_cast<std::uint8_t>(data_flag));  // a packet of a large message is not a single message
  for (const std::uint8_t byte : contents) add(byte);
  return hash;
}

// Whether `sequence` comes before `last` (modulo 2^16, as the numbers wrap).
bool behind(std::uint16_t sequence, std::uint16_t last) {
  const auto distance = static_cast<std::uint16_t>(last - sequence);
  return distance != 0 && distance < 0x8000;
}

}  // namespace

JssDuplicateFilter::JssDuplicateFilter(Options options) : options_(options) {
  options_.max_entries = std::max<std::size_t>(options_.max_entries, 1);
}

bool JssDuplicateFilter::is_stop(std::uint16_t message_id) {
  constexpr std::uint16_t shutdown = 0x0002, standby = 0x0003, set_emergency = 0x0006;
  return message_id == set_emergency || message_id == standby || message_id == shutdown;
}

JssCopyVerdict JssDuplicateFilter::check(const jss::JudpHeader& h, std::span<const std::uint8_t> contents,
                                         rt::TimePoint now) {
  expire(now);
  const StreamKey stream_key{h.source.packed(), h.destination.packed()};
  auto stream = streams_.find(stream_key);
  // The sender numbers again from its start: it restarted (a copy that a
  // stop followed is judged below, before this counts).
  const bool restarted = stream != streams_.end() && h.sequence <= kHighestFirstSequence &&
                         behind(h.sequence, stream->second.last_sequence);
  const bool stop = h.data_flag == jss::JudpDataFlag::single && is_stop(jss::message_id_of(contents));
  if (stop || h.ack_nak != jss::JudpAckNak::ack_requested) {
    // Never filtered. What the stream remembers learns of it: a stop makes
    // every copy of what came before it a late one.
    if (stream == streams_.end()) return JssCopyVerdict::not_filtered;
    if (restarted && !stop) {
      forget_session(stream_key);
      if (const auto kept = streams_.find(stream_key); kept != streams_.end()) kept->second.last_sequence = h.sequence;
      return JssCopyVerdict::new_session;
    }
    stream->second.last_sequence = h.sequence;
    if (stop) stream->second.last_stop = ++arrivals_;
    return JssCopyVerdict::not_filtered;
  }
  const Key key{stream_key.first, stream_key.second, h.sequence};
  const Entry entry{fingerprint_of(h.data_flag, contents), contents.size(), now, ++arrivals_};
  if (const auto it = entries_.find(key); it != entries_.end()) {
    // (An entry's stream exists while the entry does.)
    const std::uint64_t last_stop = stream != streams_.end() ? stream->second.last_stop : 0;
    const bool superseded = last_stop > it->second.arrival;  // a stop came after it
    const bool same = it->second.fingerprint == entry.fingerprint && it->second.size == entry.size;
    if (same && superseded) return JssCopyVerdict::late_copy;
    if (same && !restarted) {
      if (stream != streams_.end()) stream->second.last_sequence = h.sequence;
      return JssCopyVerdict::copy;
    }
    if (!same && superseded && !restarted) {
      // Another message under a number used before a stop: new (what a
      // stop followed is never acted on again anyway).
      remember(key, entry);
      return JssCopyVerdict::first;
    }
    // Its number reused for another message, or numbering again from the
    // start: a new session of the sender.
    forget_session(stream_key);
    remember(key, entry);
    return JssCopyVerdict::new_session;
  }
  if (restarted) {
    forget_session(stream_key);
    remember(key, entry);
    return JssCopyVerdict::new_session;
  }
  remember(key, entry);
  return JssCopyVerdict::first;
}

void JssDuplicateFilter::remember(const Key& key, const Entry& entry) {
  auto& stream = streams_[{std::get<0>(key), std::get<1>(key)}];
  stream.last_sequence = std::get<2>(key);
  if (entries_.insert_or_assign(key, entry).second) ++stream.entries;
  order_.push_back(Arrival{entry.at, entry.arrival, key});
  // Bounded: the oldest make room (stale items of the order first: they cost nothing).
  while (entries_.size() > options_.max_entries || order_.size() > 2 * options_.max_entries) {
    const Arrival oldest = order_.front();
    order_.pop_front();
    if (const auto found = entries_.find(oldest.key); found != entries_.end() && found->second.arrival == oldest.arrival)
      erase_entry(found);
  }
}

void JssDuplicateFilter::erase_entry(std::map<Key, Entry>::iterator it) {
  const StreamKey stream_key{std::get<0>(it->first), std::get<1>(it->first)};
  entries_.erase(it);
  if (const auto stream = streams_.find(stream_key); stream != streams_.end() && --stream->second.entries == 0)
    streams_.erase(stream);
}

void JssDuplicateFilter::forget_session(const StreamKey& stream_key) {
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

void JssDuplicateFilter::expire(rt::TimePoint now) {
  while (!order_.empty() && now - order_.front().at >= options_.window) {
    const Arrival oldest = order_.front();
    order_.pop_front();
    if (const auto it = entries_.find(oldest.key); it != entries_.end() && it->second.arrival == oldest.arrival)
      erase_entry(it);
  }
}

}  // namespace jaus::jss_face
