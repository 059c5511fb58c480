#include "jaus/ocu/repeated_query.hpp"

#include <algorithm>
#include <optional>

namespace jaus::ocu {

jaus::Expected<Received> await_reply_resending(OcuSession& session, const jaus::Address& from,
                                               std::vector<std::uint16_t> codes, jaus::rt::Duration timeout,
                                               const std::function<void()>& send, jaus::rt::Duration resend_every) {
  std::optional<Received> reply;
  const auto id = session.listen([&](const Received& r) {
    if (reply || !from.matches(r.header.source)) return;
    if (!codes.empty() && std::find(codes.begin(), codes.end(), r.header.command_code) == codes.end()) return;
    reply = r;
  });
  const auto period = std::max<jaus::rt::Duration>(resend_every, std::chrono::milliseconds(1));
  const auto deadline = session.clock().now() + timeout;
  send();
  for (;;) {
    const auto now = session.clock().now();
    if (now >= deadline) break;
    if (session.run_until([&] { return reply.has_value(); }, std::min(period, deadline - now))) break;
    if (session.interrupted() || session.clock().now() >= deadline) break;
    send();  // the query or its reply was lost (or is late: a second reply is ignored)
  }
  session.unlisten(id);
  if (reply) return std::move(*reply);
  if (session.interrupted()) return jaus::unexpected(jaus::make_error(jaus::ErrorCode::interrupted, "interrupted"));
  return jaus::unexpected(no_reply_error(from, timeout));
}

jaus::Expected<Received> request_raw_resending(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                               std::span<const std::uint8_t> payload,
                                               std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout,
                                               jaus::rt::Duration resend_every) {
  header.destination = to;
  return await_reply_resending(session, to, std::move(reply_codes), timeout,
                               [&] { session.send_raw(header, payload); }, resend_every);
}

}  // namespace jaus::ocu
