// Commands that must arrive (issue 32): over a lossy radio link a datagram
// sent once may simply be gone, and a Set Emergency that never arrives is a
// vehicle that does not stop. Such a command goes with an ACK request
// (ack_nak = 1) and is sent again until the destination's node ACKs or NAKs
// it. By default the pace is the round trip measured to that node (RFC 6298,
// jaus/node/round_trip.hpp): sent again after its retransmission timeout
// (at least 50 ms: a LAN's loss is repaired at once; a radio's 300 ms round
// trip is waited for instead of sending every command five times), each
// wait twice the last, at most 1 s apart, given up 3 s after the first. A
// stop keeps trying harder: MustArrivePolicy::emergency() sends again at the
// measured pace without doubling, at least every 100 ms, for 10 s. These
// are the defaults of a session's MustArriveSettings (must_arrive_settings.hpp;
// jausctl's and jaus-console's --give-up-after and the like), which a send
// without a policy follows by its message's code. The destination's node
// ACKs after its component has handled the message, so the ACK's time
// bounds when it was acted on. Retransmissions repeat the packet exactly
// (same sequence number): a receiver drops a retransmitted duplicate it
// already handled, except stops (Set Emergency and the like), which are
// always acted on.
//
// A broadcast destination (255 anywhere) asks no ACK: every receiver would
// answer, and the first ACK would say nothing of the others. The message is
// instead sent max_transmissions times, retransmit_after apart, and the
// result is `unacknowledged` with that count: nobody confirmed it.
//
// docs/safety.md, "Loss: what must arrive", lists which commands go this way.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "jaus/node/ack_tracker.hpp"
#include "jaus/ocu/must_arrive_settings.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::ocu {

// The node's ACK policy (jaus/node/ack_tracker.hpp) with an operator
// unit's defaults: measured timing, backing off, at most 10 transmissions,
// given up 3 s after the first, at most 1 s between two. Its
// retransmit_after is the fixed timing's period and, either timing, the pace
// of a broadcast's repeats.
struct MustArrivePolicy : jaus::node::AckPolicy {
  constexpr MustArrivePolicy()
      : AckPolicy{std::chrono::milliseconds(50), 10, jaus::node::RetransmitTiming::measured, std::chrono::seconds(3),
                  std::chrono::seconds(1), true, {}} {}
  constexpr explicit MustArrivePolicy(const AckPolicy& policy) : AckPolicy(policy) {}

  // Every `period`, `times` times, whatever the round trip.
  static constexpr MustArrivePolicy every(jaus::rt::Duration period, std::uint32_t times) {
    return MustArrivePolicy(AckPolicy{period, times});
  }
  // A stop: again after each timeout of the measured round trip (at least
  // 50 ms; every 50 ms before anything is measured: a stop never waits
  // longer than a LAN's pace to learn the link), never doubled and at least
  // every 100 ms, for 10 s: over a radio's 300 ms round trip a lost copy
  // costs 100 ms, not a round trip and its variation (bench_radio_acks at
  // 20 % loss each way: p99 1.24-1.25 s, 4.5 copies of 53 bytes; 1.3-1.5 s
  // at 200 ms, 2.1-2.5 s at 500 ms), and a link back from a drop-out gets it
  // within 100 ms.
  static constexpr MustArrivePolicy emergency() {
    MustArrivePolicy policy;
    policy.max_transmissions = 200;
    policy.give_up_after = std::chrono::seconds(10);
    policy.max_retransmit_after = std::chrono::milliseconds(100);
    policy.back_off = false;
    policy.unmeasured_wait = std::chrono::milliseconds(50);
    return policy;
  }
  // Clean-up on the way out (a Release Component Control after Ctrl-C):
  // bounded at 1 s, so no second Ctrl-C is needed.
  static constexpr MustArrivePolicy cleanup() {
    MustArrivePolicy policy;
    policy.give_up_after = std::chrono::seconds(1);
    return policy;
  }

  // A command's and a stop's policies under `settings` (a session's:
  // SessionOptions::must_arrive); MustArrivePolicy{} and emergency() are
  // these under the default settings.
  static MustArrivePolicy command(const MustArriveSettings& settings);
  static MustArrivePolicy stop(const MustArriveSettings& settings);
  // A stop's for a stop command (jaus::is_stop_command), a command's otherwise.
  static MustArrivePolicy for_code(std::uint16_t command_code, const MustArriveSettings& settings);

  // When the sender has given up at the latest: the longest a send waits.
  jaus::rt::Duration longest_wait() const;
};

enum class Arrival {
  acknowledged,    // the destination's node ACKed it: a component there handled it
  refused,         // NAK: it arrived, but no component there could take it
  unacknowledged,  // no answer to any transmission (or a broadcast, which asks none)
  interrupted,     // the session was asked to stop while waiting (retransmissions go on while it runs)
};

struct ArrivalResult {
  Arrival outcome = Arrival::unacknowledged;
  std::uint32_t transmissions = 0;  // how many times it went out
  jaus::rt::Duration elapsed{};     // first transmission -> ACK/NAK (or giving up)
};

std::string_view to_string(Arrival arrival);

// The raw form: a message known only at run time (jausctl send). The header's
// command code and priority are kept; source, destination (`to`), data size
// and ack_nak are set here. Without a policy, the session's settings say it
// (MustArrivePolicy::for_code: a stop tries harder than a command). More than 4080 bytes of payload cannot be
// acknowledged (one ACK answers one packet): unacknowledged, nothing sent.
ArrivalResult send_must_arrive(OcuSession& session, const jaus::Address& to, jaus::Header header,
                               std::span<const std::uint8_t> payload,
                               std::optional<MustArrivePolicy> policy = std::nullopt);

// The same, but the wait goes on after the session was asked to stop:
// clean-up after Ctrl-C (a Release Component Control), bounded by the policy
// (its longest_wait(): MustArrivePolicy::cleanup()), so no second Ctrl-C is needed.
ArrivalResult send_must_arrive_through_stop(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                            std::span<const std::uint8_t> payload, MustArrivePolicy policy);

// Sends `message` from the session's OCU component with an ACK request and
// again per `policy` (none: the session's, for its code) until the
// destination ACKs or NAKs it; runs the session until then.
template <class M>
ArrivalResult send_must_arrive(OcuSession& session, const jaus::Address& to, const M& message,
                               std::uint8_t priority = jaus::priority::kDefault,
                               std::optional<MustArrivePolicy> policy = std::nullopt) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  if (!size) return ArrivalResult{};  // too large to acknowledge (or not encodable): nothing sent
  jaus::Header header;
  header.priority = priority;
  header.command_code = M::code;
  return send_must_arrive(session, to, header, std::span(payload).first(*size), policy);
}

}  // namespace jaus::ocu
