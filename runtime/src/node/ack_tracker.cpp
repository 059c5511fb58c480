#include "jaus/node/ack_tracker.hpp"

#include <algorithm>

namespace jaus::node {

AckKey ack_key_of_sent(const Header& sent) {
  return AckKey{sent.source, sent.destination, sent.command_code, sent.sequence};
}

std::string_view to_string(AckOutcome outcome) {
  switch (outcome) {
    case AckOutcome::acknowledged: return "acknowledged";
    case AckOutcome::refused: return "refused (NAK)";
    case AckOutcome::exhausted: return "no answer after the last transmission";
  }
  return "unknown";
}

AckTracker::AckTracker(Options options) : options_(options) {
  options_.max_transmissions = std::max<std::uint32_t>(options_.max_transmissions, 1);
}

TrackResult AckTracker::track(const Header& sent, std::span<const std::uint8_t> payload, rt::TimePoint now,
                              std::optional<AckPolicy> policy) {
  if (sent.ack_nak != AckNak::ack_requested) return TrackResult::not_ack_requested;
  const AckKey key = ack_key_of_sent(sent);
  if (pending_.contains(key)) {
    ++counters_.rejected;
    return TrackResult::already_tracked;
  }
  if (pending_.size() >= options_.max_pending) {
    ++counters_.rejected;
    return TrackResult::full;
  }
  AckPolicy chosen = policy.value_or(AckPolicy{options_.retransmit_after, options_.max_transmissions});
  chosen.max_transmissions = std::max<std::uint32_t>(chosen.max_transmissions, 1);
  pending_.emplace(key, Pending{sent, {payload.begin(), payload.end()}, chosen, 1, now + chosen.retransmit_after});
  ++counters_.tracked;
  return TrackResult::tracked;
}

AckTracker::PendingMap::iterator AckTracker::find_answered(const Header& reply) {
  const AckKey key{reply.destination, reply.source, reply.command_code, reply.sequence};
  if (const auto it = pending_.find(key); it != pending_.end()) return it;
  // A message sent to a broadcast address is answered by whoever received it first.
  return std::find_if(pending_.begin(), pending_.end(), [&](const auto& entry) {
    const AckKey& k = entry.first;
    return k.peer.is_broadcast() && k.peer.matches(reply.source) && k.local == key.local &&
           k.command_code == key.command_code && k.sequence == key.sequence;
  });
}

std::optional<AckResolution> AckTracker::on_reply(const Header& received) {
  if (received.ack_nak != AckNak::ack && received.ack_nak != AckNak::nak) return std::nullopt;
  const auto it = find_answered(received);
  if (it == pending_.end()) {
    ++counters_.unmatched_replies;
    return std::nullopt;
  }
  const bool acknowledged = received.ack_nak == AckNak::ack;
  ++(acknowledged ? counters_.acknowledged : counters_.refused);
  AckResolution resolution{it->first, acknowledged ? AckOutcome::acknowledged : AckOutcome::refused,
                           it->second.transmissions};
  pending_.erase(it);
  return resolution;
}

AckPoll AckTracker::poll(rt::TimePoint now) {
  AckPoll due;
  for (auto it = pending_.begin(); it != pending_.end();) {
    Pending& p = it->second;
    if (now < p.next_due) {
      ++it;
      continue;
    }
    if (p.transmissions >= p.policy.max_transmissions) {
      due.failed.push_back({it->first, AckOutcome::exhausted, p.transmissions});
      ++counters_.exhausted;
      it = pending_.erase(it);
      continue;
    }
    ++p.transmissions;
    // From `now`, not from the missed due time: a late poll must not cause a burst.
    p.next_due = now + p.policy.retransmit_after;
    due.retransmit.push_back({p.header, p.payload, p.transmissions});
    ++counters_.retransmissions;
    ++it;
  }
  return due;
}

std::optional<rt::TimePoint> AckTracker::next_deadline() const {
  std::optional<rt::TimePoint> earliest;
  for (const auto& [key, p] : pending_)
    if (!earliest || p.next_due < *earliest) earliest = p.next_due;
  return earliest;
}

}  // namespace jaus::node
