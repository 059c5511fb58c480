#include "jaus/transport/route_table.hpp"

#include <algorithm>
#include <vector>

namespace jaus::transport {

void RouteTable::add_static_peer(const Ipv4Endpoint& endpoint, Framing framing) {
  auto [it, inserted] = peers_.try_emplace(endpoint);
  if (!inserted && !it->second.is_static) --learnt_peers_;
  const std::size_t routes = it->second.routes;
  const auto subsystems = it->second.subsystems;
  it->second = Peer{endpoint, framing, true, {}, routes, subsystems};
}

void RouteTable::erase_route(std::map<std::uint32_t, Route>::iterator route) {
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
    if (route.endpoint == peer.endpoint) mark_subsystem(peer, k >> 8);
}

bool RouteTable::holds_pinned_route(const Ipv4Endpoint& endpoint) const {
  if (!holds_state_) return false;
  // An endpoint holds a few routes at most; the scan stops once it saw them
  // all, and asks the node (which looks through its components' holders and
  // connections) only about those.
  const auto peer = peers_.find(endpoint);
  std::size_t unseen = peer == peers_.end() ? 0 : peer->second.routes;
  for (auto it = routes_.begin(); unseen > 0 && it != routes_.end(); ++it) {
    if (it->second.endpoint != endpoint) continue;
    if (pinned(it->first)) return true;
    --unseen;
  }
  return false;
}

void RouteTable::erase_peer(std::map<Ipv4Endpoint, Peer>::iterator peer) {
  const Ipv4Endpoint endpoint = peer->first;
  for (auto it = routes_.begin(); it != routes_.end();) {
    auto next = std::next(it);
    if (it->second.endpoint == endpoint) routes_.erase(it);
    it = next;
  }
  peers_.erase(peer);
  --learnt_peers_;
  if (forgotten_) forgotten_(endpoint);
}

bool RouteTable::room_for_endpoint_of(std::uint32_t address) {
  // The map orders endpoints by address, then port: an address's endpoints are one range.
  const auto first = peers_.lower_bound(Ipv4Endpoint{address, 0});
  const auto last = peers_.upper_bound(Ipv4Endpoint{address, 0xFFFF});
  std::size_t learnt = 0;
  for (auto it = first; it != last; ++it) learnt += !it->second.is_static;
  if (learnt < options_.max_endpoints_per_address) return true;
  // Only when an address is at its share (a flood of ports, or many short
  // tool runs): the least recently heard endpoint without state gives way.
  std::vector<std::map<Ipv4Endpoint, Peer>::iterator> candidates;
  for (auto it = first; it != last; ++it)
    if (!it->second.is_static) candidates.push_back(it);
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) { return a->second.last_heard < b->second.last_heard; });
  for (const auto& candidate : candidates) {
    if (holds_pinned_route(candidate->first)) continue;
    erase_peer(candidate);
    ++counters_.endpoints_replaced;
    return true;
  }
  return false;
}

Learnt RouteTable::learn(std::uint16_t subsystem, std::uint8_t node, const Ipv4Endpoint& from, Framing framing,
                         rt::TimePoint now) {
  const std::uint32_t k = key(subsystem, node);
  auto peer = peers_.find(from);
  // The claim check comes first: whether or not the table has room, a known
  // ID is never taken by a host the rules refuse.
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
    // Another address that the silence rules would let in: the one case the
    // node is asked (rare), since an ID holding state never leaves its host.
    if (!same_host && pinned(k)) {
      ++counters_.claims_refused;
      ++counters_.pinned_claims_refused;
      return Learnt::claim_refused;
    }
  }
  if (peer == peers_.end()) {
    if (!room_for_endpoint_of(from.address)) {
      ++counters_.rejected_per_address;
      return Learnt::rejected;
    }
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
  auto existing = routes_.find(k);
  if (existing != routes_.end() && existing->second.endpoint == from) {
    existing->second.last_heard = now;
    return Learnt::known;
  }
  if (peer->second.routes >= options_.max_routes_per_endpoint) {
    // The endpoint's oldest route without state gives way to its newest; a
    // route holding state stays (else its ID would be free to claim).
    std::vector<std::map<std::uint32_t, Route>::iterator> own;
    for (auto it = routes_.begin(); it != routes_.end(); ++it)
      if (it->second.endpoint == from) own.push_back(it);
    std::sort(own.begin(), own.end(),
              [](const auto& x, const auto& y) { return x->second.last_heard < y->second.last_heard; });
    auto oldest = routes_.end();
    for (const auto& it : own)
      if (!pinned(it->first)) {
        oldest = it;
        break;
      }
    if (oldest == routes_.end()) {
      ++counters_.rejected_full;
      return Learnt::rejected;
    }
    erase_route(oldest);
    ++counters_.replaced;
  } else if (existing == routes_.end() && routes_.size() >= options_.max_entries) {
    ++counters_.rejected_full;
    return Learnt::rejected;
  }
  if (existing != routes_.end()) {
    erase_route(existing);  // the node restarted elsewhere (allowed above): the newest source wins
    ++counters_.moved;
    result = Learnt::moved;
  } else {
    ++counters_.learnt;
  }
  routes_.emplace(k, Route{from, now});
  ++peer->second.routes;
  mark_subsystem(peer->second, subsystem);
  return result;
}

void RouteTable::reserve(std::uint16_t subsystem, std::uint8_t node, std::uint32_t address, rt::TimePoint now) {
  // Port 0 is no sender's source port: the route names the host only, and no
  // peer endpoint exists for it (route() answers nullopt, nothing is sent).
  routes_.try_emplace(key(subsystem, node), Route{Ipv4Endpoint{address, 0}, now});
}

std::optional<std::uint32_t> RouteTable::address_of(std::uint16_t subsystem, std::uint8_t node) const {
  const auto route = routes_.find(key(subsystem, node));
  if (route == routes_.end()) return std::nullopt;
  return route->second.endpoint.address;
}

std::optional<Peer> RouteTable::route(std::uint16_t subsystem, std::uint8_t node) const {
  const auto route = routes_.find(key(subsystem, node));
  if (route == routes_.end()) return std::nullopt;
  const auto peer = peers_.find(route->second.endpoint);
  if (peer == peers_.end()) return std::nullopt;
  return peer->second;
}

void RouteTable::expire(rt::TimePoint now) {
  for (auto it = routes_.begin(); it != routes_.end();) {
    auto next = std::next(it);
    // A route holding state never expires: its ID would be free to claim.
    if (now - it->second.last_heard > options_.route_timeout && !pinned(it->first)) {
      erase_route(it);
      ++counters_.expired;
    }
    it = next;
  }
  for (auto it = peers_.begin(); it != peers_.end();) {
    if (!it->second.is_static && it->second.routes == 0 && now - it->second.last_heard > options_.route_timeout) {
      const Ipv4Endpoint endpoint = it->first;
      it = peers_.erase(it);
      --learnt_peers_;
      if (forgotten_) forgotten_(endpoint);
    } else {
      ++it;
    }
  }
}

}  // namespace jaus::transport
