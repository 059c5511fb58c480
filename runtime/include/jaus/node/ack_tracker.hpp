// Sender side of ACK/NAK: remembers the messages we sent with an ACK request
// (ack_nak = 1), says when to send them again, and settles each one when the
// destination answers with a matching ACK (3) or NAK (2), or when every
// transmission went unanswered.
//
// Defaults: 3 transmissions 1 s apart, failure 1 s after the last one, so a
// silent peer is given up after 3 s, the time after which peers treat a component
// as gone (docs/wire-format.md, "Liveness and discovery"). A message may carry its own AckPolicy instead (commands
// that must arrive over a lossy link: every 50 ms, 10 times; issue 32). Retransmissions repeat the packet exactly (same
// sequence number, which the ACK echoes, and same data flag: a flag of 4
// would hide which part of a large data set the packet is).
//
// One tracker for both dialects: BasicAckTracker<Dialect> knows a dialect's
// headers through a small description (RaAcks here for RA 3.x; the JSS
// operator session's for AS5669A), so the policy, the count of
// transmissions, the settling by an answer and the counters are written once.
#pragma once

#include <algorithm>
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

// An ACK carries the acknowledged message's code and sequence number (docs/wire-format.md, "Priority and
// ACK/NAK"): keyed by those and its destination, and by our sending component, since a node hosts several.
struct AckKey {
  Address local;  // our component that sent the message
  Address peer;   // its destination
  std::uint16_t command_code = 0;
  std::uint16_t sequence = 0;
  auto operator<=>(const AckKey&) const = default;
};
AckKey ack_key_of_sent(const Header& sent);

// RA 3.x's headers as the tracker reads them.
struct RaAcks {
  using Header = jaus::Header;
  using Key = AckKey;
  static bool asks_ack(const Header& h) { return h.ack_nak == AckNak::ack_requested; }
  // true: an ACK; false: a NAK; none: neither.
  static std::optional<bool> answer_of(const Header& h) {
    if (h.ack_nak == AckNak::ack) return true;
    if (h.ack_nak == AckNak::nak) return false;
    return std::nullopt;
  }
  static Key key_of_sent(const Header& sent) { return ack_key_of_sent(sent); }
  // The key of the message an answer answers (its source is our peer).
  static Key key_of_answer(const Header& answer) {
    return Key{answer.destination, answer.source, answer.command_code, answer.sequence};
  }
  // A message sent to a broadcast address is answered by whoever received it first.
  static bool settled_by(const Key& pending, const Key& answered) {
    return pending.peer.is_broadcast() && pending.peer.matches(answered.peer) && pending.local == answered.local &&
           pending.command_code == answered.command_code && pending.sequence == answered.sequence;
  }
};

enum class AckOutcome : std::uint8_t {
  acknowledged,  // the destination answered ACK
  refused,       // the destination answered NAK
  exhausted,     // no answer after the last transmission
};
std::string_view to_string(AckOutcome outcome);

template <class Key>
struct BasicAckResolution {
  Key key;
  AckOutcome outcome = AckOutcome::acknowledged;
  std::uint32_t transmissions = 0;  // how many times the message went out
};

enum class TrackResult : std::uint8_t {
  tracked,
  not_ack_requested,  // the header does not request an ACK: nothing to wait for
  already_tracked,    // same key still pending (sequence numbers repeated too soon)
  full,               // max_pending reached: the caller should fail the send
};

// How one message is retransmitted: every `retransmit_after` until
// answered, at most `max_transmissions` times (the first one included, at
// least 1), given up `retransmit_after` after the last one.
struct AckPolicy {
  rt::Duration retransmit_after = std::chrono::seconds(1);
  std::uint32_t max_transmissions = 3;  // first one included
};

// A message to send again, exactly as first sent.
template <class Header>
struct BasicRetransmission {
  Header header;
  std::vector<std::uint8_t> payload;
  std::uint32_t transmission = 0;  // 2 for the first retransmission, ...
};

template <class Dialect>
struct BasicAckPoll {
  std::vector<BasicRetransmission<typename Dialect::Header>> retransmit;
  std::vector<BasicAckResolution<typename Dialect::Key>> failed;  // outcome exhausted
};

struct AckCounters {
  std::uint64_t tracked = 0;
  std::uint64_t acknowledged = 0;
  std::uint64_t refused = 0;
  std::uint64_t exhausted = 0;
  std::uint64_t retransmissions = 0;
  std::uint64_t unmatched_replies = 0;  // ACK/NAK for nothing we wait for (late, duplicate or forged)
  std::uint64_t rejected = 0;           // track() calls refused as already tracked or full
};

template <class Dialect>
class BasicAckTracker {
 public:
  using Header = typename Dialect::Header;
  using Key = typename Dialect::Key;
  using Resolution = BasicAckResolution<Key>;
  using Poll = BasicAckPoll<Dialect>;

  struct Options {
    rt::Duration retransmit_after = std::chrono::seconds(1);  // between transmissions, and after the last
    std::uint32_t max_transmissions = 3;                      // first one included (at least 1)
    std::size_t max_pending = 256;                            // messages awaiting an answer
  };

  BasicAckTracker() : BasicAckTracker(Options{}) {}
  explicit BasicAckTracker(Options options) : options_(options) {
    options_.max_transmissions = std::max<std::uint32_t>(options_.max_transmissions, 1);
  }

  // Records a message just sent at `now` (its payload, or for a dialect
  // whose retransmission is a whole datagram that datagram, is copied for
  // retransmission), retransmitted per `policy`, or per the Options when none.
  TrackResult track(const Header& sent, std::span<const std::uint8_t> payload, rt::TimePoint now,
                    std::optional<AckPolicy> policy = {}) {
    if (!Dialect::asks_ack(sent)) return TrackResult::not_ack_requested;
    const Key key = Dialect::key_of_sent(sent);
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

  // Settles the pending message a received ACK or NAK answers; nothing for
  // other messages and for answers to nothing pending (counted).
  std::optional<Resolution> on_reply(const Header& received) {
    const auto answer = Dialect::answer_of(received);
    if (!answer) return std::nullopt;
    const auto it = find_answered(Dialect::key_of_answer(received));
    if (it == pending_.end()) {
      ++counters_.unmatched_replies;
      return std::nullopt;
    }
    ++(*answer ? counters_.acknowledged : counters_.refused);
    Resolution resolution{it->first, *answer ? AckOutcome::acknowledged : AckOutcome::refused,
                          it->second.transmissions};
    pending_.erase(it);
    return resolution;
  }

  // Stops waiting for a pending message (its sender gave up on it, e.g.
  // interrupted): nothing more is sent of it. How many times it went out; none when not pending.
  std::optional<std::uint32_t> forget(const Key& key) {
    const auto it = pending_.find(key);
    if (it == pending_.end()) return std::nullopt;
    const std::uint32_t transmissions = it->second.transmissions;
    pending_.erase(it);
    return transmissions;
  }

  // What is due at `now`: messages to send again and messages given up.
  Poll poll(rt::TimePoint now) {
    Poll due;
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
  // When poll() next has something to do.
  std::optional<rt::TimePoint> next_deadline() const {
    std::optional<rt::TimePoint> earliest;
    for (const auto& [key, p] : pending_)
      if (!earliest || p.next_due < *earliest) earliest = p.next_due;
    return earliest;
  }

  std::size_t pending() const { return pending_.size(); }
  bool is_pending(const Key& key) const { return pending_.contains(key); }
  const AckCounters& counters() const { return counters_; }

 private:
  struct Pending {
    Header header;
    std::vector<std::uint8_t> payload;
    AckPolicy policy;
    std::uint32_t transmissions = 1;
    rt::TimePoint next_due{};
  };
  using PendingMap = std::map<Key, Pending>;

  typename PendingMap::iterator find_answered(const Key& answered) {
    if (const auto it = pending_.find(answered); it != pending_.end()) return it;
    return std::find_if(pending_.begin(), pending_.end(),
                        [&](const auto& entry) { return Dialect::settled_by(entry.first, answered); });
  }

  Options options_;
  PendingMap pending_;
  AckCounters counters_;
};

// RA 3.x's, the node's (compiled once, in jaus_runtime).
extern template class BasicAckTracker<RaAcks>;
using AckTracker = BasicAckTracker<RaAcks>;
using AckResolution = AckTracker::Resolution;
using AckPoll = AckTracker::Poll;
using Retransmission = BasicRetransmission<Header>;

}  // namespace jaus::node
