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
// A known node moves to a new endpoint only when the claim comes from the same
// IP address (a tool restarted on a new port), from a configured peer, or once
// its old endpoint has been silent for `move_after_silence`; any other host
// claiming its ID is refused, so nobody can steer a node's traffic away by
// forging its ID. A configured peer that is already another live node's
// endpoint is relaying (udp_link.hpp): what it relays for a node heard
// directly is a copy, dropped without moving the route.
#pragma once

#include <bitset>
#include <cstdint>
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
  // The subsystems of those routes: a subsystem's broadcasts go only to its
  // own nodes (jaus-wire-notes.md, "Liveness and discovery").
  std::bitset<256> subsystems;
  bool hosts_subsystem(std::uint8_t subsystem) const { return subsystems.test(subsystem); }
};

struct RouteTableOptions {
  std::size_t max_entries = 256;  // learnt routes, and learnt peer endpoints, each
  std::size_t max_routes_per_endpoint = 4;
  rt::Duration route_timeout = std::chrono::seconds(30);
  rt::Duration move_after_silence = std::chrono::seconds(3);
};

// What learn() did, so the link can tell the operator about new and moved nodes.
// claim_refused: the node is heard from another live endpoint; drop the datagram.
// relayed_copy: a configured peer that is another node relayed a message of a
// node heard directly: drop the copy, keep the direct route.
enum class Learnt : std::uint8_t { known, new_route, moved, rejected, claim_refused, relayed_copy };

struct RouteTableCounters {
  std::uint64_t learnt = 0;          // new routes
  std::uint64_t moved = 0;           // a node heard from a new endpoint
  std::uint64_t claims_refused = 0;  // a node's ID from another host while its endpoint is live
  std::uint64_t relayed_copies = 0;  // a configured relay's copy of a node heard directly
  std::uint64_t rejected_full = 0;   // newcomers not recorded
  std::uint64_t replaced = 0;        // an endpoint's oldest route gave way to its newest
  std::uint64_t expired = 0;
};

class RouteTable {
 public:
  explicit RouteTable(RouteTableOptions options = {}) : options_(options) {}

  void add_static_peer(const Ipv4Endpoint& endpoint, Framing framing);
  // A datagram from `from`, framed in `framing`, whose JAUS source is subsystem.node.
  Learnt learn(std::uint8_t subsystem, std::uint8_t node, const Ipv4Endpoint& from, Framing framing,
               rt::TimePoint now);
  // Where (subsystem, node) lives, if known.
  std::optional<Peer> route(std::uint8_t subsystem, std::uint8_t node) const;
  // Every distinct peer endpoint (static and learnt), for broadcasts.
  const std::map<Ipv4Endpoint, Peer>& peers() const { return peers_; }
  // Forgets learnt routes and peers silent for longer than route_timeout.
  void expire(rt::TimePoint now);

  std::size_t route_count() const { return routes_.size(); }
  const RouteTableCounters& counters() const { return counters_; }

 private:
  static std::uint16_t key(std::uint8_t subsystem, std::uint8_t node) {
    return static_cast<std::uint16_t>((subsystem << 8) | node);
  }

  struct Route {
    Ipv4Endpoint endpoint;
    rt::TimePoint last_heard{};
  };
  void erase_route(std::map<std::uint16_t, Route>::iterator route);
  void recount_subsystems(Peer& peer) const;

  RouteTableOptions options_;
  std::map<std::uint16_t, Route> routes_;         // (subsystem, node) -> endpoint
  std::map<Ipv4Endpoint, Peer> peers_;            // endpoint -> framing, liveness
  std::size_t learnt_peers_ = 0;
  RouteTableCounters counters_;
};

}  // namespace jaus::transport
