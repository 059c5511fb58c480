// AS5669A's headers as the ACK tracker (jaus/node/ack_tracker.hpp, the RA
// node's too) reads them, for the JSS operator session's must-arrive sends:
// an ACK or NAK echoes the sequence number of the packet it answers, from the
// peer it went to. One session has one JSS ID: the peer and the sequence
// number tell its messages apart. Broadcasts ask no ACK (they are repeated
// instead, repeat_broadcast.hpp).
#pragma once

#include <cstdint>
#include <optional>

#include "jaus/jss/judp.hpp"
#include "jaus/node/ack_tracker.hpp"

namespace jaus::ocu::detail {

struct JudpAcks {
  using Header = jss::JudpHeader;
  struct Key {
    jss::JssId peer;
    std::uint16_t sequence = 0;
    auto operator<=>(const Key&) const = default;
  };
  using Peer = jss::JssId;
  // The node a message went to: its components share one round trip.
  static std::optional<Peer> peer_of(const Key& sent) {
    if (sent.peer.is_broadcast()) return std::nullopt;
    return Peer{sent.peer.subsystem, sent.peer.node, 0};
  }
  static bool asks_ack(const Header& h) { return h.ack_nak == jss::JudpAckNak::ack_requested; }
  static std::optional<bool> answer_of(const Header& h) {
    if (h.ack_nak == jss::JudpAckNak::ack) return true;
    if (h.ack_nak == jss::JudpAckNak::nak) return false;
    return std::nullopt;
  }
  static Key key_of_sent(const Header& sent) { return Key{sent.destination, sent.sequence}; }
  static Key key_of_answer(const Header& answer) { return Key{answer.source, answer.sequence}; }
  static bool settled_by(const Key&, const Key&) { return false; }
};
using JudpAckTracker = node::BasicAckTracker<JudpAcks>;

}  // namespace jaus::ocu::detail
