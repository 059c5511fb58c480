#include "jaus/node/duplicate_filter.hpp"

#include <algorithm>

namespace jaus::node {

namespace {
constexpr std::uint16_t kShutdown = 0x0002;
constexpr std::uint16_t kStandby = 0x0003;
constexpr std::uint16_t kSetEmergency = 0x0006;

std::uint64_t fingerprint_of(std::span<const std::uint8_t> payload) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bits
  for (const std::uint8_t byte : payload) {
    hash ^= byte;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}
}  // namespace

DuplicateFilter::DuplicateFilter(Options options) : options_(options) {
  options_.max_entries = std::max<std::size_t>(options_.max_entries, 1);
}

bool DuplicateFilter::always_delivered(std::uint16_t command_code) {
  return command_code == kSetEmergency || command_code == kStandby || command_code == kShutdown;
}

DuplicateVerdict DuplicateFilter::check(const Header& h, std::span<const std::uint8_t> payload, rt::TimePoint now) {
  if (h.ack_nak != AckNak::ack_requested || h.data_flag != DataFlag::single || always_delivered(h.command_code))
    return DuplicateVerdict::not_filtered;
  const DuplicateKey key{h.source, h.destination, h.command_code, h.sequence};
  const std::uint64_t fingerprint = fingerprint_of(payload);
  if (const auto it = entries_.find(key); it != entries_.end()) {
    Entry& e = it->second;
    const bool duplicate = e.fingerprint == fingerprint && e.size == payload.size() &&
                           now - e.last_seen <= options_.window;
    // Either way the entry now stands for this message, seen now.
    e.fingerprint = fingerprint;
    e.size = payload.size();
    e.last_seen = now;
    recency_.splice(recency_.end(), recency_, e.in_recency);
    if (!duplicate) return DuplicateVerdict::first_copy;
    ++counters_.duplicates;
    return DuplicateVerdict::duplicate;
  }
  if (entries_.size() >= options_.max_entries) {
    // The least recently seen makes room, its nodes reused: a full table
    // (a flood of distinct messages) allocates nothing.
    auto oldest = entries_.extract(recency_.front());
    if (now - oldest.mapped().last_seen <= options_.window) ++counters_.forgotten;
    recency_.splice(recency_.end(), recency_, recency_.begin());
    recency_.back() = key;
    oldest.key() = key;
    oldest.mapped() = Entry{fingerprint, payload.size(), now, std::prev(recency_.end())};
    entries_.insert(std::move(oldest));
    return DuplicateVerdict::first_copy;
  }
  recency_.push_back(key);
  entries_.emplace(key, Entry{fingerprint, payload.size(), now, std::prev(recency_.end())});
  return DuplicateVerdict::first_copy;
}

}  // namespace jaus::node
