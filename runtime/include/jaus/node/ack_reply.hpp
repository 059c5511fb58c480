// Answering a received message whose header requests an ACK (ack_nak = 1):
// the reply echoes its command code and sequence number with an empty
// payload, from the component that handled it back to the sender; ack_nak is
// 3 (ACK) when the message was delivered, 2 (NAK) when it could not be (no
// such component, queue full, undecodable, ...).
#pragma once

#include <optional>

#include "jaus/core/address.hpp"
#include "jaus/core/header.hpp"

namespace jaus::node {

enum class Delivery : bool { undeliverable, delivered };

// The ACK or NAK header for `received`, or nothing when it did not request
// one. `responder` is our component that answers (the received destination
// may be a broadcast address). The reply keeps the received priority, so a
// safety-critical command is acknowledged as urgently as it was sent.
std::optional<Header> ack_reply_for(const Header& received, const Address& responder, Delivery delivery);

}  // namespace jaus::node
