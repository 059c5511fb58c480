#include "jaus/ocu/repeated_query.hpp"

namespace jaus::ocu {

jaus::Expected<Received> request_raw_resending(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                               std::span<const std::uint8_t> payload,
                                               std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout,
                                               jaus::rt::Duration resend_every) {
  header.destination = to;
  return session.await_reply_resending(to, std::move(reply_codes), timeout,
                                       [&] { session.send_raw(header, payload); }, resend_every);
}

}  // namespace jaus::ocu
