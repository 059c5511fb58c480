// A command that must arrive, sent to a broadcast ID (must_arrive.hpp): no
// one receiver's ACK could confirm it for everyone, so both dialects'
// sessions send it policy.max_transmissions times, policy.retransmit_after
// apart, and report it unacknowledged with that count (interrupted when the
// session is asked to stop between two, unless `through_stop`: clean-up).
#pragma once

#include <cstdint>
#include <utility>

#include "jaus/ocu/must_arrive.hpp"

namespace jaus::ocu::detail {

// `policy` already made sane (a period of 1 ms and one transmission at least).
template <class Session, class SendOnce>
ArrivalResult repeat_broadcast(Session& session, const MustArrivePolicy& policy, bool through_stop,
                               SendOnce&& send_once) {
  ArrivalResult result;
  const auto start = session.clock().now();
  const auto never = [] { return false; };
  for (std::uint32_t i = 0; i < policy.max_transmissions; ++i) {
    if (i > 0) {
      if (through_stop) {
        session.run_cleanup_until(never, policy.retransmit_after);
      } else {
        session.run_until(never, policy.retransmit_after);
      }
      if (!through_stop && session.interrupted()) {
        result.outcome = Arrival::interrupted;
        break;
      }
    }
    send_once();
    ++result.transmissions;
  }
  result.elapsed = session.clock().now() - start;
  return result;
}

}  // namespace jaus::ocu::detail
