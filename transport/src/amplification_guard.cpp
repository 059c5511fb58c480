#include "jaus/transport/amplification_guard.hpp"

#include <algorithm>
#include <chrono>

namespace jaus::transport {

namespace {

constexpr std::uint64_t rotl(std::uint64_t x, int b) { return (x << b) | (x >> (64 - b)); }

// SipHash-2-4 of one 64-bit word: a keyed PRF, so challenge numbers seen at
// one's own endpoints tell nothing of those sent elsewhere (a plain PRNG such
// as mt19937 can be rebuilt from its outputs).
std::uint64_t siphash(const std::array<std::uint64_t, 2>& key, std::uint64_t message) {
  std::uint64_t v0 = key[0] ^ 0x736f6d6570736575ULL, v1 = key[1] ^ 0x646f72616e646f6dULL;
  std::uint64_t v2 = key[0] ^ 0x6c7967656e657261ULL, v3 = key[1] ^ 0x7465646279746573ULL;
  auto round = [&] {
    v0 += v1, v1 = rotl(v1, 13), v1 ^= v0, v0 = rotl(v0, 32);
    v2 += v3, v3 = rotl(v3, 16), v3 ^= v2;
    v0 += v3, v3 = rotl(v3, 21), v3 ^= v0;
    v2 += v1, v1 = rotl(v1, 17), v1 ^= v2, v2 = rotl(v2, 32);
  };
  v3 ^= message;
  round(), round();
  v0 ^= message;
  const std::uint64_t last = std::uint64_t{8} << 56;  // the length byte of an 8-byte message
  v3 ^= last;
  round(), round();
  v0 ^= last;
  v2 ^= 0xFF;
  round(), round(), round(), round();
  return v0 ^ v1 ^ v2 ^ v3;
}

}  // namespace

std::size_t AmplificationGuard::framed_size(Framing framing, std::size_t packet_size) {
  return frame_prefix(framing, packet_size).size + packet_size;
}

std::uint16_t AmplificationGuard::next_sequence() {
  return static_cast<std::uint16_t>(siphash(key_, ++challenges_made_));
}

void AmplificationGuard::track(const Ipv4Endpoint& endpoint) { endpoints_.try_emplace(endpoint); }

void AmplificationGuard::forget(const Ipv4Endpoint& endpoint) {
  const auto it = endpoints_.find(endpoint);
  if (it == endpoints_.end()) return;
  drop_held(it->second);
  endpoints_.erase(it);
}

bool AmplificationGuard::unverified(const Ipv4Endpoint& endpoint) const {
  const auto it = endpoints_.find(endpoint);
  return it != endpoints_.end() && !it->second.verified;
}

void AmplificationGuard::drop_held(State& state) {
  counters_.replies_dropped_unverified += state.held.size();
  held_bytes_ -= state.held_bytes;
  state.held.clear();
  state.held_bytes = 0;
}

AmplificationGuard::State* AmplificationGuard::count_received(const Ipv4Endpoint& from, std::size_t size) {
  const auto it = endpoints_.find(from);
  if (it == endpoints_.end() || it->second.verified) return nullptr;
  State& state = it->second;
  state.credit = std::min<std::uint64_t>(state.credit + size, options_.max_received_credit);
  counters_.bytes_received_unverified += size;
  return &state;
}

void AmplificationGuard::refill(State& state, rt::TimePoint now) {
  const auto refill_bucket = [now](double& tokens, std::optional<rt::TimePoint>& at, std::size_t burst,
                                   std::size_t per_second) {
    if (!at) {
      tokens = static_cast<double>(burst);  // full at first contact
    } else if (now > *at) {
      const double seconds = std::chrono::duration<double>(now - *at).count();
      tokens = std::min(static_cast<double>(burst), tokens + seconds * static_cast<double>(per_second));
    }
    if (!at || now > *at) at = now;
  };
  refill_bucket(state.tokens, state.refilled_at, options_.unverified_burst_bytes, options_.unverified_bytes_per_second);
  refill_bucket(global_tokens_, global_refilled_at_, options_.unverified_total_burst_bytes,
                options_.unverified_total_bytes_per_second);
}

bool AmplificationGuard::spend(State& state, std::size_t size, rt::TimePoint now) {
  refill(state, now);
  // What admit_command set aside was taken from both budgets already.
  const std::size_t from_reserve = std::min(state.reserved, size);
  const std::size_t rest = size - from_reserve;
  const std::size_t from_credit = static_cast<std::size_t>(std::min<std::uint64_t>(state.credit, rest));
  const double from_tokens = static_cast<double>(rest - from_credit);
  if (from_tokens > state.tokens || static_cast<double>(rest) > global_tokens_) return false;
  state.reserved -= from_reserve;
  state.credit -= from_credit;
  state.tokens -= from_tokens;
  global_tokens_ -= static_cast<double>(rest);
  counters_.bytes_sent_unverified += size;
  return true;
}

bool AmplificationGuard::answers(State& state, std::uint16_t sequence) {
  if (!state.challenge) return false;
  if (sequence != *state.challenge) {
    ++counters_.wrong_answers;
    if (++state.wrong_answers >= options_.wrong_answers_per_challenge) {
      // Retired: the next challenge (not before challenge_interval) has a new number.
      state.challenge.reset();
      state.wrong_answers = 0;
    }
    return false;
  }
  state.verified = true;  // its limits are lifted
  state.challenge.reset();
  ++counters_.endpoints_verified;
  return true;
}

bool AmplificationGuard::received(const Ipv4Endpoint& from, std::size_t size, const Address& source,
                                  const Header& header) {
  State* state = count_received(from, size);
  if (state == nullptr) return false;
  state->source = source;
  const bool answer =
      (header.ack_nak == AckNak::ack || header.ack_nak == AckNak::nak) && header.command_code == kChallengeCode;
  return answer && answers(*state, header.sequence);
}

bool AmplificationGuard::received_jss(const Ipv4Endpoint& from, std::size_t size, const jss::JudpHeader& header) {
  State* state = count_received(from, size);
  if (state == nullptr) return false;
  state->jss_source = header.source;
  // An AS5669A ACK is header only: it carries no message ID to compare.
  return header.ack_nak == jss::JudpAckNak::ack && answers(*state, header.sequence);
}

bool AmplificationGuard::received(const Ipv4Endpoint& from, const Inbound& inbound) {
  if (inbound.framing == Framing::as5669a) return received_jss(from, inbound.bytes.size(), inbound.jss.front().header);
  return received(from, inbound.bytes.size(), inbound.ra.header.source, inbound.ra.header);
}

AmplificationGuard::Verdict AmplificationGuard::offer(const Ipv4Endpoint& to, Framing framing,
                                                      std::span<const std::uint8_t> packet, rt::TimePoint now) {
  const auto it = endpoints_.find(to);
  if (it == endpoints_.end() || it->second.verified) return Verdict::send;
  State& state = it->second;
  const std::size_t size = framed_size(framing, packet.size());
  // A later part of a large data set goes behind the held ones, never before
  // them (the parts stay in order); anything else within the budgets goes at
  // once: an ACK is never withheld behind a held Report Image.
  const bool continues_held = !state.held.empty() && framing != Framing::as5669a && packet.size() >= kHeaderSize &&
                              static_cast<unsigned>(packet[13] >> 4) != static_cast<unsigned>(DataFlag::single);
  if (!continues_held && spend(state, size, now)) {
    state.dropping = false;
    return Verdict::send;
  }
  // Beyond the budgets. Held while the endpoint may yet answer a challenge
  // (the link sends one): our own tools do, and get a large reply at once.
  const bool may_hold = !state.unanswered && state.held.size() < options_.max_held_per_endpoint &&
                        state.held_bytes + packet.size() <= options_.max_held_bytes_per_endpoint &&
                        held_bytes_ + packet.size() <= options_.max_held_bytes_total;
  if (may_hold) {
    state.held.push_back(Held{framing, std::vector<std::uint8_t>(packet.begin(), packet.end()), now});
    state.held_bytes += packet.size();
    held_bytes_ += packet.size();
    ++counters_.replies_held;
    return Verdict::held;
  }
  ++counters_.replies_dropped_unverified;
  last_drop_began_streak_ = !state.dropping;
  if (last_drop_began_streak_) ++counters_.drop_streaks;
  state.dropping = true;
  return Verdict::dropped;
}

bool AmplificationGuard::admit_command(const Ipv4Endpoint& from, Framing framing, rt::TimePoint now) {
  (void)framing;  // the reserve fits every framing's prefix
  const bool admitted = reserve_reply(from, now);
  if (const auto it = endpoints_.find(from); it != endpoints_.end()) it->second.refused = !admitted;
  if (!admitted) ++counters_.commands_refused;
  return admitted;
}

bool AmplificationGuard::reserve_reply(const Ipv4Endpoint& from, rt::TimePoint now) {
  const auto it = endpoints_.find(from);
  if (it == endpoints_.end() || it->second.verified) return true;
  State& state = it->second;
  if (state.reserved >= kCommandReplyReserve) return true;  // set aside by an earlier command, still unspent
  const std::size_t missing = kCommandReplyReserve - state.reserved;
  if (!spend(state, missing, now)) return false;
  counters_.bytes_sent_unverified -= missing;  // set aside, not sent: offer() counts it when it goes
  state.reserved += missing;
  return true;
}

std::vector<AmplificationGuard::Held> AmplificationGuard::release(const Ipv4Endpoint& endpoint) {
  const auto it = endpoints_.find(endpoint);
  if (it == endpoints_.end()) return {};
  State& state = it->second;
  std::vector<Held> out(std::make_move_iterator(state.held.begin()), std::make_move_iterator(state.held.end()));
  held_bytes_ -= state.held_bytes;
  state.held.clear();
  state.held_bytes = 0;
  return out;
}

std::optional<std::uint16_t> AmplificationGuard::due_challenge(State& state, std::size_t size, rt::TimePoint now,
                                                              bool at_first_contact) {
  if (state.verified) return std::nullopt;
  // Due while a reply is held or was just dropped, or a command was refused
  // (answering lifts the limits: an OCU that ACKs gets its commands through).
  const bool wanted =
      !state.held.empty() || state.dropping || state.refused || (at_first_contact && !state.challenged_at);
  if (!wanted) return std::nullopt;
  if (state.challenged_at && now - *state.challenged_at < options_.challenge_interval) return std::nullopt;
  if (!spend(state, size, now)) return std::nullopt;  // wait for the budgets to grow
  if (!state.challenge) {
    state.challenge = next_sequence();
    state.wrong_answers = 0;
  }
  state.challenged_at = now;
  ++counters_.challenges_sent;
  return state.challenge;
}

std::optional<Header> AmplificationGuard::challenge(const Ipv4Endpoint& to, Framing framing, std::uint8_t subsystem,
                                                    std::uint8_t node, rt::TimePoint now) {
  const auto it = endpoints_.find(to);
  if (it == endpoints_.end()) return std::nullopt;
  State& state = it->second;
  if (!state.source.is_valid()) return std::nullopt;  // never heard: nowhere to address it
  const auto sequence = due_challenge(state, framed_size(framing, kHeaderSize), now);
  if (!sequence) return std::nullopt;
  Header h;
  h.ack_nak = AckNak::ack_requested;
  h.command_code = kChallengeCode;
  h.destination = state.source;
  h.source = Address{subsystem, node, 1, 1};  // this node's node manager
  h.data_size = 0;
  h.sequence = *sequence;
  return h;
}

std::optional<std::vector<std::uint8_t>> AmplificationGuard::challenge_jss(const Ipv4Endpoint& to,
                                                                           const jss::JssId& self, rt::TimePoint now,
                                                                           bool at_first_contact) {
  const auto it = endpoints_.find(to);
  if (it == endpoints_.end()) return std::nullopt;
  State& state = it->second;
  if (!state.jss_source.is_valid()) return std::nullopt;  // never heard: nowhere to address it
  const auto sequence = due_challenge(state, kJssChallengeSize, now, at_first_contact);
  if (!sequence) return std::nullopt;
  jss::JudpHeader h;
  h.ack_nak = jss::JudpAckNak::ack_requested;
  h.destination = state.jss_source;
  h.source = self;
  h.sequence = *sequence;
  constexpr std::array<std::uint8_t, 2> kQueryHeartbeatPulse = {kChallengeCode & 0xFF, kChallengeCode >> 8};
  return jss::make_judp_datagram(h, kQueryHeartbeatPulse);
}

std::vector<AmplificationGuard::Expired> AmplificationGuard::expire(rt::TimePoint now) {
  std::vector<Expired> expired;
  for (auto& [endpoint, state] : endpoints_) {
    std::size_t replies = 0;
    while (!state.held.empty() && now - state.held.front().since >= options_.hold_time) {
      state.held_bytes -= state.held.front().packet.size();
      held_bytes_ -= state.held.front().packet.size();
      state.held.pop_front();
      ++replies;
    }
    if (replies == 0) continue;
    counters_.replies_dropped_unverified += replies;
    counters_.held_replies_expired += replies;
    // It did not answer within hold_time: a peer that ignores ACK requests.
    // Its replies beyond the budget are dropped at once from now on.
    state.unanswered = true;
    expired.push_back(Expired{endpoint, replies});
  }
  return expired;
}

}  // namespace jaus::transport
