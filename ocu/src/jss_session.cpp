#include "jaus/ocu/jss_session.hpp"

#include <algorithm>
#include <random>

#include "jaus/ocu/names.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"
#include "judp_acks.hpp"
#include "repeat_broadcast.hpp"

namespace jaus::ocu {

namespace {

using namespace std::chrono_literals;

// What the session answers by itself (docs/jss.md, "Liveness", "Discovery").
constexpr std::uint16_t kQueryHeartbeatPulse = 0x2202;
constexpr std::uint16_t kReportHeartbeatPulse = 0x4202;
constexpr std::uint16_t kQueryIdentification = 0x2B00;
constexpr std::uint16_t kReportIdentification = 0x4B00;
constexpr std::uint16_t kNodeType = 40001;
constexpr std::uint16_t kComponentType = 60001;

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

jss::JudpBroadcast broadcast_of(const jss::JssId& to) {
  if (to.subsystem == jss::JssId::kAllSubsystems) return jss::JudpBroadcast::global;
  return to.is_broadcast() ? jss::JudpBroadcast::local : jss::JudpBroadcast::none;
}

// The tracker's round-trip bounds are the session's.
detail::JudpAckTracker::Options jss_ack_options(const MustArriveSettings& settings) {
  detail::JudpAckTracker::Options options;
  options.round_trip = settings.round_trip;
  return options;
}

}  // namespace

struct JssSession::Impl {
  explicit Impl(JssSessionOptions o)
      : options(std::move(o)), assembler(options.reassembly), acks(jss_ack_options(options.must_arrive)) {
    if (!options.log) options.log = rt::silent_log();
  }

  void transmit(const jss::JssId& to, std::span<const std::uint8_t> datagram);
  std::uint16_t send(const jss::JssId& to, std::span<const std::uint8_t> contents, jss::JudpPriority priority,
                     bool ack_requested, std::vector<std::uint8_t>* first_datagram);
  void send_ack(const jss::JudpHeader& received);
  void receive(std::span<const std::uint8_t> datagram);
  void receive_packets(std::span<const jss::JudpPacket> packets);
  void handle(const jss::JudpPacket& packet);
  std::optional<JssReceived> assemble(const jss::JudpPacket& packet);
  void answer_builtin(const JssReceived& message);
  void deliver(const JssReceived& message);
  // On UDP the link drops what does not decode (counted there): counters() adds it.
  void sync_link_counters();
  ArrivalResult must_arrive(JssSession& session, const jss::JssId& to, std::span<const std::uint8_t> contents,
                            jss::JudpPriority priority, MustArrivePolicy policy, bool through_stop);
  MustArrivePolicy policy_for(std::span<const std::uint8_t> contents) const;

  JssSessionOptions options;
  JssSession* owner = nullptr;  // whose listeners hear what arrives
  // On UDP.
  std::unique_ptr<boost::asio::io_context> owned_io;
  boost::asio::io_context* io = nullptr;
  std::unique_ptr<transport::AsioRuntime> runtime;
  // The node's own transport (transport::UdpLink): it decodes each datagram
  // once, learns where each JSS node is and routes by JSS ID, as jausd's does.
  std::unique_ptr<transport::UdpLink> link;
  // Attached.
  JssEnvironment environment;
  rt::Clock* clock = nullptr;
  rt::Scheduler* scheduler = nullptr;
  std::unique_ptr<rt::RepeatedLines> repeated;

  JssSessionCounters counters;
  std::uint64_t decoded_here = 0;    // datagrams this session decoded (attached), and of those
  std::uint64_t malformed_here = 0;  // the ones that did not decode
  std::uint64_t delivered_by_link = 0;
  std::uint16_t next_sequence = 0;
  jss::JssLargeMessageAssembler assembler;
  // Must-arrive sends waiting for their ACK, and those settled (ACK, NAK or
  // given up) until their sender looks.
  detail::JudpAckTracker acks;
  std::map<detail::JudpAcks::Key, detail::JudpAckTracker::Resolution> settled;
};

void JssSession::Impl::transmit(const jss::JssId& to, std::span<const std::uint8_t> datagram) {
  ++counters.datagrams_sent;
  // On UDP: to where `to`'s node was heard; a broadcast, or an ID not heard
  // from yet, to every listed peer and the group.
  if (link) return link->transmit_jss(to, datagram);
  environment.transmit(to, datagram);
}

std::uint16_t JssSession::Impl::send(const jss::JssId& to, std::span<const std::uint8_t> contents,
                                     jss::JudpPriority priority, bool ack_requested,
                                     std::vector<std::uint8_t>* first_datagram) {
  jss::JudpHeader header;
  header.priority = priority;
  header.broadcast = broadcast_of(to);
  header.ack_nak = ack_requested && !to.is_broadcast() ? jss::JudpAckNak::ack_requested : jss::JudpAckNak::none;
  header.destination = to;
  header.source = options.self;
  const std::uint16_t first_sequence = next_sequence;
  header.sequence = first_sequence;
  // Broadcasts are never split: they go whole (the receivers' limit is theirs).
  const std::size_t limit = to.is_broadcast() ? std::max<std::size_t>(contents.size(), 2)
                                              : std::max<std::size_t>(options.max_packet_contents, 3);
  auto datagrams = jss::make_judp_datagrams(header, contents, limit);
  if (!datagrams) {  // contents over 65521 bytes in a packet: nothing sent
    repeated->write(rt::Repeated{"jss session: not sent"}, rt::LogLevel::error, [&] {
      return "JSS: cannot send " + std::to_string(contents.size()) + " bytes to " + to.to_string() + ": " +
             datagrams.error().message();
    });
    return first_sequence;
  }
  next_sequence = static_cast<std::uint16_t>(next_sequence + datagrams->size());
  if (datagrams->size() > 1) ++counters.large_messages_sent;
  for (const auto& datagram : *datagrams) transmit(to, datagram);
  if (first_datagram && !datagrams->empty()) *first_datagram = std::move(datagrams->front());
  return first_sequence;
}

void JssSession::Impl::send_ack(const jss::JudpHeader& received) {
  jss::JudpHeader ack;
  ack.priority = received.priority;
  ack.ack_nak = jss::JudpAckNak::ack;
  ack.destination = received.source;
  ack.source = options.self;
  ack.sequence = received.sequence;
  transmit(ack.destination, jss::make_judp_datagram(ack, {}));
  ++counters.acks_sent;
}

void JssSession::Impl::receive(std::span<const std::uint8_t> datagram) {
  ++decoded_here;
  auto packets = jss::decode_judp_datagram(datagram);
  if (!packets) {
    ++malformed_here;
    sync_link_counters();
    repeated->write(rt::Repeated{"jss session: malformed datagram"}, rt::LogLevel::warn, [&] {
      return "JSS: dropped a datagram of " + std::to_string(datagram.size()) + " bytes: " + packets.error().message();
    });
    return;
  }
  receive_packets(*packets);
}

void JssSession::Impl::receive_packets(std::span<const jss::JudpPacket> packets) {
  if (link) ++delivered_by_link;
  sync_link_counters();
  for (const auto& packet : packets) {
    if (packet.header.source == options.self) continue;  // our own broadcast, looped back by the group
    handle(packet);
  }
}

void JssSession::Impl::sync_link_counters() {
  const std::uint64_t link_malformed =
      link ? link->counters().dropped_for(transport::DropReason::jss_malformed) : 0;
  counters.malformed = malformed_here + link_malformed;
  counters.datagrams_received = decoded_here + delivered_by_link + link_malformed;
}

void JssSession::Impl::handle(const jss::JudpPacket& packet) {
  const jss::JudpHeader& h = packet.header;
  if (!h.destination.matches(options.self)) {
    ++counters.not_for_us;
    return;
  }
  if (h.ack_nak == jss::JudpAckNak::ack || h.ack_nak == jss::JudpAckNak::nak) {
    ++counters.acks_received;
    if (auto resolution = acks.on_reply(h, clock->now())) settled.insert_or_assign(resolution->key, *resolution);
    return;
  }
  std::optional<JssReceived> message;
  if (h.data_flag == jss::JudpDataFlag::single) {
    message = JssReceived{h, {packet.contents.begin(), packet.contents.end()}};
  } else {
    message = assemble(packet);
  }
  if (message) {
    answer_builtin(*message);
    deliver(*message);
  }
  // After it was handled, as JSS nodes do (one ACK per packet that asks).
  if (h.ack_nak == jss::JudpAckNak::ack_requested && !h.destination.is_broadcast()) send_ack(h);
}

// A piece of a large message, in any order: the whole message once its last piece is in.
std::optional<JssReceived> JssSession::Impl::assemble(const jss::JudpPacket& packet) {
  const rt::TimePoint now = clock->now();
  for (const auto& discarded : assembler.expire(now)) {
    ++counters.large_messages_dropped;
    repeated->write(rt::Repeated{"jss session: large message discarded"}, rt::LogLevel::warn, [&] {
      return "JSS: a large message from " + discarded.key.source.to_string() + " discarded: " +
             std::string(to_string(discarded.reason));
    });
  }
  const jss::JudpHeader& h = packet.header;
  auto assembled = assembler.feed(h, packet.contents, now);
  if (assembled.status == AssemblyStatus::dropped) {
    ++counters.large_messages_dropped;
    repeated->write(rt::Repeated{"jss session: large message packet dropped"}, rt::LogLevel::warn, [&] {
      return "JSS: dropped a large message packet from " + h.source.to_string() + " (sequence " +
             std::to_string(h.sequence) + "): " + std::string(to_string(assembled.issue));
    });
  }
  if (assembled.status != AssemblyStatus::complete) return std::nullopt;
  ++counters.large_messages_received;
  return JssReceived{assembled.message->header, std::move(assembled.message->payload)};
}

void JssSession::Impl::answer_builtin(const JssReceived& message) {
  const auto id = message.message_id();
  if (id == kQueryHeartbeatPulse) {
    std::vector<std::uint8_t> report;
    put_u16(report, kReportHeartbeatPulse);
    send(message.source(), report, jss::JudpPriority::normal, false, nullptr);
  } else if (id == kQueryIdentification && message.contents.size() >= 3) {
    const std::uint8_t query_type = message.contents[2];
    if (query_type < 2 || query_type > 4) return;  // system identification is a system commander's
    std::vector<std::uint8_t> report;
    put_u16(report, kReportIdentification);
    report.push_back(query_type);
    put_u16(report, query_type == 2 ? options.identification_type : query_type == 3 ? kNodeType : kComponentType);
    const std::string name = options.name.substr(0, 255);
    report.push_back(static_cast<std::uint8_t>(name.size()));
    report.insert(report.end(), name.begin(), name.end());
    send(message.source(), report, jss::JudpPriority::normal, false, nullptr);
  }
}

void JssSession::Impl::deliver(const JssReceived& message) {
  ++counters.messages_received;
  owner->deliver(message);
}

JssSession::JssSession(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {
  impl_->owner = this;
  run_on(*impl_->clock, *impl_->scheduler, impl_->io, impl_->environment.wait);
}

JssSession::~JssSession() {
  if (impl_->environment.connect) impl_->environment.connect({});
}

namespace {
Expected<void> check_self(const jss::JssId& self) {
  if (!self.is_valid() || self.is_broadcast())
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "the JSS operator unit's ID " + self.to_string() +
                                     " must be a real component (subsystem 1..65534, node and component 1..254)"));
  return {};
}
}  // namespace

Expected<std::unique_ptr<JssSession>> JssSession::open(JssSessionOptions options, boost::asio::io_context* io) {
  if (auto checked = check_self(options.self); !checked) return unexpected(checked.error());
  auto impl = std::make_unique<Impl>(std::move(options));
  if (!io) {
    impl->owned_io = std::make_unique<boost::asio::io_context>();
    io = impl->owned_io.get();
  }
  impl->io = io;
  if (impl->options.first_sequence) {
    impl->next_sequence = *impl->options.first_sequence;
  } else {
    std::random_device entropy;
    impl->next_sequence = static_cast<std::uint16_t>(std::uniform_int_distribution<unsigned>(0, 0xFFFF)(entropy));
  }
  impl->runtime = std::make_unique<transport::AsioRuntime>(*io);
  impl->clock = impl->runtime.get();
  impl->scheduler = impl->runtime.get();
  impl->repeated = std::make_unique<rt::RepeatedLines>(*impl->clock, *impl->scheduler, impl->options.log);
  transport::UdpLinkOptions link_options;
  link_options.bind = impl->options.bind;
  link_options.jss_self = impl->options.self;
  link_options.jss_multicast = impl->options.multicast;
  for (const auto& peer : impl->options.to) link_options.peers.push_back({peer, transport::Framing::as5669a});
  link_options.routes.max_entries = std::max<std::size_t>(impl->options.max_learnt_endpoints, 1);
  // A client starts its conversations: no endpoint is challenged (as an RA OCU session's link).
  link_options.verify_endpoints = false;
  auto link = transport::UdpLink::open(*io, *impl->clock, *impl->scheduler, std::move(link_options), impl->options.log);
  if (!link) return unexpected(link.error());
  impl->link = std::move(*link);
  Impl* raw = impl.get();
  raw->link->on_jss_packets(
      [raw](const transport::Inbound& inbound, rt::SenderStanding) { raw->receive_packets(inbound.jss); });
  std::unique_ptr<JssSession> session(new JssSession(std::move(impl)));
  raw->link->start();  // what arrives has a session to go to
  return session;
}

Expected<std::unique_ptr<JssSession>> JssSession::attach(JssSessionOptions options, JssEnvironment environment) {
  if (auto checked = check_self(options.self); !checked) return unexpected(checked.error());
  if (!environment.clock || !environment.scheduler || !environment.transmit || !environment.connect ||
      !environment.wait)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "an attached JSS session needs a clock, a scheduler, transmit, connect and wait"));
  auto impl = std::make_unique<Impl>(std::move(options));
  impl->environment = std::move(environment);
  impl->next_sequence = impl->options.first_sequence.value_or(0);
  impl->clock = impl->environment.clock;
  impl->scheduler = impl->environment.scheduler;
  impl->repeated = std::make_unique<rt::RepeatedLines>(*impl->clock, *impl->scheduler, impl->options.log);
  Impl* raw = impl.get();
  std::unique_ptr<JssSession> session(new JssSession(std::move(impl)));
  raw->environment.connect([raw](std::span<const std::uint8_t> datagram) { raw->receive(datagram); });
  return session;
}

const jss::JssId& JssSession::self() const { return impl_->options.self; }
const JssSessionOptions& JssSession::options() const { return impl_->options; }
const JssSessionCounters& JssSession::counters() const {
  impl_->sync_link_counters();  // what the link dropped since the last datagram
  return impl_->counters;
}

std::optional<transport::Ipv4Endpoint> JssSession::endpoint_of(const jss::JssId& id) const {
  if (!impl_->link) return std::nullopt;
  const auto route = impl_->link->jss_routes().route(id.subsystem, id.node);
  if (!route) return std::nullopt;
  return route->endpoint;
}

void JssSession::receive_datagram(std::span<const std::uint8_t> datagram) { impl_->receive(datagram); }

std::uint16_t JssSession::send_contents(const jss::JssId& to, std::span<const std::uint8_t> contents,
                                        jss::JudpPriority priority, bool ack_requested) {
  return impl_->send(to, contents, priority, ack_requested, nullptr);
}

// The session's policy for `contents` (its message ID first, little-endian).
MustArrivePolicy JssSession::Impl::policy_for(std::span<const std::uint8_t> contents) const {
  const std::uint16_t id = contents.size() >= 2 ? static_cast<std::uint16_t>(contents[0] | contents[1] << 8) : 0;
  return MustArrivePolicy::for_code(id, options.must_arrive);
}

ArrivalResult JssSession::send_contents_must_arrive(const jss::JssId& to, std::span<const std::uint8_t> contents,
                                                    jss::JudpPriority priority,
                                                    std::optional<MustArrivePolicy> policy) {
  return impl_->must_arrive(*this, to, contents, priority, policy.value_or(impl_->policy_for(contents)), false);
}

ArrivalResult JssSession::send_contents_must_arrive_through_stop(const jss::JssId& to,
                                                                 std::span<const std::uint8_t> contents,
                                                                 jss::JudpPriority priority,
                                                                 std::optional<MustArrivePolicy> policy) {
  return impl_->must_arrive(*this, to, contents, priority, policy.value_or(impl_->policy_for(contents)), true);
}

ArrivalResult JssSession::Impl::must_arrive(JssSession& session, const jss::JssId& to,
                                            std::span<const std::uint8_t> contents, jss::JudpPriority priority,
                                            MustArrivePolicy policy, bool through_stop) {
  ArrivalResult result;
  const auto started = clock->now();
  policy.retransmit_after = std::max<rt::Duration>(policy.retransmit_after, 1ms);
  policy.max_transmissions = std::max<std::uint32_t>(policy.max_transmissions, 1);
  if (contents.size() > std::max<std::size_t>(options.max_packet_contents, 3)) return result;
  if (to.is_broadcast())  // nobody could confirm for everyone: sent `most` times
    return detail::repeat_broadcast(session, policy, through_stop,
                                    [&] { send(to, contents, priority, false, nullptr); });
  std::vector<std::uint8_t> datagram;
  jss::JudpHeader sent;
  sent.ack_nak = jss::JudpAckNak::ack_requested;
  sent.source = options.self;
  sent.destination = to;
  sent.sequence = send(to, contents, priority, true, &datagram);
  result.transmissions = 1;
  const detail::JudpAcks::Key key = detail::JudpAcks::key_of_sent(sent);
  // The datagram is kept whole: a retransmission is the same packet, the same sequence number.
  if (acks.track(sent, datagram, started, policy) != node::TrackResult::tracked) {
    result.elapsed = clock->now() - started;
    return result;  // sent once, nothing to wait on (a sequence number still pending after a wrap)
  }
  const auto done = [&] { return settled.contains(key); };
  while (!done()) {
    const auto due = acks.next_deadline();
    if (!due) break;
    const auto wait = std::max<rt::Duration>(*due - clock->now(), rt::Duration::zero());
    if (through_stop ? session.run_cleanup_until(done, wait) : session.run_until(done, wait)) break;
    if (session.interrupted() && !through_stop) break;
    // A receiver that already acted on it drops a retransmission as a duplicate.
    auto poll = acks.poll(clock->now());
    for (const auto& again : poll.retransmit) transmit(again.header.destination, again.payload);
    for (const auto& given_up : poll.failed) settled.insert_or_assign(given_up.key, given_up);
  }
  result.elapsed = clock->now() - started;
  if (const auto it = settled.find(key); it != settled.end()) {
    result.transmissions = it->second.transmissions;
    result.outcome = it->second.outcome == node::AckOutcome::acknowledged ? Arrival::acknowledged
                     : it->second.outcome == node::AckOutcome::refused    ? Arrival::refused
                                                                          : Arrival::unacknowledged;
    settled.erase(it);
    return result;
  }
  // Stopped waiting (interrupted, or run through a cleanup's limit): nothing more of it goes out.
  result.transmissions = acks.forget(key).value_or(result.transmissions);
  result.outcome = session.interrupted() && !through_stop ? Arrival::interrupted : Arrival::unacknowledged;
  return result;
}

Expected<JssReceived> JssSession::request_contents(const jss::JssId& to, std::span<const std::uint8_t> query,
                                                   std::vector<std::uint16_t> reply_ids, rt::Duration timeout,
                                                   rt::Duration resend_every) {
  return await_reply_resending(to, std::move(reply_ids), timeout, [&] { send_contents(to, query); }, resend_every);
}

}  // namespace jaus::ocu
