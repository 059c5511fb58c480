#include "jaus/transport/udp_link.hpp"

#include <boost/asio/ip/multicast.hpp>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>

#include "handler_memory.hpp"

namespace jaus::transport {

namespace asio = boost::asio;
using asio::ip::udp;

namespace {

udp::endpoint to_asio(const Ipv4Endpoint& e) { return udp::endpoint(asio::ip::address_v4(e.address), e.port); }

Ipv4Endpoint from_asio(const udp::endpoint& e) {
  if (!e.address().is_v4()) return Ipv4Endpoint{0, e.port()};
  return Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
}

std::string bind_error(const Ipv4Endpoint& endpoint, const boost::system::error_code& ec) {
  if (ec == asio::error::address_in_use) return to_string(endpoint) + " is already in use";
  if (ec == boost::system::errc::address_not_available) return to_string(endpoint) + " is not an address of this machine";
  if (ec == boost::system::errc::permission_denied) return "not allowed to bind " + to_string(endpoint) + " (" + ec.message() + ")";
  return "cannot bind " + to_string(endpoint) + ": " + ec.message();
}

// Asks for `bytes` of receive buffer (0: the system's default stays), best
// effort: the kernel caps it. Returns what it granted (0: not readable).
std::size_t size_receive_buffer(udp::socket& socket, std::size_t bytes) {
  boost::system::error_code ec;
  if (bytes > 0)
    socket.set_option(udp::socket::receive_buffer_size(static_cast<int>(
                          std::min<std::size_t>(bytes, std::numeric_limits<int>::max()))),
                      ec);
  udp::socket::receive_buffer_size granted;
  socket.get_option(granted, ec);
  return ec || granted.value() < 0 ? 0 : static_cast<std::size_t>(granted.value());
}

constexpr rt::Duration kExpiryPeriod = std::chrono::seconds(1);
// New and moved routes are worth a line each, a flood of forged sources is not.
constexpr int kNewRouteLinesPerWindow = 10;

std::array<std::uint64_t, 2> challenge_key(const UdpLinkOptions& options) {
  if (options.challenge_key) return *options.challenge_key;
  std::random_device random;  // the kernel's entropy (getrandom), once per link
  std::array<std::uint64_t, 2> key{};
  for (auto& word : key) word = (std::uint64_t{random()} << 32) ^ random();
  return key;
}

// The JSS guard's key: another key, so its challenge numbers are not the RA guard's.
std::array<std::uint64_t, 2> jss_challenge_key(std::array<std::uint64_t, 2> key) {
  return {key[0] ^ 0x4a53532d6a756470ULL, key[1] ^ 0x415335363639410aULL};
}

}  // namespace

std::uint64_t UdpLinkCounters::dropped_total() const {
  return std::accumulate(dropped.begin(), dropped.end(), std::uint64_t{0});
}

struct UdpLink::Socket {
  explicit Socket(asio::io_context& io) : socket(io) {}
  udp::socket socket;
  udp::endpoint sender;
  // The one outstanding receive's operation (and one being freed) lives here.
  std::shared_ptr<detail::HandlerMemory> receive_memory = std::make_shared<detail::HandlerMemory>(2, 512);
  // As large as a UDP datagram can be: an AS5669A datagram may carry up to
  // 64 KiB of transport messages, and an RA datagram larger than any JAUS
  // one (kMaxDatagramSize) arrives whole, so its decoder drops it as
  // oversized instead of it being cut to a plausible length.
  std::array<std::uint8_t, 65536> buffer{};
};

UdpLink::UdpLink(asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler, UdpLinkOptions options,
                 rt::LogFn log)
    : io_(io),
      clock_(clock),
      scheduler_(scheduler),
      options_(std::move(options)),
      log_(log ? std::move(log) : rt::silent_log()),
      routes_(options_.routes),
      guard_(options_.amplification, challenge_key(options_)),
      jss_routes_(options_.routes),
      jss_guard_(options_.amplification, jss_challenge_key(challenge_key(options_))),
      repeated_lines_(clock_, scheduler_, log_) {
  for (const auto& peer : options_.peers) {
    routes_.add_static_peer(peer.endpoint, peer.framing);
    // A configured peer is one for JSS too: never challenged, and reached by what has no route.
    jss_routes_.add_static_peer(peer.endpoint, Framing::as5669a);
  }
  // Verification goes with the endpoint: a new one at that port starts unverified.
  routes_.on_forgotten([this](const Ipv4Endpoint& endpoint) {
    guard_.forget(endpoint);
    sync_amplification_counters();
  });
  jss_routes_.on_forgotten([this](const Ipv4Endpoint& endpoint) {
    jss_guard_.forget(endpoint);
    sync_amplification_counters();
  });
}

void UdpLink::sync_amplification_counters() {
  counters_.amplification = guard_.counters();
  counters_.jss.amplification = jss_guard_.counters();
}

jss::JssId UdpLink::jss_self() const {
  return options_.jss_self.value_or(jss::JssId{options_.subsystem, options_.node, 1});
}

void UdpLink::receive_datagram(const Ipv4Endpoint& from, std::span<const std::uint8_t> datagram) {
  if (!closed_) on_datagram(from, datagram);
}

Expected<std::unique_ptr<UdpLink>> UdpLink::open(asio::io_context& io, rt::Clock& clock,
                                                              rt::Scheduler& scheduler, UdpLinkOptions options,
                                                              rt::LogFn log) {
  std::unique_ptr<UdpLink> link(new UdpLink(io, clock, scheduler, std::move(options), std::move(log)));
  auto bound = link->bind_sockets();
  if (!bound) return unexpected(bound.error());
  // An open posture (anyone may command) is the node host's to warn about
  // (NodeHost::open): a tool's link is open by design.
  return link;
}

Expected<void> UdpLink::bind_sockets() {
  const auto failed = [](std::string what) { return unexpected(make_error(ErrorCode::io, std::move(what))); };
  boost::system::error_code ec;
  main_ = std::make_unique<Socket>(io_);
  main_->socket.open(udp::v4(), ec);
  if (ec) return failed("cannot open a UDP socket: " + ec.message());
  // No SO_REUSEADDR on the main socket: a second node on the same address and
  // port must fail loudly instead of silently sharing the traffic.
  main_->socket.bind(to_asio(options_.bind), ec);
  if (ec) return failed(bind_error(options_.bind, ec));
  main_->socket.non_blocking(true, ec);
  if (ec) return failed("cannot make the socket non-blocking: " + ec.message());
  receive_buffer_bytes_ = size_receive_buffer(main_->socket, options_.receive_buffer_bytes);
  local_port_ = main_->socket.local_endpoint(ec).port();

  if (options_.multicast && !options_.multicast->is_multicast())
    return failed(to_string(*options_.multicast) + " is not a multicast address (224.0.0.0/4)");
  if (options_.jss_multicast && !options_.jss_multicast->is_multicast())
    return failed(to_string(*options_.jss_multicast) + " is not a multicast address (224.0.0.0/4)");
  if (!options_.multicast && !options_.jss_multicast) return {};
  // Multicast is best effort: a host without a multicast route still talks to
  // its known and static peers.
  const auto interface = asio::ip::address_v4(options_.bind.address);
  if (!options_.bind.is_any()) main_->socket.set_option(asio::ip::multicast::outbound_interface(interface), ec);
  if (!ec) main_->socket.set_option(asio::ip::multicast::enable_loopback(true), ec);
  if (!ec) main_->socket.set_option(asio::ip::multicast::hops(options_.multicast_ttl), ec);
  const auto degrade = [&](std::optional<Ipv4Endpoint>& group, const std::string& what, std::string_view rest) {
    log_(rt::LogLevel::warn, "multicast " + to_string(*group) + ": " + what + "; " + std::string(rest));
    group.reset();
  };
  if (ec) {
    const std::string what = "cannot send: " + ec.message();
    if (options_.multicast) degrade(options_.multicast, what, "broadcasts go to known peers only");
    if (options_.jss_multicast) degrade(options_.jss_multicast, what, "JSS broadcasts go to static peers only");
    return {};
  }
  if (options_.multicast)
    if (auto joined = join_group(*options_.multicast); !joined)
      degrade(options_.multicast, joined.error().message(), "broadcasts go to known peers only");
  // One group for both dialects is joined once (the first byte tells them apart).
  if (options_.jss_multicast && options_.jss_multicast != options_.multicast)
    if (auto joined = join_group(*options_.jss_multicast); !joined)
      degrade(options_.jss_multicast, joined.error().message(), "JSS broadcasts go to static peers only");
  return {};
}

Expected<void> UdpLink::join_group(const Ipv4Endpoint& group) {
  const auto failed = [](const std::string& what, const boost::system::error_code& error) {
    return unexpected(make_error(ErrorCode::io, what + ": " + error.message()));
  };
  boost::system::error_code ec;
  const auto interface = asio::ip::address_v4(options_.bind.address);
  const auto group_address = asio::ip::address_v4(group.address);
  if (options_.bind.is_any() && options_.bind.port == group.port) {
    // The main socket already receives everything sent to its port.
    main_->socket.set_option(asio::ip::multicast::join_group(group_address), ec);
    if (ec) return failed("cannot join", ec);
    return {};
  }
  // A socket bound to one address does not see the group's datagrams: a
  // second socket, bound to the group, receives them. Several nodes on one
  // host share the group, hence SO_REUSEADDR here.
  auto socket = std::make_unique<Socket>(io_);
  socket->socket.open(udp::v4(), ec);
  if (!ec) socket->socket.set_option(udp::socket::reuse_address(true), ec);
  if (!ec) size_receive_buffer(socket->socket, options_.receive_buffer_bytes);
  if (!ec) socket->socket.bind(to_asio(group), ec);
  if (!ec) socket->socket.set_option(asio::ip::multicast::join_group(group_address, interface), ec);
  if (ec) return failed("cannot receive", ec);
  group_sockets_.push_back(std::move(socket));
  return {};
}

UdpLink::~UdpLink() { close(); }

void UdpLink::start() {
  if (closed_) return;
  receive_next(*main_);
  for (const auto& socket : group_sockets_) receive_next(*socket);
  schedule_expiry();
}

void UdpLink::close() {
  if (closed_) return;
  closed_ = true;
  if (expiry_timer_ != rt::kNoTimer) scheduler_.cancel(expiry_timer_);
  expiry_timer_ = rt::kNoTimer;
  boost::system::error_code ignored;
  if (main_) main_->socket.close(ignored);
  for (const auto& socket : group_sockets_) socket->socket.close(ignored);
}

Ipv4Endpoint UdpLink::local_endpoint() const {
  boost::system::error_code ec;
  const auto endpoint = main_->socket.local_endpoint(ec);
  return ec ? options_.bind : from_asio(endpoint);
}

void UdpLink::schedule_expiry() {
  expiry_timer_ = scheduler_.call_at(clock_.now() + kExpiryPeriod, [this] {
    expiry_timer_ = rt::kNoTimer;
    routes_.expire(clock_.now());
    jss_routes_.expire(clock_.now());
    report_expired(guard_.expire(clock_.now()), guard_);
    report_expired(jss_guard_.expire(clock_.now()), jss_guard_);
    sync_amplification_counters();
    schedule_expiry();
  });
}

void UdpLink::receive_next(Socket& socket) {
  auto on_received = [this, &socket, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec,
                                                                         std::size_t size) {
    if (alive.expired() || ec == asio::error::operation_aborted || closed_) return;
    if (!ec) on_datagram(from_asio(socket.sender), std::span(socket.buffer).first(size));
    // Other errors (ICMP unreachable reported on the socket) are transient.
    receive_next(socket);
  };
  socket.socket.async_receive_from(asio::buffer(socket.buffer), socket.sender,
                                   detail::with_memory(socket.receive_memory, std::move(on_received)));
}

bool UdpLink::allowed(std::uint32_t address) const {
  if (options_.allow.empty()) return true;
  for (const auto& cidr : options_.allow)
    if (cidr.contains(address)) return true;
  return false;
}

bool UdpLink::may_control(std::uint32_t address) const {
  if (options_.control_from.empty()) return true;
  for (const auto& cidr : options_.control_from)
    if (cidr.contains(address)) return true;
  return false;
}

template <class MakeDetail>
void UdpLink::drop(DropReason reason, const Ipv4Endpoint& from, MakeDetail make_detail) {
  count_drop(reason);
  // The reason's name is a literal (to_string), so it can key the limiter.
  repeated_lines_.write(to_string(reason), rt::LogLevel::warn, [&] {
    const std::string detail = make_detail();
    return "dropped a datagram from " + to_string(from) + ": " + std::string(to_string(reason)) +
           (detail.empty() ? "" : " (" + detail + ")") + " [" +
           std::to_string(counters_.dropped[static_cast<std::size_t>(reason)]) + " so far]";
  });
}

void UdpLink::drop(DropReason reason, const Ipv4Endpoint& from) {
  drop(reason, from, [] { return std::string(); });
}

std::pair<std::uint16_t, std::uint8_t> UdpLink::self_in(IdSpace space) const {
  if (space == IdSpace::jss) return {jss_self().subsystem, jss_self().node};
  return {options_.subsystem, options_.node};
}

UdpLink::DeliveryCounters UdpLink::delivery_counters(IdSpace space) {
  if (space == IdSpace::jss)
    return {counters_.jss.datagrams_delivered, counters_.jss.delivered_unrecorded, counters_.jss.delivered_observer};
  return {counters_.packets_delivered, counters_.delivered_unrecorded, counters_.delivered_observer};
}

void UdpLink::on_datagram(const Ipv4Endpoint& from, std::span<const std::uint8_t> datagram) {
  ++counters_.datagrams_received;
  if (!allowed(from.address)) return drop(DropReason::not_allowed, from);
  if (!options_.bind.is_any() && from == options_.bind) return count_drop(DropReason::from_self);
  if (!datagram.empty() && datagram[0] == jss::kAs5669aVersion) {
    ++counters_.jss.datagrams_received;
    if (!jss_handler_) return drop(DropReason::jss_off, from);
  }
  const auto inbound = decode_datagram(datagram);
  if (!inbound)
    return drop(drop_reason(datagram, inbound.error()), from, [&] { return inbound.error().message(); });
  const Inbound& in = *inbound;
  const IdSpace space = in.id_space();
  const bool jss = space == IdSpace::jss;
  const auto [self_subsystem, self_node] = self_in(space);
  if (in.subsystem == self_subsystem && in.node == self_node) {
    // Our own broadcast looped back comes from our port; anything else with
    // our ID is a misconfigured peer, which the operator must hear about.
    const bool ours = from.port == local_port_ && (options_.bind.is_any() || from.address == options_.bind.address);
    if (ours) return count_drop(DropReason::from_self);
    return drop(DropReason::from_self, from, [&] {
      return (jss ? "another JSS node uses this node's JSS ID " : "another node uses this node's ID ") +
             in.source_text();
    });
  }
  // Nothing is learnt from, nor delivered for, a source that cannot answer.
  if (!in.one_sender)
    return drop(DropReason::invalid_source, from, [&] { return (jss ? "JSS source " : "source ") + in.source_text(); });
  // Safety (issue 42): a JSS client's alias is the face's alone. An RA
  // datagram naming one as its source is a forgery (or a peer configured
  // into the alias subsystem): dropped from any host, before any route is
  // learnt, so it never reaches the node as that JSS operator.
  if (!jss && options_.alias_subsystem != 0 && in.subsystem == options_.alias_subsystem)
    return drop(DropReason::alias_source, from, [&] {
      return "source " + in.source_text() + " is in the JSS clients' alias subsystem " +
             std::to_string(options_.alias_subsystem) + "; only the JSS face speaks for it";
    });
  RouteTable& routes = routes_of(space);
  const Learnt learnt = routes.learn(in.subsystem, in.node, from, in.framing, clock_.now());
  auto who = [&] {
    return (jss ? "JSS " : "node ") + std::to_string(in.subsystem) + "." + std::to_string(in.node);
  };
  if (learnt == Learnt::relayed_copy) return count_drop(DropReason::relayed_copy);
  if (learnt == Learnt::claim_refused) {
    return drop(DropReason::route_claim, from, [&] {
      const auto route = routes.route(in.subsystem, in.node);
      return who() + " is at " + (route ? to_string(route->endpoint) : std::string("?")) +
             "; spoofed, or two peers with one ID";
    });
  }
  if (learnt == Learnt::new_route || learnt == Learnt::moved) {
    // A move is a restarted peer (same host, or its old endpoint silent) or a
    // configured one: worth a line, not a warning. A flood of forged sources
    // is a few lines and a count.
    repeated_lines_.write({"new and moved routes", kNewRouteLinesPerWindow}, rt::LogLevel::info, [&] {
      return who() + (learnt == Learnt::moved ? " moved to " : " at ") + to_string(from) + " (" +
             std::string(to_string(in.framing)) + ")";
    });
  }
  if (options_.verify_endpoints && !passes_verification(from, in)) return;
  const DeliveryCounters delivered = delivery_counters(space);
  const rt::SenderStanding standing = standing_of(from, learnt, delivered, who);
  ++delivered.delivered;
  if (jss) return jss_handler_(in, standing);
  if (options_.relay) relay(from, in.ra.header, datagram.last(kHeaderSize + in.ra.payload.size()));
  if (handler_) handler_(in.ra, in.framing, standing);
}

bool UdpLink::passes_verification(const Ipv4Endpoint& from, const Inbound& in) {
  const IdSpace space = in.id_space();
  AmplificationGuard& guard = guard_of(space);
  // A new learnt endpoint starts unverified (static peers are verified from
  // the start); one without a route too, since (255, ...) broadcasts reach it.
  if (!guard.tracks(from)) {
    const RouteTable& routes = routes_of(space);
    const auto peer = routes.peers().find(from);
    if (peer != routes.peers().end() && !peer->second.is_static) guard.track(from);
  }
  if (!guard.unverified(from)) return true;
  if (guard.received(from, in)) {
    // The challenge's answer is the link's, not the node's: the endpoint
    // receives at its address, so what was held goes.
    for (const auto& held : guard.release(from)) send_to(from, held.framing, held.packet);
    sync_amplification_counters();
    return false;
  }
  // Its budget grew: a challenge may fit now. A JSS endpoint is challenged
  // at once, before its first reply (a JSS client may not send again for a
  // half timeout: amplification_guard.hpp).
  send_challenge(from, in.framing, /*at_first_contact=*/space == IdSpace::jss);
  // Safety (issue 43): never a command acted on for an endpoint whose
  // replies are withheld. The guarantee is kept here, at entry, for both
  // dialects: a datagram carrying a command is delivered only once its
  // reply's bytes are set aside (admit_command); a Request Control whose
  // Confirm could not be sent is not granted, since it never reaches the
  // component. Stops always act (nobody packs a stop with other commands),
  // their ACK's bytes set aside if there are any.
  if (in.carries_stop) {
    guard.reserve_reply(from, clock_.now());
  } else if (in.carries_command && !guard.admit_command(from, in.framing, clock_.now())) {
    send_challenge(from, in.framing);  // answering it lets its next command through
    sync_amplification_counters();
    refuse_command(from, in.command_code, guard);
    return false;
  }
  sync_amplification_counters();
  return true;
}

template <class Who>
rt::SenderStanding UdpLink::standing_of(const Ipv4Endpoint& from, Learnt learnt, DeliveryCounters counters, Who who) {
  if (learnt == Learnt::rejected) {
    ++counters.unrecorded;
    repeated_lines_.write("senders not recorded", rt::LogLevel::warn, [&] {
      return who() + " at " + to_string(from) +
             " not recorded (route table full, or its host's endpoints all hold state): delivered as unrecorded [" +
             std::to_string(counters.unrecorded) + " so far]";
    });
    return rt::SenderStanding::unrecorded;
  }
  if (!may_control(from.address)) {
    ++counters.observer;
    return rt::SenderStanding::observer;
  }
  return rt::SenderStanding::trusted;
}

void UdpLink::send_challenge(const Ipv4Endpoint& to, Framing framing, bool at_first_contact) {
  if (framing == Framing::as5669a) {
    if (const auto challenge = jss_guard_.challenge_jss(to, jss_self(), clock_.now(), at_first_contact))
      send_to(to, framing, *challenge);
    return;
  }
  const auto challenge = guard_.challenge(to, framing, options_.subsystem, options_.node, clock_.now());
  if (!challenge) return;
  std::array<std::uint8_t, kHeaderSize> bytes{};
  encode_header_unchecked(*challenge, bytes);
  send_to(to, framing, bytes);
}

void UdpLink::send_routed(const Ipv4Endpoint& to, Framing framing, std::span<const std::uint8_t> packet) {
  if (!options_.verify_endpoints) return send_to(to, framing, packet);
  AmplificationGuard& guard = guard_of(id_space_of(framing));
  const auto verdict = guard.offer(to, framing, packet, clock_.now());
  if (verdict == AmplificationGuard::Verdict::send) {
    send_to(to, framing, packet);
  } else if (verdict == AmplificationGuard::Verdict::held) {
    repeated_lines_.write("replies held for unverified endpoints", rt::LogLevel::info, [&] {
      const auto& c = guard.counters();
      return "reply to " + to_string(to) +
             " held: beyond the budget of an unverified endpoint until it answers a challenge (ACK requested) [" +
             std::to_string(c.replies_held) + " held so far]";
    });
    send_challenge(to, framing);
  } else {
    // One line per streak (a reply sent ends it), limited across endpoints: a flood is a few lines and a count.
    if (guard.last_drop_began_streak())
      repeated_lines_.write({"reply drop streaks", kNewRouteLinesPerWindow}, rt::LogLevel::warn, [&] {
        const auto& c = guard.counters();
        return "replies to " + to_string(to) +
               " dropped: beyond the budget of an endpoint that has not answered a challenge (transport."
               "unverified_*; a peer that ignores ACK requests may go in transport.peers) [" +
               std::to_string(c.replies_dropped_unverified) + " dropped so far]";
      });
    send_challenge(to, framing);
  }
  sync_amplification_counters();
}

void UdpLink::refuse_command(const Ipv4Endpoint& from, std::uint16_t code, const AmplificationGuard& guard) {
  repeated_lines_.write({"commands refused for want of reply budget", kNewRouteLinesPerWindow}, rt::LogLevel::warn,
                        [&] {
                          char hex[16];
                          std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(code));
                          return "command " + std::string(hex) + " from " + to_string(from) +
                                 " not executed: its reply could not be sent (the endpoint's budget is spent and "
                                 "it has not answered a challenge) [" +
                                 std::to_string(guard.counters().commands_refused) + " so far]";
                        });
}

void UdpLink::report_expired(const std::vector<AmplificationGuard::Expired>& expired, const AmplificationGuard& guard) {
  for (const auto& e : expired)
    repeated_lines_.write({"held replies expired", kNewRouteLinesPerWindow}, rt::LogLevel::warn, [&] {
      return std::to_string(e.replies) + " held repl" + (e.replies == 1 ? "y" : "ies") + " to " +
             to_string(e.endpoint) +
             " dropped: it did not answer the challenge (ACK requested) in time; its replies beyond the budget "
             "are dropped from now on [" +
             std::to_string(guard.counters().held_replies_expired) + " expired so far]";
    });
}

void UdpLink::relay(const Ipv4Endpoint& from, const Header& header, std::span<const std::uint8_t> packet) {
  const Address& to = header.destination;
  if (to.subsystem == options_.subsystem || to.subsystem == Address::kBroadcast || to.node == Address::kBroadcast)
    return;
  const auto next = routes_.route(to.subsystem, to.node);
  if (!next || next->endpoint == from) return;
  // Only what its sender handed us itself: a relayed message is never relayed
  // again, so two relays cannot pass one back and forth.
  const auto sender = routes_.route(header.source.subsystem, header.source.node);
  if (!sender || sender->endpoint != from) return;
  ++counters_.relayed;
  send_routed(next->endpoint, next->framing, packet);
}

bool UdpLink::broadcast_reaches(const Address& to, const Peer& peer) const {
  if (to.subsystem == Address::kBroadcast || peer.hosts_subsystem(to.subsystem)) return true;
  // A configured peer never heard from may be one of the subsystem's nodes (udp_link.hpp).
  return options_.broadcast_to_unheard_peers && peer.is_static && peer.subsystems.none();
}

void UdpLink::send_to(const Ipv4Endpoint& to, Framing framing, std::span<const std::uint8_t> packet) {
  if (closed_) return;
  const FramePrefix prefix = frame_prefix(framing, packet.size());
  const std::array<asio::const_buffer, 2> buffers = {asio::buffer(prefix.bytes.data(), prefix.size),
                                                     asio::buffer(packet.data(), packet.size())};
  boost::system::error_code ec;
  main_->socket.send_to(buffers, to_asio(to), 0, ec);
  if (ec) {
    ++counters_.send_errors;
    repeated_lines_.write("send errors", rt::LogLevel::warn, [&] {
      return "cannot send to " + to_string(to) + ": " + ec.message() + " [" + std::to_string(counters_.send_errors) +
             " send errors so far]";
    });
    return;
  }
  ++counters_.datagrams_sent;
}

void UdpLink::transmit(const Header& header, std::span<const std::uint8_t> packet) {
  const Address& to = header.destination;
  const bool broadcast = to.subsystem == Address::kBroadcast || to.node == Address::kBroadcast;
  if (!broadcast) {
    if (auto peer = routes_.route(to.subsystem, to.node)) return send_routed(peer->endpoint, peer->framing, packet);
    ++counters_.unrouted;
  }
  // Broadcast, or a node not heard from yet: the multicast group and the
  // static peers (and, for broadcasts, every known peer) may reach it.
  // What is addressed to our own subsystem (S.255.1.1 heartbeats, a node of
  // S not heard yet) never goes to the group: other subsystems share it, and
  // a node manager rejects (and logs, every time) a message for another
  // subsystem on its subsystem interface (udp_link.hpp). Our subsystem's
  // other nodes announce themselves with (255, 255, 1, 1) heartbeats, which
  // do go to the group; from then on they are known peers and get these.
  bool sent = false;
  if (options_.multicast && to.subsystem != options_.subsystem) {
    send_to(*options_.multicast, options_.multicast_framing.value_or(options_.framing), packet);
    sent = true;
  }
  if (broadcast && options_.broadcast_to_peers) {
    for (const auto& [endpoint, peer] : routes_.peers()) {
      if (!broadcast_reaches(to, peer)) continue;
      send_routed(endpoint, peer.framing, packet);
      sent = true;
    }
  } else {
    // Only the configured peers: a unicast to a node without a route (one of
    // many forged requesters) must not cost a walk over every learnt peer.
    for (const auto& configured : options_.peers) {
      const auto peer = routes_.peers().find(configured.endpoint);
      send_to(configured.endpoint, peer != routes_.peers().end() ? peer->second.framing : configured.framing, packet);
      sent = true;
    }
  }
  if (!sent && !broadcast) {
    ++counters_.no_route;
    // Replies to a flood of forged sources are as many as the flood: limited
    // per window like the drops, not per count (a fast node sends thousands a second).
    repeated_lines_.write("packets with no route dropped", rt::LogLevel::warn, [&] {
      return "no route to " + to.to_string() + ": dropped [" + std::to_string(counters_.no_route) + " so far]";
    });
  }
}

void UdpLink::transmit_jss(const jss::JssId& to, std::span<const std::uint8_t> datagram) {
  if (!to.is_broadcast()) {
    if (auto peer = jss_routes_.route(to.subsystem, to.node))
      return send_routed(peer->endpoint, Framing::as5669a, datagram);
    ++counters_.jss.unrouted;
  }
  // Broadcast, or a JSS node not heard from yet: the JSS group and the static
  // peers (JRM and fkie's node manager send there too; the reply teaches the route).
  bool sent = false;
  if (options_.jss_multicast) {
    send_to(*options_.jss_multicast, Framing::as5669a, datagram);
    sent = true;
  }
  for (const auto& configured : options_.peers) {
    send_to(configured.endpoint, Framing::as5669a, datagram);
    sent = true;
  }
  if (!sent && !to.is_broadcast()) {
    ++counters_.jss.no_route;
    repeated_lines_.write("JSS datagrams with no route dropped", rt::LogLevel::warn, [&] {
      return "no route to JSS " + to.to_string() + ": dropped [" + std::to_string(counters_.jss.no_route) +
             " so far]";
    });
  }
}

}  // namespace jaus::transport
