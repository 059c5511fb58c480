#include "jaus/ocu/must_arrive.hpp"

#include <algorithm>
#include <memory>
#include <optional>

#include "jaus/core/stop_commands.hpp"
#include "repeat_broadcast.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;

// The node resolves every message it tracks (exhausted at the latest
// retransmit_after after the last transmission): this is only a backstop.
constexpr jaus::rt::Duration kResolutionMargin = 1s;

struct Pending {
  std::optional<jaus::node::AckResolution> resolution;
  jaus::rt::TimePoint resolved_at{};
};

Arrival arrival_of(jaus::node::AckOutcome outcome) {
  switch (outcome) {
    case jaus::node::AckOutcome::acknowledged: return Arrival::acknowledged;
    case jaus::node::AckOutcome::refused: return Arrival::refused;
    case jaus::node::AckOutcome::exhausted: break;
  }
  return Arrival::unacknowledged;
}

MustArrivePolicy sane(MustArrivePolicy policy) {
  policy.retransmit_after = std::max<jaus::rt::Duration>(policy.retransmit_after, 1ms);
  policy.max_transmissions = std::max<std::uint32_t>(policy.max_transmissions, 1);
  return policy;
}

// Runs the session until `done` or `limit`; through a stop request too when `through_stop`.
bool run(OcuSession& session, const std::function<bool()>& done, jaus::rt::Duration limit, bool through_stop) {
  return through_stop ? session.run_cleanup_until(done, limit) : session.run_until(done, limit);
}

ArrivalResult send(OcuSession& session, const jaus::Address& to, jaus::Header header,
                   std::span<const std::uint8_t> payload, MustArrivePolicy policy, bool through_stop) {
  policy = sane(policy);
  header.destination = to;
  header.source = session.self();
  if (payload.size() > jaus::kMaxPayloadSize) return ArrivalResult{};
  header.data_size = static_cast<std::uint16_t>(payload.size());
  if (to.is_broadcast()) {
    header.ack_nak = jaus::AckNak::none;
    return detail::repeat_broadcast(session, policy, through_stop, [&] { session.send_raw(header, payload); });
  }
  // The node may call back after we return (interrupted): the state is shared.
  auto pending = std::make_shared<Pending>();
  auto& clock = session.clock();
  const auto start = clock.now();
  const auto key = session.node().send_acknowledged(header, payload, policy,
                                                    [pending, &clock](const jaus::node::AckResolution& resolution) {
                                                      pending->resolution = resolution;
                                                      pending->resolved_at = clock.now();
                                                    });
  run(session, [&] { return pending->resolution.has_value(); }, policy.longest_wait() + kResolutionMargin,
      through_stop);
  ArrivalResult result;
  if (!pending->resolution) {
    // Stopped waiting (interrupted): nothing more of it goes out, in either dialect.
    result.outcome = session.interrupted() && !through_stop ? Arrival::interrupted : Arrival::unacknowledged;
    result.elapsed = clock.now() - start;
    result.transmissions = session.node().forget_acknowledged(key).value_or(1);
    return result;
  }
  result.outcome = arrival_of(pending->resolution->outcome);
  result.transmissions = pending->resolution->transmissions;
  result.elapsed = pending->resolved_at - start;
  return result;
}

}  // namespace

MustArrivePolicy MustArrivePolicy::command(const MustArriveSettings& settings) {
  MustArrivePolicy policy;
  policy.give_up_after = settings.give_up_after;
  policy.max_retransmit_after = settings.resend_at_most;
  // The deadline decides, not the count: enough copies for a give-up at the
  // round trip's least timeout doubling up to resend_at_most.
  policy.max_transmissions =
      std::max<std::uint32_t>(policy.max_transmissions,
                              static_cast<std::uint32_t>(settings.give_up_after / settings.resend_at_most) + 7);
  return policy;
}

MustArrivePolicy MustArrivePolicy::stop(const MustArriveSettings& settings) {
  MustArrivePolicy policy = emergency();
  policy.give_up_after = settings.stop_give_up_after;
  policy.max_retransmit_after = settings.stop_resend_at_most;
  policy.unmeasured_wait = std::min(policy.unmeasured_wait, settings.stop_resend_at_most);
  // Never doubled: one copy every stop_resend_at_most at the least, or at
  // the round trip's least timeout when that is shorter.
  const auto fastest = std::max<jaus::rt::Duration>(
      std::min(settings.stop_resend_at_most, settings.round_trip.min_timeout), 1ms);
  policy.max_transmissions = std::max<std::uint32_t>(
      policy.max_transmissions, static_cast<std::uint32_t>(std::min<std::int64_t>(
                                    settings.stop_give_up_after / fastest, 100'000)));
  return policy;
}

MustArrivePolicy MustArrivePolicy::for_code(std::uint16_t command_code, const MustArriveSettings& settings) {
  return jaus::is_stop_command(command_code) ? stop(settings) : command(settings);
}

jaus::rt::Duration MustArrivePolicy::longest_wait() const {
  // Fixed: given up one period after the last transmission.
  if (timing == jaus::node::RetransmitTiming::fixed) return retransmit_after * max_transmissions;
  // Measured: by the deadline, or one longest wait after each transmission
  // (none given: the node's longest, RoundTripOptions::max_timeout).
  const auto longest = max_retransmit_after > jaus::rt::Duration::zero() ? max_retransmit_after
                                                                          : jaus::node::RoundTripOptions{}.max_timeout;
  const auto by_count = longest * max_transmissions;
  return give_up_after > jaus::rt::Duration::zero() ? std::min(give_up_after, by_count) : by_count;
}

std::string_view to_string(Arrival arrival) {
  switch (arrival) {
    case Arrival::acknowledged: return "acknowledged";
    case Arrival::refused: return "refused";
    case Arrival::unacknowledged: return "unacknowledged";
    case Arrival::interrupted: return "interrupted";
  }
  return "unknown";
}

ArrivalResult send_must_arrive(OcuSession& session, const jaus::Address& to, jaus::Header header,
                               std::span<const std::uint8_t> payload, std::optional<MustArrivePolicy> policy) {
  const MustArrivePolicy chosen =
      policy ? *policy : MustArrivePolicy::for_code(header.command_code, session.options().must_arrive);
  return send(session, to, header, payload, chosen, false);
}

ArrivalResult send_must_arrive_through_stop(OcuSession& session, const jaus::Address& to, jaus::Header header,
                                            std::span<const std::uint8_t> payload, MustArrivePolicy policy) {
  return send(session, to, header, payload, policy, true);
}

}  // namespace jaus::ocu
