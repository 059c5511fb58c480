// Routes learnt from where datagrams come from, static peers, expiry and the
// bound on entries, under virtual time.
#include <gtest/gtest.h>

#include "jaus/base/virtual_time.hpp"
#include "jaus/transport/route_table.hpp"

namespace jaus::transport {
namespace {

using namespace std::chrono_literals;

const Ipv4Endpoint kPeerA{0x7F000002, 3794};  // 127.0.0.2:3794
const Ipv4Endpoint kPeerB{0x7F000003, 3794};

TEST(RouteTable, LearnsWhereANodeLivesAndHowItSpeaks) {
  rt::VirtualTime time;
  RouteTable table;
  EXPECT_FALSE(table.route(2, 1));
  table.learn(2, 1, kPeerA, Framing::judp, time.now());
  auto route = table.route(2, 1);
  ASSERT_TRUE(route);
  EXPECT_EQ(route->endpoint, kPeerA);
  EXPECT_EQ(route->framing, Framing::judp);
  table.learn(2, 1, kPeerA, Framing::opc, time.now());  // the peer switched framing: follow it
  EXPECT_EQ(table.route(2, 1)->framing, Framing::opc);
  const Ipv4Endpoint restarted{kPeerA.address, 40001};
  EXPECT_EQ(table.learn(2, 1, restarted, Framing::opc, time.now()), Learnt::moved);  // same host, new port
  EXPECT_EQ(table.route(2, 1)->endpoint, restarted);
  EXPECT_EQ(table.counters().learnt, 1u);
  EXPECT_EQ(table.counters().moved, 1u);
  EXPECT_EQ(table.peers().size(), 2u);
}

// Nobody steers a node's replies away by claiming its ID from another host
// while the node is alive; a restart, a silent node or a configured peer may.
TEST(RouteTable, AnotherHostClaimingALiveNodesIdIsRefused) {
  rt::VirtualTime time;
  RouteTable table;  // moves from another host after 3 s of silence
  const Ipv4Endpoint kConfigured{0x7F000004, 3794};
  table.add_static_peer(kConfigured, Framing::judp);
  table.learn(2, 1, kPeerA, Framing::judp, time.now());
  time.advance(2s);
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::judp, time.now()), Learnt::claim_refused);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerA);
  EXPECT_EQ(table.counters().claims_refused, 1u);
  EXPECT_EQ(table.peers().size(), 2u);  // the claimant is not even remembered
  // A refused claim does not keep the old route alive: 3 s after A was last heard, B may take it.
  time.advance(900ms);
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::judp, time.now()), Learnt::claim_refused);
  time.advance(100ms);
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::judp, time.now()), Learnt::moved);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerB);
  // A configured peer is believed at once.
  EXPECT_EQ(table.learn(2, 1, kConfigured, Framing::judp, time.now()), Learnt::moved);
  EXPECT_EQ(table.route(2, 1)->endpoint, kConfigured);
  EXPECT_EQ(table.counters().moved, 2u);
  EXPECT_EQ(table.counters().claims_refused, 2u);
}

// A configured peer that is another node relays (udp_link.hpp): its copy of a
// message from a node we hear directly moves nothing and is dropped.
TEST(RouteTable, AConfiguredRelaysCopyOfANodeHeardDirectlyMovesNothing) {
  rt::VirtualTime time;
  RouteTable table;
  const Ipv4Endpoint kRelay{0x7F000004, 3794};
  const Ipv4Endpoint kRestarted{0x7F000005, 3794};
  table.add_static_peer(kRelay, Framing::opc);
  table.add_static_peer(kRestarted, Framing::opc);
  table.learn(2, 1, kRelay, Framing::opc, time.now());  // the relay is node 2.1
  table.learn(9, 1, kPeerA, Framing::opc, time.now());  // an OCU, heard directly
  EXPECT_EQ(table.learn(9, 1, kRelay, Framing::opc, time.now()), Learnt::relayed_copy);
  EXPECT_EQ(table.route(9, 1)->endpoint, kPeerA);
  EXPECT_EQ(table.counters().relayed_copies, 1u);
  EXPECT_FALSE(table.peers().at(kRelay).hosts_subsystem(9));
  // A configured endpoint that is no other node is still believed at once (a restart).
  EXPECT_EQ(table.learn(9, 1, kRestarted, Framing::opc, time.now()), Learnt::moved);
  // Once the OCU is silent, its route may move through the relay.
  time.advance(3s);
  EXPECT_EQ(table.learn(9, 1, kRelay, Framing::opc, time.now()), Learnt::moved);
}

// Each endpoint knows the subsystems of its routes: a subsystem's broadcasts go to its own nodes only.
TEST(RouteTable, EachPeerKnowsTheSubsystemsItHosts) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{256, 2, 10s});
  table.add_static_peer(kPeerB, Framing::opc);
  EXPECT_TRUE(table.peers().at(kPeerB).subsystems.none());  // not heard yet: unknown
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  table.learn(1, 1, kPeerA, Framing::opc, time.now() + 1s);  // relayed through A
  EXPECT_TRUE(table.peers().at(kPeerA).hosts_subsystem(2));
  EXPECT_TRUE(table.peers().at(kPeerA).hosts_subsystem(1));
  time.advance(2s);
  table.learn(3, 1, kPeerA, Framing::opc, time.now());  // two routes per endpoint: 2.1, the oldest, gives way
  EXPECT_FALSE(table.peers().at(kPeerA).hosts_subsystem(2));
  EXPECT_TRUE(table.peers().at(kPeerA).hosts_subsystem(3));
  table.learn(3, 1, kPeerB, Framing::opc, time.now() + 3s);  // moved (a configured peer)
  EXPECT_FALSE(table.peers().at(kPeerA).hosts_subsystem(3));
  EXPECT_TRUE(table.peers().at(kPeerB).hosts_subsystem(3));
  time.advance(20s);
  table.expire(time.now());
  EXPECT_TRUE(table.peers().at(kPeerB).subsystems.none());  // static, its route silent
}

TEST(RouteTable, SilentLearntRoutesExpireStaticPeersStay) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{256, 4, 10s});
  table.add_static_peer(kPeerB, Framing::judp);
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  table.learn(3, 1, kPeerB, Framing::judp, time.now());
  time.advance(9s);
  table.expire(time.now());
  EXPECT_TRUE(table.route(2, 1));
  EXPECT_TRUE(table.route(3, 1));
  time.advance(2s);
  table.expire(time.now());
  EXPECT_FALSE(table.route(2, 1));
  EXPECT_FALSE(table.route(3, 1));  // silent too, though its endpoint stays
  ASSERT_EQ(table.peers().size(), 1u);
  EXPECT_TRUE(table.peers().begin()->second.is_static);
  EXPECT_EQ(table.counters().expired, 2u);
}

TEST(RouteTable, AFloodOfNewSourcesCannotPushOutKnownPeers) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{4, 4, 30s});
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  for (std::uint32_t i = 0; i < 1000; ++i)
    table.learn(static_cast<std::uint8_t>(10 + i % 200), 1, Ipv4Endpoint{0x0A000000 + i, 3794}, Framing::opc,
                time.now());
  EXPECT_LE(table.peers().size(), 4u);
  EXPECT_LE(table.route_count(), 4u);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerA);
  EXPECT_GT(table.counters().rejected_full, 0u);
}

TEST(RouteTable, OneEndpointClaimingManyNodesKeepsOnlyItsNewest) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{256, 2, 30s});
  for (std::uint8_t subsystem = 10; subsystem < 200; ++subsystem) {
    table.learn(subsystem, 1, kPeerB, Framing::opc, time.now());
    time.advance(1ms);
  }
  EXPECT_EQ(table.route_count(), 2u);
  EXPECT_TRUE(table.route(199, 1));
  EXPECT_TRUE(table.route(198, 1));
  table.learn(2, 1, kPeerA, Framing::opc, time.now());  // a newcomer still finds room
  EXPECT_TRUE(table.route(2, 1));
  EXPECT_EQ(table.peers().at(kPeerB).routes, 2u);
}

// Issue 28: an ID holding state (a controller, an emergency holder) never
// moves to another host, whatever its silence, and never expires; its own
// host on a new port (the OCU restarted) may still take it.
TEST(RouteTable, APinnedIdNeverMovesToAnotherHostNorExpires) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{.route_timeout = 30s});
  bool holds = true;
  int asked = 0;
  table.pin_while([&](std::uint8_t subsystem, std::uint8_t node) {
    ++asked;
    return holds && subsystem == 2 && node == 1;
  });
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  for (int i = 0; i < 100; ++i) table.learn(2, 1, kPeerA, Framing::opc, time.now());
  EXPECT_EQ(asked, 0);  // not per datagram
  time.advance(10min);
  table.expire(time.now());
  ASSERT_TRUE(table.route(2, 1));  // silent for 10 min, still held
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::opc, time.now()), Learnt::claim_refused);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerA);
  EXPECT_EQ(table.counters().pinned_claims_refused, 1u);
  // A configured peer on another host does not take it either.
  const Ipv4Endpoint kConfigured{0x7F000004, 3794};
  table.add_static_peer(kConfigured, Framing::opc);
  EXPECT_EQ(table.learn(2, 1, kConfigured, Framing::opc, time.now()), Learnt::claim_refused);
  // The operator's OCU restarted on the same host: it may move it (and then release).
  const Ipv4Endpoint restarted{kPeerA.address, 40001};
  EXPECT_EQ(table.learn(2, 1, restarted, Framing::opc, time.now()), Learnt::moved);
  EXPECT_EQ(table.route(2, 1)->endpoint, restarted);
  // Released: today's rules again (expiry, then anyone).
  holds = false;
  time.advance(31s);
  table.expire(time.now());
  EXPECT_FALSE(table.route(2, 1));
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::opc, time.now()), Learnt::new_route);
}

// Issue 42: a holder restored at start is bound to its host before it is
// heard: its first datagram from that host (any port) takes the route, the
// ID from another host is refused however long it waits, and nothing is sent
// to the reservation itself (no port known).
TEST(RouteTable, AReservedIdIsTheReservedHostsFromTheStart) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{.route_timeout = 30s});
  bool holds = true;
  table.pin_while([&](std::uint8_t subsystem, std::uint8_t node) { return holds && subsystem == 2 && node == 1; });
  table.reserve(2, 1, kPeerA.address, time.now());
  EXPECT_FALSE(table.route(2, 1));  // nowhere to send yet
  EXPECT_EQ(table.address_of(2, 1), kPeerA.address);
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::opc, time.now()), Learnt::claim_refused);  // at once
  time.advance(10min);
  table.expire(time.now());
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::opc, time.now()), Learnt::claim_refused);  // and ever after
  EXPECT_EQ(table.counters().pinned_claims_refused, 1u);
  // The holder is back, from its host on a new port.
  const Ipv4Endpoint back{kPeerA.address, 40123};
  EXPECT_EQ(table.learn(2, 1, back, Framing::judp, time.now()), Learnt::moved);
  ASSERT_TRUE(table.route(2, 1));
  EXPECT_EQ(table.route(2, 1)->endpoint, back);
  // A reservation does not displace a route already learnt.
  table.reserve(2, 1, kPeerB.address, time.now());
  EXPECT_EQ(table.route(2, 1)->endpoint, back);
  // Unheld, an unheard reservation expires like a silent route.
  holds = false;
  table.reserve(3, 1, kPeerB.address, time.now());
  time.advance(31s);
  table.expire(time.now());
  EXPECT_FALSE(table.address_of(3, 1));
}

TEST(RouteTable, AnUnpinnedSilentIdStillMovesAfterTheSilence) {
  rt::VirtualTime time;
  RouteTable table;
  table.pin_while([](std::uint8_t, std::uint8_t node) { return node == 9; });
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  time.advance(3s);
  EXPECT_EQ(table.learn(2, 1, kPeerB, Framing::opc, time.now()), Learnt::moved);
}

// One host with 256 ports cannot fill the learnt endpoints: its ninth port
// replaces its least recently heard one, and an OCU on another host is recorded.
TEST(RouteTable, OneHostWithManyPortsCannotFillTheTable) {
  rt::VirtualTime time;
  RouteTable table;  // 256 entries, 8 endpoints per address
  std::vector<Ipv4Endpoint> forgotten;
  table.on_forgotten([&](const Ipv4Endpoint& e) { forgotten.push_back(e); });
  const std::uint32_t flooder = 0x0A000009;
  for (std::uint16_t port = 1000; port < 1256; ++port) {
    table.learn(static_cast<std::uint8_t>(10 + port % 200), 1, Ipv4Endpoint{flooder, port}, Framing::opc, time.now());
    time.advance(1ms);
  }
  EXPECT_EQ(table.peers().size(), 8u);
  EXPECT_EQ(table.counters().endpoints_replaced, 248u);
  EXPECT_EQ(forgotten.size(), 248u);
  EXPECT_EQ(forgotten.front(), (Ipv4Endpoint{flooder, 1000}));  // least recently heard first
  EXPECT_LE(table.route_count(), 8u);
  EXPECT_EQ(table.learn(2, 1, kPeerA, Framing::opc, time.now()), Learnt::new_route);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerA);
}

// An endpoint holding state is never the one replaced; if all of an
// address's endpoints hold state, the newcomer is not recorded.
TEST(RouteTable, EndpointsHoldingStateAreNotReplaced) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{.max_endpoints_per_address = 2});
  table.pin_while([](std::uint8_t subsystem, std::uint8_t) { return subsystem < 10; });
  table.learn(2, 1, Ipv4Endpoint{kPeerA.address, 1}, Framing::opc, time.now());  // pinned, oldest
  time.advance(1s);
  table.learn(20, 1, Ipv4Endpoint{kPeerA.address, 2}, Framing::opc, time.now());
  time.advance(1s);
  // The third port replaces port 2 (no state), not port 1 (older, but holding state).
  EXPECT_EQ(table.learn(3, 1, Ipv4Endpoint{kPeerA.address, 3}, Framing::opc, time.now()), Learnt::new_route);
  EXPECT_TRUE(table.route(2, 1));
  EXPECT_FALSE(table.route(20, 1));
  EXPECT_EQ(table.counters().endpoints_replaced, 1u);
  // Both left hold state: a fourth port is not recorded.
  EXPECT_EQ(table.learn(30, 1, Ipv4Endpoint{kPeerA.address, 4}, Framing::opc, time.now()), Learnt::rejected);
  EXPECT_EQ(table.counters().rejected_per_address, 1u);
  EXPECT_FALSE(table.peers().contains(Ipv4Endpoint{kPeerA.address, 4}));
  // Another address is not affected.
  EXPECT_EQ(table.learn(30, 1, kPeerB, Framing::opc, time.now()), Learnt::new_route);
}

// An endpoint's newest route replaces its oldest one without state, never a pinned one.
TEST(RouteTable, AnEndpointsRouteHoldingStateIsNotReplacedByItsNewest) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{.max_routes_per_endpoint = 2});
  table.pin_while([](std::uint8_t subsystem, std::uint8_t) { return subsystem == 2; });
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  time.advance(1ms);
  table.learn(3, 1, kPeerA, Framing::opc, time.now());
  time.advance(1ms);
  table.learn(4, 1, kPeerA, Framing::opc, time.now());
  EXPECT_TRUE(table.route(2, 1));
  EXPECT_FALSE(table.route(3, 1));
  EXPECT_TRUE(table.route(4, 1));
}

// A full table records no newcomer, but the claim check still runs first.
TEST(RouteTable, AFullTableStillRefusesClaims) {
  rt::VirtualTime time;
  RouteTable table(RouteTableOptions{.max_entries = 2});
  table.learn(2, 1, kPeerA, Framing::opc, time.now());
  table.learn(3, 1, kPeerB, Framing::opc, time.now());
  const Ipv4Endpoint stranger{0x7F000009, 3794};
  EXPECT_EQ(table.learn(2, 1, stranger, Framing::opc, time.now()), Learnt::claim_refused);
  EXPECT_EQ(table.learn(4, 1, stranger, Framing::opc, time.now()), Learnt::rejected);
  EXPECT_EQ(table.route(2, 1)->endpoint, kPeerA);
  EXPECT_FALSE(table.route(4, 1));
}

}  // namespace
}  // namespace jaus::transport
