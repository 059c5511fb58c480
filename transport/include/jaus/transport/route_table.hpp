// Where other JAUS nodes live on the network. Sans-I/O: the UDP link feeds it
// what it receives and asks it where to send.
//
// A route (subsystem, node) -> endpoint is learnt from the source endpoint of
// every datagram a node sends, together with the framing it used, so each
// peer is answered the way it speaks. Static peers from the configuration are
// always there (broadcasts and not-yet-routed messages reach them). Learnt
// entries are forgotten after a silence of `route_timeout`; when the table is
// full, newcomers are not recorded, so a flood of forged sources cannot push
// out peers already known. One endpoint is one node in RA 3.x, so a single
// endpoint may hold only a few routes (its newest replace its oldest): a flood
// of forged JAUS sources from one socket cannot fill the table either.
//
// Learnt endpoints are bounded per IP address (`max_endpoints_per_address`):
// a new port of an address that already has that many replaces the address's
// least recently heard endpoint whose routes hold no state (its routes go);
// if all of them hold state the newcomer is not recorded. One host with 256
// ports cannot fill the table, and hundreds of short-lived tools run from one
// host (each a new port) keep working.
//
// Who may take over a node's ID (a claim: the ID heard from a new endpoint):
// - the same IP address on a new port: the tool or OCU restarted on the same
//   host. Always allowed, pinned or not: it is how an operator whose OCU
//   restarted releases its control or clears its own emergency hold. Telling
//   it apart from a hijack by the address only is deliberate: another process
//   on the operator's own host can reach the node as that host anyway, and an
//   off-path host cannot receive the replies to a forged local address.
// - another IP address, for an ID that holds state at this node (control, an
//   emergency hold, a service connection: the node answers through
//   pin_while()): never, whatever the silence, and such a route never expires
//   while the state lasts, so nobody can claim a silent controller's or a
//   one-shot emergency holder's ID and act in its name (Clear Emergency).
// - another IP address, for an ID holding no state: a configured peer at
//   once, anyone else once the old endpoint has been silent for
//   `move_after_silence`; otherwise the claim is refused, so nobody can steer
//   a live node's traffic away by forging its ID.
// The claim check runs before anything is recorded, so a full table never
// skips it.
//
// Subsystems are 16-bit so the same rules serve SAE JAUS (AS5669A) IDs: the
// UDP link keeps a second table for JSS nodes (subsystem 1..65534, node),
// whose peers' framing is as5669a. RA subsystems are 1..254. A configured peer that is already another live node's endpoint
// is relaying (udp_link.hpp): what it relays for a node heard directly is a
// copy, dropped without moving the route.
#pragma once

#include <bitset>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>

#include "jaus/base/time.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::transport {

struct Peer {
  Ipv4Endpoint endpoint;
  Framing framing = Framing::opc;
  bool is_static = false;
  rt::TimePoint last_heard{};
  std::size_t routes = 0;  // routes through this endpoint
  // The RA subsystems of those routes: a subsystem's broadcasts go only to its
  // own nodes (docs/wire-format.md, "Liveness and discovery"). JSS subsystems
  // above 255 are not recorded (JSS broadcasts go to the group and static peers).
  std::bitset<256> subsystems;
  bool hosts_subsystem(std::uint8_t subsystem) const { return subsystems.test(subsystem); }
};

struct RouteTableOptions {
  std::size_t max_entries = 256;  // learnt routes, and learnt peer endpoints, each
  std::size_t max_routes_per_endpoint = 4;
  rt::Duration route_timeout = std::chrono::seconds(30);
  rt::Duration move_after_silence = std::chrono::seconds(3);
  std::size_t max_endpoints_per_address = 8;  // learnt endpoints (ports) of one IP address
};

// What learn() did, so the link can tell the operator about new and moved nodes.
// rejected: the source could not be recorded (table full, or its address has
// max_endpoints_per_address endpoints holding state): deliver it as unrecorded.
// claim_refused: the node is heard from another live endpoint, or its ID
// holds state and the claim comes from another address; drop the datagram.
// relayed_copy: a configured peer that is another node relayed a message of a
// node heard directly: drop the copy, keep the direct route.
enum class Learnt : std::uint8_t { known, new_route, moved, rejected, claim_refused, relayed_copy };

struct RouteTableCounters {
  std::uint64_t learnt = 0;          // new routes
  std::uint64_t moved = 0;           // a node heard from a new endpoint
  std::uint64_t claims_refused = 0;  // a node's ID from another host while its endpoint is live or it is pinned
  std::uint64_t pinned_claims_refused = 0;  // ...of those, refused because the ID holds state
  std::uint64_t relayed_copies = 0;  // a configured relay's copy of a node heard directly
  std::uint64_t rejected_full = 0;   // newcomers not recorded: a table full
  std::uint64_t rejected_per_address = 0;  // new endpoints not recorded: their address's all hold state
  std::uint64_t endpoints_replaced = 0;    // an address's least recently heard endpoint gave way to a new one
  std::uint64_t replaced = 0;        // an endpoint's oldest route gave way to its newest
  std::uint64_t expired = 0;
};

class RouteTable {
 public:
  explicit RouteTable(RouteTableOptions options = {}) : options_(options) {}

  // Whether a node ID holds state at this node (control, an emergency hold, a
  // service connection): such a route never moves to another IP address and
  // never expires (see above). Asked only on a claim from another address, on
  // expiry of a silent route and when an endpoint or route must give way,
  // never per datagram. Unset: nothing is pinned.
  using HoldsState = std::function<bool(std::uint16_t subsystem, std::uint8_t node)>;
  void pin_while(HoldsState holds_state) { holds_state_ = std::move(holds_state); }
  // Told when a learnt endpoint is forgotten (expired or replaced), so what
  // the link keeps per endpoint (its verification) goes with it.
  using Forgotten = std::function<void(const Ipv4Endpoint& endpoint)>;
  void on_forgotten(Forgotten forgotten) { forgotten_ = std::move(forgotten); }

  void add_static_peer(const Ipv4Endpoint& endpoint, Framing framing);
  // A datagram from `from`, framed in `framing`, whose JAUS source is subsystem.node.
  Learnt learn(std::uint16_t subsystem, std::uint8_t node, const Ipv4Endpoint& from, Framing framing,
               rt::TimePoint now);
  // Binds (subsystem, node) to an IP address before it is heard: a holder
  // of state restored at start (an emergency hold persisted with its host,
  // issue 42). Until the ID is heard, nothing is sent to it (no port is
  // known: route() is nullopt); the ID heard from that address (any port)
  // takes the route as a restarted peer does, and a claim from another
  // address is refused while the ID holds state (pin_while), exactly as for
  // a live pinned route. Not counted against max_entries (holds are bounded
  // by the emergency latches). An ID with a route already keeps it.
  void reserve(std::uint16_t subsystem, std::uint8_t node, std::uint32_t address, rt::TimePoint now);
  // The IP address an ID is bound to: its learnt route's, or a reservation's.
  std::optional<std::uint32_t> address_of(std::uint16_t subsystem, std::uint8_t node) const;
  // Where (subsystem, node) lives, if known.
  std::optional<Peer> route(std::uint16_t subsystem, std::uint8_t node) const;
  // Every distinct peer endpoint (static and learnt), for broadcasts.
  const std::map<Ipv4Endpoint, Peer>& peers() const { return peers_; }
  // Forgets learnt routes and peers silent for longer than route_timeout.
  void expire(rt::TimePoint now);

  std::size_t route_count() const { return routes_.size(); }
  const RouteTableCounters& counters() const { return counters_; }

 private:
  static std::uint32_t key(std::uint16_t subsystem, std::uint8_t node) {
    return (static_cast<std::uint32_t>(subsystem) << 8) | node;
  }
  static void mark_subsystem(Peer& peer, std::uint32_t subsystem) {
    if (subsystem < peer.subsystems.size()) peer.subsystems.set(subsystem);
  }

  struct Route {
    Ipv4Endpoint endpoint;
    rt::TimePoint last_heard{};
  };
  void erase_route(std::map<std::uint32_t, Route>::iterator route);
  void recount_subsystems(Peer& peer) const;
  bool pinned(std::uint32_t k) const {
    return holds_state_ && holds_state_(static_cast<std::uint16_t>(k >> 8), static_cast<std::uint8_t>(k & 0xFF));
  }
  bool holds_pinned_route(const Ipv4Endpoint& endpoint) const;
  // Makes room for a new endpoint of `address` if it has its share: false if
  // every endpoint of the address holds state (the newcomer is not recorded).
  bool room_for_endpoint_of(std::uint32_t address);
  void erase_peer(std::map<Ipv4Endpoint, Peer>::iterator peer);

  RouteTableOptions options_;
  std::map<std::uint32_t, Route> routes_;         // (subsystem, node) -> endpoint
  std::map<Ipv4Endpoint, Peer> peers_;            // endpoint -> framing, liveness
  std::size_t learnt_peers_ = 0;
  RouteTableCounters counters_;
  HoldsState holds_state_;
  Forgotten forgotten_;
};

}  // namespace jaus::transport
