// Commands that must arrive (issue 32): over a lossy radio link a datagram
// sent once may simply be gone, and a Set Emergency that never arrives is a
// vehicle that does not stop. Such a command goes with an ACK request
// (ack_nak = 1) and is sent again every policy.retransmit_after (50 ms) until
// the destination's node ACKs or NAKs it, at most policy.max_transmissions
// times (10: half a second). The destination's node ACKs after its
// component has handled the message, so the ACK's time bounds when it was
// acted on. Retransmissions repeat the packet exactly (same sequence
// number): a receiver drops a retransmitted duplicate it already handled,
// except stops (Set Emergency and the like), which are always acted on.
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
#include <span>
#include <string_view>
#include <vector>

#include "jaus/ocu/session.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::ocu {

struct MustArrivePolicy {
  jaus::rt::Duration retransmit_after = std::chrono::milliseconds(50);
  std::uint32_t max_transmissions = 10;
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
// and ack_nak are set here. More than 4080 bytes of payload cannot be
// acknowledged (one ACK answers one packet): unacknowledged, nothing sent.
ArrivalResult send_must_arrive(OcuSession& session, const jaus::Address& to, jaus::Header header,
                               std::span<const std::uint8_t> payload, MustArrivePolicy policy = {});

// The same, but the wait goes on after the session was asked to stop:
// clean-up after Ctrl-C (a Release Component Control), bounded by the policy
// (retransmit_after * max_transmissions), so no second Ctrl-C is needed.
ArrivalResult send_must_arrive_through_stop(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                            std::span<const std::uint8_t> payload, MustArrivePolicy policy);

// Sends `message` from the session's OCU component with an ACK request and
// again every policy.retransmit_after until the destination ACKs or NAKs it,
// at most policy.max_transmissions times; runs the session until then.
template <class M>
ArrivalResult send_must_arrive(OcuSession& session, const jaus::Address& to, const M& message,
                               std::uint8_t priority = jaus::priority::kDefault, MustArrivePolicy policy = {}) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  if (!size) return ArrivalResult{};  // too large to acknowledge (or not encodable): nothing sent
  jaus::Header header;
  header.priority = priority;
  header.command_code = M::code;
  return send_must_arrive(session, to, header, std::span(payload).first(*size), policy);
}

}  // namespace jaus::ocu
