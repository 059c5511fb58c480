// Queries over a lossy link: a query is idempotent, so instead of waiting its
// whole timeout for one reply that may never come (the query or its report
// lost), it is sent again every `resend_every` until a reply arrives or the
// timeout is up. One datagram lost costs a resend period, not the command.
// (SessionCore::await_reply_resending, for a message known at compile time
// or only at run time.) Errors as await_reply: timeout ("no reply from
// 1.1.33.1 within 1 s") or interrupted.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "jaus/ocu/session.hpp"

namespace jaus::ocu {

// A query from the OCU component to `to`, resent until answered.
template <class M>
jaus::Expected<Received> request_resending(OcuSession& session, const jaus::Address& to, const M& query,
                                           std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout,
                                           jaus::rt::Duration resend_every = kQueryResendPeriod) {
  return session.await_reply_resending(to, std::move(reply_codes), timeout, [&] { session.send(to, query); },
                                       resend_every);
}

// The same for a query known only at run time (header: code, priority, ...;
// its destination is `to`).
jaus::Expected<Received> request_raw_resending(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                               std::span<const std::uint8_t> payload,
                                               std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout,
                                               jaus::rt::Duration resend_every = kQueryResendPeriod);

}  // namespace jaus::ocu
