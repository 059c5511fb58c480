// Sender side of ACK/NAK: remembers the messages we sent with an ACK request
// (ack_nak = 1), says when to send them again, and settles each one when the
// destination answers with a matching ACK (3) or NAK (2), or when every
// transmission went unanswered.
//
// Defaults: 3 transmissions 1 s apart, failure 1 s after the last one, so a
// silent peer is given up after 3 s, the time after which peers treat a
// component as gone (docs/wire-format.md, "Liveness and discovery"). A
// message may carry its own AckPolicy instead (commands that must arrive over
// a lossy link; issues 32 and 45): at a fixed pace, or timed by the round
// trip measured to the peer (RetransmitTiming::measured, round_trip.hpp: a
// radio's 300 ms is waited for, a LAN's loss repaired in 50 ms), backing off,
// with a deadline. Retransmissions repeat the packet exactly (same sequence
// number, which the ACK echoes, and same data flag: a flag of 4 would hide
// which part of a large data set the packet is).
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

#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"
#include "jaus/node/round_trip.hpp"

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
  using Peer = Address;
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
  // Whose round trip an answer measures: the node the message went to (its
  // components share the path and their node answers); none for a broadcast.
  static std::optional<Peer> peer_of(const Key& sent) {
    if (sent.peer.is_broadcast()) return std::nullopt;
    return Address{sent.peer.subsystem, sent.peer.node, 0, 0};
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

enum class RetransmitTiming : std::uint8_t {
  fixed,     // every retransmit_after
  measured,  // after the peer's retransmission timeout (round_trip.hpp)
};

// How one message is retransmitted until answered, at most
// `max_transmissions` times (the first one included, at least 1):
// - fixed: every `retransmit_after`, given up `retransmit_after` after the
//   last transmission;
// - measured: first after the retransmission timeout of the round trip
//   measured to the peer, then after twice the previous wait (with
//   `back_off`; else the same wait each time), never longer than
//   `max_retransmit_after` apart; given up `give_up_after` after the first
//   transmission (zero: one wait after the last transmission). Without
//   `back_off` the wait is what the measurements alone say, not the timeout
//   earlier expired waits doubled: a stop keeps its pace. To a peer whose
//   round trip is not measured yet, the first wait is `unmeasured_wait`
//   (zero: RoundTripOptions::initial_timeout), twice the longest wait that
//   expired when longer (so that one message comes to be answered having
//   gone out once, and measures).
struct AckPolicy {
  rt::Duration retransmit_after = std::chrono::seconds(1);
  std::uint32_t max_transmissions = 3;  // first one included
  RetransmitTiming timing = RetransmitTiming::fixed;
  rt::Duration give_up_after{};
  rt::Duration max_retransmit_after = std::chrono::seconds(2);
  bool back_off = true;
  rt::Duration unmeasured_wait{};

  static constexpr AckPolicy measured(rt::Duration give_up, std::uint32_t most_transmissions,
                                      rt::Duration longest_wait, bool doubling = true,
                                      rt::Duration first_unmeasured_wait = {}) {
    return AckPolicy{{}, most_transmissions, RetransmitTiming::measured, give_up, longest_wait, doubling,
                     first_unmeasured_wait};
  }
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
    RoundTripOptions round_trip{};                            // the measured timing's bounds
    std::size_t max_peers = 256;                              // round trips remembered
  };

  BasicAckTracker() : BasicAckTracker(Options{}) {}
  explicit BasicAckTracker(Options options)
      : options_(options), round_trips_(options.round_trip, options.max_peers) {
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
    Pending p{sent, {payload.begin(), payload.end()}, chosen, Dialect::peer_of(key), now};
    if (chosen.timing == RetransmitTiming::measured) {
      p.wait = std::min(first_wait(chosen, p.peer ? round_trips_.find(*p.peer) : nullptr), longest_wait(chosen));
      if (chosen.give_up_after > rt::Duration::zero()) p.give_up_at = now + chosen.give_up_after;
    } else {
      p.wait = chosen.retransmit_after;
    }
    p.next_due = std::min(now + p.wait, p.give_up_at);
    pending_.emplace(key, std::move(p));
    ++counters_.tracked;
    return TrackResult::tracked;
  }

  // Settles the pending message a received ACK or NAK answers (at `now`: an
  // answer to a message sent once measures the round trip to its peer);
  // nothing for other messages and for answers to nothing pending (counted).
  std::optional<Resolution> on_reply(const Header& received, rt::TimePoint now) {
    const auto answer = Dialect::answer_of(received);
    if (!answer) return std::nullopt;
    const auto it = find_answered(Dialect::key_of_answer(received));
    if (it == pending_.end()) {
      ++counters_.unmatched_replies;
      return std::nullopt;
    }
    // Karn's rule: the answer to a message sent again could be any copy's.
    if (it->second.transmissions == 1 && it->second.peer)
      round_trips_.sample(*it->second.peer, now - it->second.first_sent, now);
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
      if (p.transmissions >= p.policy.max_transmissions || now >= p.give_up_at) {
        due.failed.push_back({it->first, AckOutcome::exhausted, p.transmissions});
        ++counters_.exhausted;
        it = pending_.erase(it);
        continue;
      }
      ++p.transmissions;
      if (p.policy.timing == RetransmitTiming::measured) {
        // The peer's timeout expired: it is at least doubled until the next measurement.
        if (p.peer) round_trips_.back_off(*p.peer, p.wait, now);
        if (p.policy.back_off) p.wait = std::min(2 * p.wait, longest_wait(p.policy));
      }
      // From `now`, not from the missed due time: a late poll must not cause a burst.
      p.next_due = std::min(now + p.wait, p.give_up_at);
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
  // How many times a pending message went out so far; none when not pending.
  std::optional<std::uint32_t> transmissions(const Key& key) const {
    const auto it = pending_.find(key);
    return it == pending_.end() ? std::nullopt : std::optional(it->second.transmissions);
  }
  const AckCounters& counters() const { return counters_; }
  // The round trip measured to a peer (Dialect::peer_of); nullptr: none yet.
  const RoundTripEstimator* round_trip(const typename Dialect::Peer& peer) const { return round_trips_.find(peer); }

 private:
  struct Pending {
    Header header;
    std::vector<std::uint8_t> payload;
    AckPolicy policy;
    std::optional<typename Dialect::Peer> peer;  // whose round trip its answer measures
    rt::TimePoint first_sent{};
    std::uint32_t transmissions = 1;
    rt::Duration wait{};  // from the last transmission to the next
    rt::TimePoint next_due{};
    rt::TimePoint give_up_at = rt::TimePoint::max();
  };
  using PendingMap = std::map<Key, Pending>;

  // The first wait of a message under measured timing to a peer of whom
  // `known` is known (nullptr: nothing, or a broadcast).
  rt::Duration first_wait(const AckPolicy& policy, const RoundTripEstimator* known) const {
    if (known != nullptr && known->samples() > 0) return policy.back_off ? known->timeout() : known->measured_timeout();
    // Not measured yet: the policy's own first wait, or the initial timeout,
    // and past each wait that expired twice as long even without back_off:
    // Karn's rule measures nothing from a message sent again, so only a
    // wait longer than the round trip can measure it.
    if (policy.unmeasured_wait > rt::Duration::zero())
      return std::max(policy.unmeasured_wait, known != nullptr ? 2 * known->expired() : rt::Duration::zero());
    return known != nullptr ? known->timeout() : round_trips_.options().initial_timeout;
  }

  rt::Duration longest_wait(const AckPolicy& policy) const {
    return policy.max_retransmit_after > rt::Duration::zero() ? policy.max_retransmit_after
                                                              : round_trips_.options().max_timeout;
  }

  typename PendingMap::iterator find_answered(const Key& answered) {
    if (const auto it = pending_.find(answered); it != pending_.end()) return it;
    return std::find_if(pending_.begin(), pending_.end(),
                        [&](const auto& entry) { return Dialect::settled_by(entry.first, answered); });
  }

  Options options_;
  RoundTrips<typename Dialect::Peer> round_trips_;
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
