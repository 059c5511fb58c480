#include "jaus/transport/amplification_guard.hpp"

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

// A header-only ACK or NAK, in either dialect.
bool is_acknowledgement(Framing framing, std::span<const std::uint8_t> packet) {
  if (framing == Framing::as5669a) {
    const auto packets = jss::decode_judp_datagram(packet);
    if (!packets || packets->size() != 1) return false;
    const jss::JudpPacket& only = packets->front();
    return (only.header.ack_nak == jss::JudpAckNak::ack || only.header.ack_nak == jss::JudpAckNak::nak) &&
           only.contents.empty();
  }
  const auto header = decode_header(packet);
  return header && (header->ack_nak == AckNak::ack || header->ack_nak == AckNak::nak) &&
         packet.size() == kHeaderSize;
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
  it->second.received += size;
  counters_.bytes_received_unverified += size;
  return &it->second;
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
  state.verified = true;
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

AmplificationGuard::Verdict AmplificationGuard::offer(const Ipv4Endpoint& to, Framing framing,
                                                      std::span<const std::uint8_t> packet, rt::TimePoint now) {
  const auto it = endpoints_.find(to);
  if (it == endpoints_.end() || it->second.verified) return Verdict::send;
  State& state = it->second;
  const std::size_t size = framed_size(framing, packet.size());
  // An ACK or NAK answers one datagram received from this endpoint and is
  // never larger than it: it amplifies nothing, so it is never held or
  // dropped (nor queued behind held reports). Held, the sender of a command
  // this node delivered would retransmit it blind and give up although it
  // acted (a Standby through a lossy line, tests/network).
  if (is_acknowledgement(framing, packet)) {
    state.sent += size;
    counters_.bytes_sent_unverified += size;
    return Verdict::send;
  }
  // Behind what is already held, never before it: a large data set stays in order.
  if (state.held.empty() && state.sent + size <= state.received) {
    state.sent += size;
    counters_.bytes_sent_unverified += size;
    return Verdict::send;
  }
  if (state.held.size() >= options_.max_held_per_endpoint ||
      state.held_bytes + packet.size() > options_.max_held_bytes_per_endpoint ||
      held_bytes_ + packet.size() > options_.max_held_bytes_total) {
    ++counters_.replies_dropped_unverified;
    return Verdict::dropped;
  }
  state.held.push_back(Held{framing, std::vector<std::uint8_t>(packet.begin(), packet.end()), now});
  state.held_bytes += packet.size();
  held_bytes_ += packet.size();
  ++counters_.replies_held;
  return Verdict::held;
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
  if (state.held.empty() && !(at_first_contact && !state.challenged_at)) return std::nullopt;
  if (state.challenged_at && now - *state.challenged_at < options_.challenge_interval) return std::nullopt;
  if (state.sent + size > state.received) return std::nullopt;  // wait for the sender's next datagram
  if (!state.challenge) {
    state.challenge = next_sequence();
    state.wrong_answers = 0;
  }
  state.challenged_at = now;
  state.sent += size;
  counters_.bytes_sent_unverified += size;
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

void AmplificationGuard::expire(rt::TimePoint now) {
  for (auto& [endpoint, state] : endpoints_) {
    while (!state.held.empty() && now - state.held.front().since >= options_.hold_time) {
      state.held_bytes -= state.held.front().packet.size();
      held_bytes_ -= state.held.front().packet.size();
      state.held.pop_front();
      ++counters_.replies_dropped_unverified;
    }
  }
}

}  // namespace jaus::transport
