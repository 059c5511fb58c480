// The node's UDP transport (docs/wire-format.md, "Node-to-node transport"):
// one JAUS message per datagram, OPC or JUDP framing, routes learnt from the
// source endpoint of what arrives, static peers, multicast for broadcasts.
//
// One socket sends and receives, bound to the configured address and port
// (3794 by default), so replies leave from the port peers expect: two nodes on
// one host bind 127.0.0.1:3794 and 127.0.0.2:3794. A subsystem's broadcasts
// (S.255.x.x) go only to peers known to be nodes of S, and to the multicast
// group unless S is our own: other subsystems' node managers drop them
// (docs/wire-format.md, "Liveness and discovery"), and every other subsystem shares the group.
// The link relays a message for another subsystem that arrives from a node
// heard directly to where that subsystem's node was heard, so an OCU that
// talks to one node reaches the subsystems that node knows. Sending is synchronous and
// non-blocking (the node's bytes are only valid during transmit()); a full
// socket buffer drops the datagram and counts it, never blocks the node.
// Everything runs on the io_context's thread.
//
// Hostile network (issue 28). Every delivered message carries the sender's
// standing (rt::SenderStanding), decided here:
// - unrecorded: its source could not be recorded (route table full, or its
//   address at max_endpoints_per_address endpoints that all hold state). It
//   is still delivered (Set Emergency is obeyed from anyone), but the runtime
//   lets it leave no state behind. The claim check always runs first: a
//   claim on a known ID that the rules refuse is dropped, full table or not.
// - observer: recorded, from an address outside `control_from`;
// - trusted: recorded, and `control_from` is empty or contains its address.
// Routes of IDs that hold state at this node (pin_routes_while) never move to
// another IP address and never expire while they do (route_table.hpp).
// With `verify_endpoints`, a learnt endpoint is sent no more than it sent plus
// an allowance, and all such endpoints together no more than a global rate,
// until it answers a challenge; a command from one is delivered only if its
// reply can be sent (amplification_guard.hpp, on_datagram).
//
// SAE JAUS (docs/jss.md, "Transport: one port, three framings"): datagrams
// whose first byte is 0x02 are AS5669A. Every datagram takes one receive
// path (on_datagram): decoded once by its framing's codec (inbound.hpp), its
// host filtered by `allow`, its source checked, its route learnt in the table
// of its ID space (RA, or JSS with 16-bit subsystems: same bounds and claim
// rules), its endpoint verified by that space's guard, its standing decided
// as above; then an RA message goes to the node (on_packet) and an AS5669A
// datagram's decoded messages to the JSS handler (on_jss_packets: the node's
// JSS face), which never parses the bytes again. transmit_jss() sends the face's
// datagrams by JssId: to the learnt endpoint (through the amplification guard;
// a JSS endpoint is challenged with an AS5669A Query Heartbeat Pulse, ACK
// requested), else to `jss_multicast` and the static peers. Without a
// handler AS5669A datagrams are dropped (jss_off). The link reads nothing of
// JSS beyond the transport header. An RA datagram whose source is in the
// face's alias subsystem (alias_subsystem) is dropped before anything is
// learnt from it (alias_source): the face is the only way into the node for
// an alias address.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/jss/jss_id.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/environment.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/runtime/sender_standing.hpp"
#include "jaus/transport/amplification_guard.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/inbound.hpp"
#include "jaus/transport/ipv4.hpp"
#include "jaus/transport/peer.hpp"
#include "jaus/transport/route_table.hpp"

namespace jaus::transport {

struct UdpLinkOptions {
  // This node: datagrams from it (its own multicast looped back) are dropped.
  std::uint8_t subsystem = 0;
  std::uint8_t node = 0;
  Ipv4Endpoint bind{0, kJausPort};
  Framing framing = Framing::opc;           // for peers not heard from yet
  // Broadcasts (and messages for nodes not heard yet) go here, e.g.
  // 224.1.0.1:3794, the group RA 3.x implementations on the LAN share with
  // other subsystems; so never what is addressed to our own subsystem
  // (`subsystem` above): other subsystems' node managers reject that.
  // Received datagrams are the same whichever socket took them: a sender
  // heard through the group gets the standing its address gives it
  // (`control_from`), as it would by unicast, and its route is learnt from
  // its source endpoint.
  std::optional<Ipv4Endpoint> multicast;
  // The framing of what goes to the group; unset: `framing` (jausd: judp,
  // what the common RA implementation reads on 224.1.0.1).
  std::optional<Framing> multicast_framing;
  std::uint8_t multicast_ttl = 1;
  // SO_RCVBUF asked of each socket, so that a burst (a discovery answered by
  // a hundred subsystems, a camera's frame) waits in the kernel instead of
  // being dropped; the kernel caps it at net.core.rmem_max (Linux: 208 KiB by
  // default, and it keeps twice what it grants). 0: the system's default.
  std::size_t receive_buffer_bytes = 1 << 20;
  bool broadcast_to_peers = true;           // broadcasts also go to every known peer
  // A subsystem's broadcast (S.255...) goes to the peers heard as its nodes;
  // with this, also to the static peers not heard from yet (they may be its
  // nodes). For an OCU (issue 49): its configured peers are the vehicles it
  // means to reach, and a stop to 1.255.255.255 right after a vehicle starts
  // must reach it before its first heartbeat. Off for a node (jausd): its own
  // subsystem's heartbeats are not for peers of other subsystems.
  bool broadcast_to_unheard_peers = false;
  // Relay messages for other subsystems to where their node was heard: for
  // a node that bridges subsystems (an OCU reaches every subsystem through
  // it). Off by default: a relay's copy of a message the sender also sent
  // directly can teach a receiver the relay's endpoint for the sender while
  // both start, and forwarding strangers' traffic is a choice to make.
  bool relay = false;
  std::vector<StaticPeer> peers;
  std::vector<Cidr> allow;                  // empty: anyone may talk to the node
  // Who may command: a recorded sender from outside these networks is
  // delivered as an observer (queries, reports, its own emergency hold).
  // Empty: every allowed host may command (trusted).
  std::vector<Cidr> control_from;
  // No more bytes to a learnt endpoint than it sent plus an allowance until
  // it answers a challenge (amplification_guard.hpp): on for a node (jausd),
  // off for clients that start the conversation themselves (OCU tools).
  bool verify_endpoints = false;
  AmplificationGuardOptions amplification;
  // The key of the challenges' sequence numbers; unset: random per link.
  // Tests inject it to know the numbers.
  std::optional<std::array<std::uint64_t, 2>> challenge_key;
  RouteTableOptions routes;  // the RA table's and the JSS table's bounds, each
  // SAE JAUS (AS5669A): the group JSS broadcasts and datagrams for unknown
  // JSS IDs go to, joined on open (jausd: 239.255.0.1:3794). Unset: none.
  std::optional<Ipv4Endpoint> jss_multicast;
  // Our node manager's JSS ID: the source of JSS challenges; AS5669A datagrams
  // from its (subsystem, node) are ours. Unset: (subsystem, node, 1).
  std::optional<jss::JssId> jss_self;
  // The RA subsystem of the JSS face's client aliases (FaceConfig::
  // client_alias_subsystem); 0: no face, no alias subsystem. An RA datagram
  // claiming a source in it is dropped (DropReason::alias_source) from any
  // host: only the face speaks for an alias, so nobody forges a JSS
  // operator's control, emergency hold or release over RA (issue 42).
  std::uint8_t alias_subsystem = 0;
};

struct JssLinkCounters {
  std::uint64_t datagrams_received = 0;   // first byte 0x02 (their drops count in UdpLinkCounters::dropped)
  std::uint64_t datagrams_delivered = 0;  // handed to the JSS handler
  std::uint64_t delivered_unrecorded = 0;
  std::uint64_t delivered_observer = 0;
  std::uint64_t unrouted = 0;             // to a JSS ID not heard: sent to the group and static peers
  std::uint64_t no_route = 0;             // ...and nowhere to send it: dropped
  AmplificationCounters amplification;    // the JSS endpoints' verification
};

struct UdpLinkCounters {
  std::uint64_t datagrams_received = 0;
  std::uint64_t packets_delivered = 0;  // handed to the node
  std::array<std::uint64_t, static_cast<std::size_t>(DropReason::count_)> dropped{};
  std::uint64_t datagrams_sent = 0;
  std::uint64_t send_errors = 0;        // the socket refused (buffer full, unreachable, ...)
  std::uint64_t unrouted = 0;           // unicast to an unknown node: sent to static peers and multicast
  std::uint64_t no_route = 0;           // ...and nowhere to send it: dropped
  std::uint64_t relayed = 0;            // messages for another subsystem sent on to its node
  std::uint64_t delivered_unrecorded = 0;  // delivered as rt::SenderStanding::unrecorded
  std::uint64_t delivered_observer = 0;    // delivered as rt::SenderStanding::observer
  AmplificationCounters amplification;     // verify_endpoints (amplification_guard.hpp)
  JssLinkCounters jss;                     // AS5669A datagrams
  std::uint64_t dropped_total() const;
  std::uint64_t dropped_for(DropReason reason) const { return dropped[static_cast<std::size_t>(reason)]; }
};

class UdpLink final : public node::Link {
 public:
  // A received JAUS message: header decoded and checked once, here, with its
  // payload (a view into the datagram, valid during the call), framing and
  // what the link knows of its sender (see above).
  using PacketHandler = std::function<void(const PacketView& packet, Framing framing, rt::SenderStanding standing)>;
  // A received AS5669A datagram, decoded (inbound.jss: its transport
  // messages, one sender's; views valid during the call), with what the link
  // knows of its sender.
  using JssPacketHandler = std::function<void(const Inbound& inbound, rt::SenderStanding standing)>;

  // Opens and binds the sockets. A failure is one readable line, e.g.
  // "127.0.0.1:3794 is already in use".
  static Expected<std::unique_ptr<UdpLink>> open(boost::asio::io_context& io, rt::Clock& clock,
                                                               rt::Scheduler& scheduler, UdpLinkOptions options,
                                                               rt::LogFn log = {});
  ~UdpLink() override;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  // Where received JAUS messages go; typically Node::receive.
  void on_packet(PacketHandler handler) { handler_ = std::move(handler); }
  // Whether a node ID holds control, an emergency hold or a service
  // connection at one of this node's components: its route is pinned
  // (route_table.hpp). Asked on claims from another address, never per datagram.
  void pin_routes_while(std::function<bool(std::uint8_t subsystem, std::uint8_t node)> holds_state) {
    routes_.pin_while(std::move(holds_state));
  }
  // Where AS5669A datagrams go (the JSS face); unset: they are dropped.
  void on_jss_packets(JssPacketHandler handler) { jss_handler_ = std::move(handler); }
  // Whether a JSS node (subsystem, node) holds state here (its alias holds
  // control, an emergency, ...): its JSS route is pinned as RA ones are.
  void pin_jss_routes_while(std::function<bool(std::uint16_t subsystem, std::uint8_t node)> holds_state) {
    jss_routes_.pin_while(std::move(holds_state));
  }
  // Binds an RA node ID (or a JSS node's) to the host it held state from
  // before a restart (RouteTable::reserve): called before start(), so the
  // first datagram naming that ID from another host is already a refused claim.
  void reserve_route(std::uint8_t subsystem, std::uint8_t node, std::uint32_t address) {
    routes_.reserve(subsystem, node, address, clock_.now());
  }
  void reserve_jss_route(std::uint16_t subsystem, std::uint8_t node, std::uint32_t address) {
    jss_routes_.reserve(subsystem, node, address, clock_.now());
  }
  // Starts receiving.
  void start();
  // Stops receiving and sending (pending handlers are cancelled).
  void close();

  // node::Link: routes one message by its header's destination.
  void transmit(const Header& header, std::span<const std::uint8_t> packet) override;
  // Sends one message to an endpoint in a framing, outside routing (tools):
  // not limited by verify_endpoints (the caller chose the endpoint).
  void send_to(const Ipv4Endpoint& to, Framing framing, std::span<const std::uint8_t> packet);
  // Sends one complete AS5669A datagram to a JSS ID: the endpoint learnt for
  // its (subsystem, node); broadcast IDs and IDs not heard from go to
  // jss_multicast and the static peers.
  void transmit_jss(const jss::JssId& to, std::span<const std::uint8_t> datagram);

  // Takes `datagram` as if the socket had received it from `from`: every
  // check, count and route rule applies. For captures replayed and floods
  // driven in-process (tests); a closed link ignores it.
  void receive_datagram(const Ipv4Endpoint& from, std::span<const std::uint8_t> datagram);

  Ipv4Endpoint local_endpoint() const;
  // What the kernel granted the main socket's receive buffer (SO_RCVBUF as
  // read back; Linux reports twice the data it holds); 0 when not read.
  std::size_t receive_buffer_bytes() const { return receive_buffer_bytes_; }
  const UdpLinkCounters& counters() const { return counters_; }
  const RouteTable& routes() const { return routes_; }
  const RouteTable& jss_routes() const { return jss_routes_; }

 private:
  struct Socket;
  UdpLink(boost::asio::io_context& io, rt::Clock& clock, rt::Scheduler& scheduler, UdpLinkOptions options,
          rt::LogFn log);
  Expected<void> bind_sockets();
  void receive_next(Socket& socket);
  // The one receive path, for every framing (see above).
  void on_datagram(const Ipv4Endpoint& from, std::span<const std::uint8_t> datagram);
  // verify_endpoints: whether a datagram from `from` goes on to the node. Not
  // if it answers our challenge (it is the link's) or carries a command whose
  // reply could not be sent (amplification_guard.hpp).
  bool passes_verification(const Ipv4Endpoint& from, const Inbound& inbound);
  // Per ID space: where its senders' routes live, who verifies their
  // endpoints, our own node's ID in it, and its delivery counters.
  RouteTable& routes_of(IdSpace space) { return space == IdSpace::jss ? jss_routes_ : routes_; }
  AmplificationGuard& guard_of(IdSpace space) { return space == IdSpace::jss ? jss_guard_ : guard_; }
  std::pair<std::uint16_t, std::uint8_t> self_in(IdSpace space) const;
  struct DeliveryCounters {
    std::uint64_t& delivered;
    std::uint64_t& unrecorded;
    std::uint64_t& observer;
  };
  DeliveryCounters delivery_counters(IdSpace space);
  // The group of `group`: joined on the main socket, or a socket of its own.
  Expected<void> join_group(const Ipv4Endpoint& group);
  jss::JssId jss_self() const;
  // Counts a dropped datagram and writes its line, limited per reason; the
  // detail ("source 0.1.1.1") is built only for a line that is written, not
  // per datagram of a flood. (Defined and used in udp_link.cpp only.)
  template <class MakeDetail>
  void drop(DropReason reason, const Ipv4Endpoint& from, MakeDetail make_detail);
  void drop(DropReason reason, const Ipv4Endpoint& from);
  // Counts a drop that is expected and worth no line (our multicast coming back).
  void count_drop(DropReason reason) { ++counters_.dropped[static_cast<std::size_t>(reason)]; }
  bool allowed(std::uint32_t address) const;
  bool may_control(std::uint32_t address) const;
  // The standing of a sender whose route learn() answered with `learnt`,
  // counted; `who` names it, built only for a line that is written.
  // (Defined and used in udp_link.cpp only.)
  template <class Who>
  rt::SenderStanding standing_of(const Ipv4Endpoint& from, Learnt learnt, DeliveryCounters counters, Who who);
  // send_to, through the amplification guard when verify_endpoints is on:
  // what goes to learnt endpoints the routes chose.
  void send_routed(const Ipv4Endpoint& to, Framing framing, std::span<const std::uint8_t> packet);
  // A challenge to `to`, if one is due. `at_first_contact`: due also when
  // nothing is held yet (JSS endpoints, amplification_guard.hpp).
  void send_challenge(const Ipv4Endpoint& to, Framing framing, bool at_first_contact = false);
  // A command from an unverified endpoint not delivered (its reply could not be sent): a line, limited.
  void refuse_command(const Ipv4Endpoint& from, std::uint16_t code, const AmplificationGuard& guard);
  // A line for each endpoint whose held replies expired, limited.
  void report_expired(const std::vector<AmplificationGuard::Expired>& expired, const AmplificationGuard& guard);
  void sync_amplification_counters();
  // A message for a node of another subsystem whose route we know, from a
  // node heard directly at `from`: sent on, in the framing that node speaks.
  void relay(const Ipv4Endpoint& from, const Header& header, std::span<const std::uint8_t> packet);
  // Whether a broadcast to `to` goes to `peer`: a subsystem's broadcasts only
  // to nodes of that subsystem (a peer not heard yet may be of any: none,
  // unless options_.broadcast_to_unheard_peers).
  bool broadcast_reaches(const Address& to, const Peer& peer) const;
  void schedule_expiry();

  boost::asio::io_context& io_;
  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  UdpLinkOptions options_;
  rt::LogFn log_;
  std::unique_ptr<Socket> main_;
  // Bound to a group (RA, JSS) when the main socket is bound to one address.
  std::vector<std::unique_ptr<Socket>> group_sockets_;
  RouteTable routes_;
  AmplificationGuard guard_;
  RouteTable jss_routes_;
  AmplificationGuard jss_guard_;
  PacketHandler handler_;
  JssPacketHandler jss_handler_;
  UdpLinkCounters counters_;
  rt::TimerId expiry_timer_ = rt::kNoTimer;
  // Lines a flood repeats: per drop reason, and new routes (10 per window).
  rt::RepeatedLines repeated_lines_;
  // Rate limit of drop logs: one line per reason per second.
  std::uint16_t local_port_ = 0;  // the bound port (options_.bind.port may be 0: any)
  std::size_t receive_buffer_bytes_ = 0;
  bool closed_ = false;
  // Completion handlers can run after the link is destroyed (the io_context
  // outlives it); they hold a weak reference to this and do nothing once it expires.
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace jaus::transport
