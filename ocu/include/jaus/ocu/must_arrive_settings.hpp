// How hard an operator unit tries to get a command through that must arrive
// (issue 45, step 1): what a session (SessionOptions::must_arrive,
// JssSessionOptions::must_arrive) and jausctl's and jaus-console's command
// lines set. The pace of the copies follows the round trip measured to each
// node (RFC 6298, jaus/node/round_trip.hpp) within `round_trip`'s bounds;
// these settings say how long each kind of message keeps trying. The
// defaults suit a LAN and a field radio (300 ms +- 100 ms) alike; a link of
// longer round trips (a satellite's, a mesh radio under load) wants longer
// give-ups and a higher upper bound.
#pragma once

#include <chrono>

#include "jaus/base/expected.hpp"
#include "jaus/node/round_trip.hpp"

namespace jaus::ocu {

struct MustArriveSettings {
  // A command (Clear Emergency, Release Component Control, `jausctl send`
  // with an ACK request, ...): sent again after each retransmission timeout,
  // doubling, at most `resend_at_most` apart, and given up this long after
  // its first send.
  rt::Duration give_up_after = std::chrono::seconds(3);
  rt::Duration resend_at_most = std::chrono::seconds(1);
  // A stop (Set Emergency, Standby, Shutdown: jaus/core/stop_commands.hpp)
  // tries harder: never doubled, at least every `stop_resend_at_most`, and
  // given up only after `stop_give_up_after`.
  rt::Duration stop_give_up_after = std::chrono::seconds(10);
  rt::Duration stop_resend_at_most = std::chrono::milliseconds(100);
  // The retransmission timeout's bounds, and its value before a node's first
  // measurement (the session's node keeps one estimate per node).
  node::RoundTripOptions round_trip{};

  // The ranges (invalid_argument naming the setting as jausctl's and
  // jaus-console's options do: "give-up-after 50 ms is out of range ..."):
  // give-ups 0.1 s..1 h, resend bounds and the timeout's 1 ms..60 s,
  // min <= initial <= max.
  Expected<void> check() const;
};

}  // namespace jaus::ocu
