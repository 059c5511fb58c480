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

enum class AckOutcome : std::uint8_t {
  acknowledged,  // the destination answered ACK
  refused,       // the destination answered NAK
  exhausted,     // no answer after the last transmission
};
std::string_view to_string(AckOutcome outcome);

struct AckResolution {
  AckKey key;
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
struct Retransmission {
  Header header;
  std::vector<std::uint8_t> payload;
  std::uint32_t transmission = 0;  // 2 for the first retransmission, ...
};

struct AckPoll {
  std::vector<Retransmission> retransmit;
  std::vector<AckResolution> failed;  // outcome exhausted
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

class AckTracker {
 public:
  struct Options {
    rt::Duration retransmit_after = std::chrono::seconds(1);  // between transmissions, and after the last
    std::uint32_t max_transmissions = 3;                      // first one included (at least 1)
    std::size_t max_pending = 256;                            // messages awaiting an answer
  };

  AckTracker() : AckTracker(Options{}) {}
  explicit AckTracker(Options options);

  // Records a message just sent at `now` (its payload is copied for
  // retransmission), retransmitted per `policy`, or per the Options when none.
  TrackResult track(const Header& sent, std::span<const std::uint8_t> payload, rt::TimePoint now,
                    std::optional<AckPolicy> policy = {});

  // Settles the pending message a received ACK or NAK answers; nothing for
  // other messages and for answers to nothing pending (counted).
  std::optional<AckResolution> on_reply(const Header& received);

  // What is due at `now`: messages to send again and messages given up.
  AckPoll poll(rt::TimePoint now);
  // When poll() next has something to do.
  std::optional<rt::TimePoint> next_deadline() const;

  std::size_t pending() const { return pending_.size(); }
  bool is_pending(const AckKey& key) const { return pending_.contains(key); }
  const AckCounters& counters() const { return counters_; }

 private:
  struct Pending {
    Header header;
    std::vector<std::uint8_t> payload;
    AckPolicy policy;
    std::uint32_t transmissions = 1;
    rt::TimePoint next_due{};
  };
  using PendingMap = std::map<AckKey, Pending>;
  PendingMap::iterator find_answered(const Header& reply);

  Options options_;
  PendingMap pending_;
  AckCounters counters_;
};

}  // namespace jaus::node
