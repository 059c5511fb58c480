// No amplification toward unverified endpoints. Sans-I/O: the UDP link tells
// it what arrives and asks it before it sends; the guard keeps the budgets,
// the held replies and the challenges, the link does the I/O. Time is an
// argument (rt::TimePoint): tests run it under a virtual clock.
//
// A UDP source address can be forged, and a 16-byte query can return tens of
// kilobytes (Report Image): a node answering every source would be an
// amplifier aimed at whoever the forger names. As DNS response-rate limiting
// and QUIC's anti-amplification limit (RFC 9000 section 8) do, an endpoint
// not yet verified is sent at most what it sent plus an allowance (issue 43):
// - per endpoint, the bytes it sent (up to a bound) and a token bucket
//   (`unverified_burst_bytes`, full at first contact, refilled at
//   `unverified_bytes_per_second`): a peer that never answers a challenge
//   (an OpenJAUS OCU, most OCUs written from the spec) polling a few queries
//   a second is answered every time;
// - all unverified endpoints together, a second bucket
//   (`unverified_total_burst_bytes`, `unverified_total_bytes_per_second`):
//   a flood from any number of forged sources reflects at most that rate.
// A reply within both budgets goes at once. One beyond them is dropped and
// counted, the first of a streak reported (offer() says so: the link writes
// one line per streak naming the endpoint) - or, while the endpoint may yet
// answer a challenge, held (a few per endpoint, bounded bytes per endpoint
// and in total, dropped, counted and reported after `hold_time`): our own
// tools answer the challenge, so a Report Image larger than the allowance
// reaches them on the first try. An endpoint whose held reply expired
// unanswered is not held for again (its replies beyond the budget are dropped
// at once) until it answers.
//
// The challenge: a header-only Query Heartbeat Pulse (0x2202) with ACK
// requested, from this node's node manager to the sender's JAUS address, with
// an unpredictable sequence number. A JAUS node answers every ACK-requested
// message with ACK or NAK carrying the same code and sequence number; only a
// sender that really receives at that address can answer, so the answer
// verifies the endpoint, lifts its limits and the held replies go out. One
// challenge outstanding per endpoint, sent again at most once per
// `challenge_interval` while a reply is held or dropped (or a command was
// refused), its bytes counted
// against both budgets. Endpoints not tracked (static peers, the multicast
// group, tools' direct sends) are not limited; verification is forgotten with
// the endpoint.
//
// Commands (issue 43): a command from an unverified endpoint acts only if its
// reply (an ACK, a Confirm Control) can be sent: admit_command() sets that
// reply's bytes aside from both budgets before the link delivers the command,
// or refuses it (counted; a challenge is then due, so an OCU that ACKs gets
// its next command through), and offer() spends what was set aside first.
// The link decides which messages are commands (stops always act, their ACK
// set aside when the budgets allow: reserve_reply).
//
// SAE JAUS (AS5669A) endpoints are verified the same way: the challenge is an
// AS5669A Query Heartbeat Pulse (contents 02 22) with ACK requested, from our
// node manager's JSS ID, and the answer an AS5669A ACK (flag 3, header only)
// with the same sequence number (received_jss, challenge_jss). The link keeps
// one guard per dialect, as it keeps one route table per dialect (so the
// global budget is per dialect too). A JSS endpoint is challenged at its
// first datagram, not only once a reply is held or dropped: a JSS client
// keeps control by re-requesting it only every half timeout (1.5 s), so a
// verified client gets every reply at once.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/core/address.hpp"
#include "jaus/core/header.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/inbound.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::transport {

inline constexpr std::uint16_t kChallengeCode = 0x2202;  // Query Heartbeat Pulse: harmless, header only
// The AS5669A challenge: version, header, contents (the message ID 0x2202), sequence number.
inline constexpr std::size_t kJssChallengeSize = 1 + jss::kTransportHeaderSize + 2 + jss::kSequenceSize;

struct AmplificationGuardOptions {
  std::size_t max_held_per_endpoint = 16;  // datagrams (a large data set is several)
  std::size_t max_held_bytes_per_endpoint = 64 * 1024;
  std::size_t max_held_bytes_total = 512 * 1024;
  rt::Duration hold_time = std::chrono::seconds(2);
  rt::Duration challenge_interval = std::chrono::seconds(1);
  // Wrong answers (ACK/NAK of the challenge's code, another sequence number)
  // after which a challenge is retired and the next gets a new number: a
  // blind forger has a few guesses per challenge, not 65,536 per second.
  std::size_t wrong_answers_per_challenge = 3;
  // The allowance beyond what an unverified endpoint sent (issue 43): per
  // endpoint a token bucket of `unverified_burst_bytes`, full at first
  // contact, refilled at `unverified_bytes_per_second`; all unverified
  // endpoints together at most `unverified_total_bytes_per_second` after a
  // burst of `unverified_total_burst_bytes` (every byte to them: replies,
  // challenges, and the part the endpoint's own bytes cover).
  std::size_t unverified_burst_bytes = 4096;
  std::size_t unverified_bytes_per_second = 1024;
  std::size_t unverified_total_burst_bytes = 32 * 1024;
  std::size_t unverified_total_bytes_per_second = 16 * 1024;
  // The received bytes an endpoint may bank for later replies.
  std::size_t max_received_credit = 64 * 1024;
};

// Set aside from the budgets for a command's replies before it acts: a
// Confirm Control (header and one byte) and the ACK a node sends after the
// handler ran (header only), each with the largest framing prefix, fit.
inline constexpr std::size_t kCommandReplyReserve = 2 * (kHeaderSize + 8 + kMaxPrefixSize);

struct AmplificationCounters {
  std::uint64_t bytes_received_unverified = 0;   // datagram bytes from unverified endpoints
  std::uint64_t bytes_sent_unverified = 0;       // datagram bytes to them (replies and challenges)
  std::uint64_t replies_held = 0;                // datagrams held for want of budget
  std::uint64_t replies_dropped_unverified = 0;  // beyond the budget, or held and dropped (expired, bounds, forgotten)
  std::uint64_t held_replies_expired = 0;        // held ones dropped after hold_time (the challenge went unanswered)
  std::uint64_t drop_streaks = 0;                // runs of replies to one endpoint dropped (one line each)
  std::uint64_t commands_refused = 0;            // commands not delivered: their reply could not have been sent
  std::uint64_t challenges_sent = 0;
  std::uint64_t endpoints_verified = 0;
  std::uint64_t wrong_answers = 0;               // ACK/NAK of the challenge code with another sequence number
};

class AmplificationGuard {
 public:
  // `key` makes the challenge sequence numbers unpredictable (SipHash-2-4 of
  // a counter): random per link, injected by tests.
  AmplificationGuard(AmplificationGuardOptions options, std::array<std::uint64_t, 2> key)
      : options_(options), key_(key) {}

  // A learnt endpoint, unverified until it answers a challenge.
  void track(const Ipv4Endpoint& endpoint);
  // The endpoint was forgotten by the route table: so is its state.
  void forget(const Ipv4Endpoint& endpoint);
  bool tracks(const Ipv4Endpoint& endpoint) const { return endpoints_.contains(endpoint); }
  bool unverified(const Ipv4Endpoint& endpoint) const;

  // A datagram of `size` bytes from an unverified endpoint whose JAUS source
  // is `source`: its budget grows. Returns true if `header` answers the
  // endpoint's challenge: the endpoint is now verified, the datagram is the
  // link's (not delivered), and release() gives what was held.
  bool received(const Ipv4Endpoint& from, std::size_t size, const Address& source, const Header& header);
  // The same for an AS5669A datagram whose (first) transport message has
  // `header`: an ACK (flag 3) with the challenge's sequence number answers.
  bool received_jss(const Ipv4Endpoint& from, std::size_t size, const jss::JudpHeader& header);
  // Either of the above, as the datagram's framing says (the link's one receive path).
  bool received(const Ipv4Endpoint& from, const Inbound& inbound);

  enum class Verdict : std::uint8_t { send, held, dropped };
  // Before sending `packet` (header and payload) framed in `framing` to
  // `to`: send (counted against the budgets), held (copied) or dropped.
  // A reply within the budgets goes at once, even while others are held,
  // unless it continues a large data set (kept in order behind them).
  Verdict offer(const Ipv4Endpoint& to, Framing framing, std::span<const std::uint8_t> packet, rt::TimePoint now);
  // Whether the last offer() that dropped began a streak of drops to its
  // endpoint (the link writes one line per streak; a reply sent ends it).
  bool last_drop_began_streak() const { return last_drop_began_streak_; }

  // Before the link delivers a command (not a stop) from `from`: whether its
  // reply can be sent. True for an endpoint not tracked or verified; for an
  // unverified one, kCommandReplyReserve bytes are set aside from both
  // budgets (offer() spends them first), or the command is refused (false,
  // counted): never a command acted on whose ACK or Confirm is withheld.
  bool admit_command(const Ipv4Endpoint& from, Framing framing, rt::TimePoint now);
  // The same for a stop, which acts whatever the answer: its ACK's bytes
  // are set aside if the budgets have them, nothing is counted if not.
  bool reserve_reply(const Ipv4Endpoint& from, rt::TimePoint now);

  struct Held {
    Framing framing;
    std::vector<std::uint8_t> packet;
    rt::TimePoint since;
  };
  // What was held for an endpoint just verified, in order (then forgotten).
  std::vector<Held> release(const Ipv4Endpoint& endpoint);

  // The challenge to send to `to` now, if one is due (something held, none
  // sent within challenge_interval, and it fits the budget): the header is
  // counted as sent. `self` is this node's ID (the challenge is from S.N.1.1).
  std::optional<Header> challenge(const Ipv4Endpoint& to, Framing framing, std::uint8_t subsystem, std::uint8_t node,
                                  rt::TimePoint now);
  // The AS5669A challenge to `to`, if one is due: a complete datagram from
  // `self` (our node manager's JSS ID) to the JSS ID last heard from `to`.
  // `at_first_contact`: due also when nothing is held, if this endpoint was
  // never challenged (within the budget, as every challenge).
  std::optional<std::vector<std::uint8_t>> challenge_jss(const Ipv4Endpoint& to, const jss::JssId& self,
                                                         rt::TimePoint now, bool at_first_contact = false);

  // Drops what was held longer than hold_time; the endpoints that lost a
  // held reply, and how many (the link writes a line for each). Such an
  // endpoint is held for no more until it answers a challenge.
  struct Expired {
    Ipv4Endpoint endpoint;
    std::size_t replies;
  };
  std::vector<Expired> expire(rt::TimePoint now);

  const AmplificationCounters& counters() const { return counters_; }
  std::size_t held_bytes() const { return held_bytes_; }

 private:
  struct State {
    bool verified = false;
    std::uint64_t credit = 0;  // bytes received while unverified, not yet spent on replies
    double tokens = 0;         // the allowance beyond them (bytes)
    std::optional<rt::TimePoint> refilled_at;  // unset: never offered anything (the bucket starts full)
    std::size_t reserved = 0;  // set aside for a command's reply (admit_command)
    bool dropping = false;     // the last reply offered was dropped
    bool unanswered = false;   // a held reply expired: no more holding until verified
    bool refused = false;      // a command of its was refused: a challenge is due (answering lifts the limits)
    Address source;  // the JAUS address last heard from it: where challenges go
    jss::JssId jss_source;  // the same for an AS5669A endpoint
    std::deque<Held> held;
    std::size_t held_bytes = 0;
    std::optional<std::uint16_t> challenge;  // the outstanding challenge's sequence number
    std::optional<rt::TimePoint> challenged_at;
    std::size_t wrong_answers = 0;
  };
  static std::size_t framed_size(Framing framing, std::size_t packet_size);
  // Counts `size` received bytes; the state of an unverified tracked endpoint, else nullptr.
  State* count_received(const Ipv4Endpoint& from, std::size_t size);
  // Whether an answer (ACK or NAK of a challenge) with `sequence` verifies the endpoint.
  bool answers(State& state, std::uint16_t sequence);
  // The sequence number of a challenge of `size` bytes due now, counted as sent.
  std::optional<std::uint16_t> due_challenge(State& state, std::size_t size, rt::TimePoint now,
                                             bool at_first_contact = false);
  void drop_held(State& state);
  std::uint16_t next_sequence();
  // Refills the endpoint's bucket and the global one up to `now`.
  void refill(State& state, rt::TimePoint now);
  // Spends `size` bytes to an unverified endpoint if both budgets have them
  // (what admit_command set aside first, then its credit and bucket, and the
  // global bucket); false, and nothing spent, if not.
  bool spend(State& state, std::size_t size, rt::TimePoint now);

  AmplificationGuardOptions options_;
  std::array<std::uint64_t, 2> key_;
  std::uint64_t challenges_made_ = 0;
  std::map<Ipv4Endpoint, State> endpoints_;  // at most the route table's learnt endpoints
  std::size_t held_bytes_ = 0;
  double global_tokens_ = 0;
  std::optional<rt::TimePoint> global_refilled_at_;  // unset: the global bucket starts full
  bool last_drop_began_streak_ = false;
  AmplificationCounters counters_;
};

}  // namespace jaus::transport
