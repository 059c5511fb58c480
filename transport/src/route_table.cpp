#include "jaus/transport/route_table.hpp"

#include <algorithm>

namespace jaus::transport {

void RouteTable::add_static_peer(const Ipv4Endpoint& endpoint, Framing framing) {
  auto [it, inserted] = peers_.try_emplace(endpoint);
  if (!inserted && !it->second.is_static) --learnt_peers_;
  const std::size_t routes = it->second.routes;
  const auto subsystems = it->second.subsystems;
  it->second = Peer{endpoint, framing, true, {}, routes, subsystems};
}

void RouteTable::erase_route(std::map<std::uint16_t, Route>::iterator route) {
  const auto peer = peers_.find(route->second.endpoint);
  routes_.erase(route);
  if (peer == peers_.end()) return;
  if (peer->second.routes > 0) --peer->second.routes;
  recount_subsystems(peer->second);
}

void RouteTable::recount_subsystems(Peer& peer) const {
  // Rare (a route replaced, moved or expired): a walk over at most max_entries routes.
  peer.subsystems.reset();
  for (const auto& [k, route] : routes_)
    if (route.endpoint == peer.endpoint) peer.subsystems.set(k >> 8);
}

Learnt RouteTable::learn(std::uint8_t subsystem, std::uint8_t node, const Ipv4Endpoint& from, Framing framing,
                         rt::TimePoint now) {
  const std::uint16_t k = key(subsystem, node);
  auto peer = peers_.find(from);
  if (auto route = routes_.find(k); route != routes_.end() && route->second.endpoint != from) {
    const bool same_host = route->second.endpoint.address == from.address;
    const bool configured = peer != peers_.end() && peer->second.is_static;
    const bool old_silent = now - route->second.last_heard >= options_.move_after_silence;
    if (configured && peer->second.routes > 0 && !same_host && !old_silent) {
      ++counters_.relayed_copies;
      return Learnt::relayed_copy;
    }
    if (!same_host && !configured && !old_silent) {
      ++counters_.claims_refused;
      return Learnt::claim_refused;
    }
  }
  if (peer == peers_.end()) {
    if (learnt_peers_ >= options_.max_entries) {
      ++counters_.rejected_full;
      return Learnt::rejected;
    }
    peer = peers_.emplace(from, Peer{from, framing, false, now, 0, {}}).first;
    ++learnt_peers_;
  }
  peer->second.framing = framing;  // answer each peer the way it speaks
  peer->second.last_heard = now;

  Learnt result = Learnt::new_route;
  if (auto route = routes_.find(k); route != routes_.end()) {
    route->second.last_heard = now;
    if (route->second.endpoint == from) return Learnt::known;
    erase_route(route);  // the node restarted elsewhere (allowed above): the newest source wins
    ++counters_.moved;
    result = Learnt::moved;
  } else {
    ++counters_.learnt;
  }
  if (peer->second.routes >= options_.max_routes_per_endpoint) {
    auto oldest = routes_.end();
    for (auto it = routes_.begin(); it != routes_.end(); ++it)
      if (it->second.endpoint == from && (oldest == routes_.end() || it->second.last_heard < oldest->second.last_heard))
        oldest = it;
    if (oldest != routes_.end()) erase_route(oldest);
    ++counters_.replaced;
  } else if (routes_.size() >= options_.max_entries) {
    ++counters_.rejected_full;
    return Learnt::rejected;
  }
  routes_.emplace(k, Route{from, now});
  ++peer->second.routes;
  peer->second.subsystems.set(subsystem);
  return result;
}

std::optional<Peer> RouteTable::route(std::uint8_t subsystem, std::uint8_t node) const {
  const auto route = routes_.find(key(subsystem, node));
  if (route == routes_.end()) return std::nullopt;
  const auto peer = peers_.find(route->second.endpoint);
  if (peer == peers_.end()) return std::nullopt;
  return peer->second;
}

void RouteTable::expire(rt::TimePoint now) {
  for (auto it = routes_.begin(); it != routes_.end();) {
    auto next = std::next(it);
    if (now - it->second.last_heard > options_.route_timeout) {
      erase_route(it);
      ++counters_.expired;
    }
    it = next;
  }
  for (auto it = peers_.begin(); it != peers_.end();) {
    if (!it->second.is_static && it->second.routes == 0 && now - it->second.last_heard > options_.route_timeout) {
      it = peers_.erase(it);
      --learnt_peers_;
    } else {
      ++it;
    }
  }
}

}  // namespace jaus::transport
