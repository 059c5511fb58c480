// Issue 28, the transport's part: IDs tied to their senders (pinned routes,
// endpoints bounded per address, no check skipped on a full table), the
// sender's standing (trusted, observer, unrecorded) and no amplification
// toward unverified endpoints. The link runs on virtual time and takes its
// datagrams through receive_datagram(); what it sends goes to real sockets on
// loopback, read back at once (loopback delivers during send).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/asio/ip/udp.hpp>
#include <deque>
#include <functional>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/node/ack_reply.hpp"
#include "jaus/transport/amplification_guard.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::transport {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

constexpr std::uint32_t kLoopback1 = 0x7F000001;
const Address kManager{1, 1, 1, 1};
const Address kOcu{2, 1, 40, 1};

// A message of `payload_size` bytes (zeros) from `from` to `to`.
std::vector<std::uint8_t> message(const Address& from, const Address& to, std::uint16_t code,
                                  std::size_t payload_size = 0) {
  std::vector<std::uint8_t> out(kHeaderSize + payload_size, 0);
  Header h;
  h.command_code = code;
  h.source = from;
  h.destination = to;
  h.data_size = static_cast<std::uint16_t>(payload_size);
  encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(out.data(), kHeaderSize));
  return out;
}

std::vector<std::uint8_t> opc(std::span<const std::uint8_t> packet) {
  const FramePrefix prefix = frame_prefix(Framing::opc, packet.size());
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), packet.begin(), packet.end());
  return out;
}

std::vector<std::uint8_t> query_from(const Address& from) {
  return opc(message(from, kManager, msg::QueryIdentification::code, 1));  // 8 + 16 + 1 bytes
}

Ipv4Endpoint endpoint_of(const udp::socket& socket) {
  const auto e = socket.local_endpoint();
  return Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
}

struct Delivered {
  Header header;
  rt::SenderStanding standing;
};

class HostileNetwork : public ::testing::Test {
 protected:
  void SetUp() override { open({}); }

  void open(UdpLinkOptions options) {
    options.subsystem = 1;
    options.node = 1;
    options.bind = Ipv4Endpoint{kLoopback1, 0};
    options.challenge_key = std::array<std::uint64_t, 2>{1, 2};
    auto opened = UdpLink::open(io, time, time, options,
                                [this](rt::LogLevel, const std::string& line) { logs.push_back(line); });
    ASSERT_TRUE(opened) << opened.error().message();
    link = std::move(*opened);
    link->on_packet([this](const PacketView& p, Framing, rt::SenderStanding standing) {
      delivered.push_back({p.header, standing});
      if (reply) reply(p.header);
    });
    link->start();
  }

  // A socket on loopback playing a peer: what the link sends to it can be read back.
  udp::socket& peer_socket(const char* address = "127.0.0.1") {
    auto& socket = sockets.emplace_back(io, udp::endpoint(asio::ip::make_address_v4(address), 0));
    socket.non_blocking(true);
    return socket;
  }
  static std::vector<std::vector<std::uint8_t>> take(udp::socket& socket) {
    std::vector<std::vector<std::uint8_t>> out;
    std::array<std::uint8_t, 9000> buffer;
    for (;;) {
      boost::system::error_code ec;
      udp::endpoint from;
      const std::size_t size = socket.receive_from(asio::buffer(buffer), from, 0, ec);
      if (ec) return out;
      out.emplace_back(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(size));
    }
  }
  static std::size_t bytes_of(const std::vector<std::vector<std::uint8_t>>& datagrams) {
    std::size_t n = 0;
    for (const auto& d : datagrams) n += d.size();
    return n;
  }
  // The node answering every Query Identification with a large report (a
  // Report Image-sized answer to a 25-byte query).
  void answer_with(std::size_t payload_size) {
    reply = [this, payload_size](const Header& query) {
      if (query.command_code != msg::QueryIdentification::code) return;
      const auto packet = message(kManager, query.source, 0x4807, payload_size);
      link->transmit(*decode_header(packet), packet);
    };
  }
  // The ACK a peer's node sends for `challenge` (node::ack_reply_for, as Node does).
  static std::vector<std::uint8_t> ack_of(const Header& challenge, std::uint16_t sequence_delta = 0) {
    Header ack = *node::ack_reply_for(challenge, challenge.destination, node::Delivery::delivered);
    ack.sequence = static_cast<std::uint16_t>(ack.sequence + sequence_delta);
    std::vector<std::uint8_t> packet(kHeaderSize);
    encode_header_unchecked(ack, std::span<std::uint8_t, kHeaderSize>(packet.data(), kHeaderSize));
    return opc(packet);
  }

  asio::io_context io;  // never run: the link's sends are synchronous, its receives injected
  rt::VirtualTime time;
  std::unique_ptr<UdpLink> link;
  std::vector<Delivered> delivered;
  std::function<void(const Header&)> reply;
  std::vector<std::string> logs;
  std::deque<udp::socket> sockets;
};

// ---- pinned IDs --------------------------------------------------------------

TEST_F(HostileNetwork, AForgedClaimOnAPinnedHoldersIdIsRefusedEvenAfterLongSilence) {
  bool holds = true;
  link->pin_routes_while([&](std::uint8_t subsystem, std::uint8_t node) { return holds && subsystem == 2 && node == 1; });
  const Ipv4Endpoint ocu{kLoopback1, 40000};
  link->receive_datagram(ocu, query_from(kOcu));  // e.g. a one-shot `jausctl emergency set`
  ASSERT_EQ(delivered.size(), 1u);
  time.advance(5min);  // far past move_after_silence and route_timeout: the expiry ran 300 times
  ASSERT_TRUE(link->routes().route(2, 1));
  const Ipv4Endpoint forger{0x7F000005, 40000};
  link->receive_datagram(forger, query_from(kOcu));  // e.g. Clear Emergency in the holder's name
  EXPECT_EQ(delivered.size(), 1u);
  EXPECT_EQ(link->counters().dropped_for(DropReason::route_claim), 1u);
  EXPECT_EQ(link->routes().counters().pinned_claims_refused, 1u);
  EXPECT_EQ(link->routes().route(2, 1)->endpoint, ocu);
  // The same host on a new port (the operator's OCU restarted) may take it, as trusted.
  const Ipv4Endpoint restarted{kLoopback1, 40001};
  link->receive_datagram(restarted, query_from(kOcu));
  ASSERT_EQ(delivered.size(), 2u);
  EXPECT_EQ(delivered.back().standing, rt::SenderStanding::trusted);
  EXPECT_EQ(link->routes().route(2, 1)->endpoint, restarted);
  // Once it holds nothing, a silent ID expires as before.
  holds = false;
  time.advance(31s);
  EXPECT_FALSE(link->routes().route(2, 1));
}

// Issue 42: a JSS operator's RA alias is the face's alone. An RA datagram
// naming an alias as its source (a forged Clear Emergency, Set Wrench Effort
// or Release in a JSS operator's name) is dropped from any host, counted,
// said in the repeat-limited drop lines, and teaches no route.
TEST_F(HostileNetwork, AnRaDatagramFromTheJssAliasSubsystemIsDroppedFromAnyHost) {
  UdpLinkOptions options;
  options.alias_subsystem = 250;
  open(options);
  const Address alias{250, 1, 40, 1};
  for (const std::uint32_t host : {kLoopback1, 0x7F000005u}) {
    link->receive_datagram(Ipv4Endpoint{host, 40000}, opc(message(alias, kManager, msg::ClearEmergency::code, 2)));
    link->receive_datagram(Ipv4Endpoint{host, 40000}, opc(message(alias, kManager, msg::ReleaseComponentControl::code)));
  }
  for (int i = 0; i < 30; ++i)
    link->receive_datagram(Ipv4Endpoint{0x7F000005u, 40000},
                           opc(message(alias, Address{1, 1, 33, 1}, msg::SetWrenchEffort::code, 2)));
  EXPECT_TRUE(delivered.empty());
  EXPECT_EQ(link->counters().dropped_for(DropReason::alias_source), 34u);
  EXPECT_FALSE(link->routes().route(250, 1));
  const auto lines = std::count_if(logs.begin(), logs.end(), [](const std::string& l) {
    return l.find("alias subsystem 250") != std::string::npos;
  });
  EXPECT_GE(lines, 1);
  EXPECT_LT(lines, 34);  // repeat-limited, not one a datagram
  // Every other subsystem is as before.
  link->receive_datagram(Ipv4Endpoint{kLoopback1, 40000}, query_from(kOcu));
  EXPECT_EQ(delivered.size(), 1u);
}

// Without a JSS face the subsystem is an ordinary one.
TEST_F(HostileNetwork, WithoutAFaceNoSubsystemIsAnAlias) {
  link->receive_datagram(Ipv4Endpoint{kLoopback1, 40000}, query_from(Address{250, 1, 40, 1}));
  EXPECT_EQ(delivered.size(), 1u);
  EXPECT_EQ(link->counters().dropped_for(DropReason::alias_source), 0u);
}

// ---- endpoints per address, full tables ---------------------------------------

TEST_F(HostileNetwork, TwoHundredFiftySixPortsFromOneHostDoNotStopALaterOcu) {
  for (std::uint16_t port = 1000; port < 1256; ++port)
    link->receive_datagram(Ipv4Endpoint{0x7F000009, port},
                           query_from(Address{static_cast<std::uint8_t>(10 + port % 200), 1, 40, 1}));
  EXPECT_LE(link->routes().peers().size(), RouteTableOptions{}.max_endpoints_per_address);
  const Ipv4Endpoint ocu{kLoopback1, 40000};
  link->receive_datagram(ocu, query_from(kOcu));
  EXPECT_EQ(delivered.back().standing, rt::SenderStanding::trusted);
  ASSERT_TRUE(link->routes().route(2, 1));
  EXPECT_EQ(link->routes().route(2, 1)->endpoint, ocu);
  EXPECT_EQ(link->counters().delivered_unrecorded, 0u);
}

TEST_F(HostileNetwork, AFullTableRoutesTheKnownOcuDeliversANewcomerUnrecordedAndStillChecksClaims) {
  UdpLinkOptions options;
  options.routes.max_entries = 3;
  open(options);
  auto& ocu_socket = peer_socket();
  const Ipv4Endpoint ocu = endpoint_of(ocu_socket);
  answer_with(10);
  link->receive_datagram(ocu, query_from(kOcu));
  link->receive_datagram(Ipv4Endpoint{0x7F000006, 3794}, query_from(Address{6, 1, 40, 1}));
  link->receive_datagram(Ipv4Endpoint{0x7F000007, 3794}, query_from(Address{7, 1, 40, 1}));
  // The table is full: a newcomer is delivered (Set Emergency is obeyed from anyone), as unrecorded.
  link->receive_datagram(Ipv4Endpoint{0x7F000008, 3794}, query_from(Address{8, 1, 40, 1}));
  ASSERT_EQ(delivered.size(), 4u);
  EXPECT_EQ(delivered.back().standing, rt::SenderStanding::unrecorded);
  EXPECT_FALSE(link->routes().route(8, 1));
  EXPECT_EQ(link->counters().delivered_unrecorded, 1u);
  // A claim on the OCU's ID from another host is still refused.
  link->receive_datagram(Ipv4Endpoint{0x7F000008, 3794}, query_from(kOcu));
  EXPECT_EQ(delivered.size(), 4u);
  EXPECT_EQ(link->counters().dropped_for(DropReason::route_claim), 1u);
  // The known OCU is still trusted and answered.
  take(ocu_socket);
  link->receive_datagram(ocu, query_from(kOcu));
  EXPECT_EQ(delivered.back().standing, rt::SenderStanding::trusted);
  EXPECT_EQ(take(ocu_socket).size(), 1u);
}

// ---- who may command ----------------------------------------------------------

TEST_F(HostileNetwork, ControlFromMakesOutsidersObservers) {
  UdpLinkOptions options;
  options.control_from = {*parse_cidr("127.0.0.1/32")};
  open(options);
  link->receive_datagram(Ipv4Endpoint{kLoopback1, 40000}, query_from(kOcu));
  link->receive_datagram(Ipv4Endpoint{0x7F000005, 40000}, query_from(Address{5, 1, 40, 1}));
  ASSERT_EQ(delivered.size(), 2u);
  EXPECT_EQ(delivered[0].standing, rt::SenderStanding::trusted);
  EXPECT_EQ(delivered[1].standing, rt::SenderStanding::observer);
  EXPECT_EQ(link->counters().delivered_observer, 1u);
}

TEST(LocalNetworks, IncludeLoopbackOnce) {
  const auto networks = local_networks();
  EXPECT_EQ(std::count(networks.begin(), networks.end(), Cidr{0x7F000000, 8}), 1);
  for (const auto& n : networks) EXPECT_TRUE(parse_cidr(to_string(n))) << to_string(n);  // host bits clear
}

// ---- amplification ------------------------------------------------------------

// A reply beyond what the endpoint sent and its allowance (none here: the
// allowance's part is AmplificationBudget's) is held while the challenge is
// out; unanswered, it is dropped after the hold time (logged), and later
// ones beyond the budget at once, one line for the streak.
TEST_F(HostileNetwork, AnUnverifiedEndpointGetsNoReplyBeyondItsAllowanceAndTheHeldOneExpires) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.amplification.unverified_burst_bytes = 0;
  open(options);
  answer_with(4000);
  auto& victim = peer_socket();  // the address a forger names
  const auto query = query_from(kOcu);
  link->receive_datagram(endpoint_of(victim), query);
  const auto got = take(victim);
  EXPECT_LE(bytes_of(got), query.size());
  ASSERT_EQ(got.size(), 1u);  // the challenge only
  const auto challenge = unframe(got[0]);
  ASSERT_TRUE(challenge);
  EXPECT_EQ(challenge->packet.header.command_code, kChallengeCode);
  EXPECT_EQ(challenge->packet.header.ack_nak, AckNak::ack_requested);
  EXPECT_EQ(challenge->packet.header.destination, kOcu);
  EXPECT_EQ(challenge->packet.header.source, kManager);
  const auto& c = link->counters().amplification;
  EXPECT_EQ(c.replies_held, 1u);
  EXPECT_EQ(c.challenges_sent, 1u);
  EXPECT_EQ(c.bytes_received_unverified, query.size());
  EXPECT_LE(c.bytes_sent_unverified, c.bytes_received_unverified);
  // Nobody answers: the reply is dropped after the hold time, with a line; nothing more is sent.
  time.advance(3s);
  EXPECT_EQ(link->counters().amplification.replies_dropped_unverified, 1u);
  EXPECT_EQ(link->counters().amplification.held_replies_expired, 1u);
  EXPECT_EQ(std::count_if(logs.begin(), logs.end(),
                          [](const std::string& l) { return l.find("did not answer the challenge") != l.npos; }),
            1);
  EXPECT_TRUE(take(victim).empty());
  // Two more queries: their replies are dropped at once (one line for the
  // streak), another challenge goes (a second is past): nothing but it.
  link->receive_datagram(endpoint_of(victim), query);
  link->receive_datagram(endpoint_of(victim), query);
  const auto more = take(victim);
  ASSERT_EQ(more.size(), 1u);
  EXPECT_EQ(unframe(more[0])->packet.header.command_code, kChallengeCode);
  EXPECT_EQ(link->counters().amplification.replies_dropped_unverified, 3u);
  EXPECT_EQ(std::count_if(logs.begin(), logs.end(),
                          [](const std::string& l) { return l.find("replies to 127.0.0.1:") != l.npos; }),
            1);
}

TEST_F(HostileNetwork, AnEndpointThatAnswersTheChallengeGetsTheHeldReply) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.amplification.unverified_burst_bytes = 0;  // no allowance: the 4000-byte reply is beyond the budget
  open(options);
  answer_with(4000);
  auto& ocu_socket = peer_socket();
  const Ipv4Endpoint ocu = endpoint_of(ocu_socket);
  link->receive_datagram(ocu, query_from(kOcu));
  const auto got = take(ocu_socket);
  ASSERT_EQ(got.size(), 1u);
  const Header challenge = unframe(got[0])->packet.header;
  // Wrong sequence numbers do not verify (and are not delivered as the answer).
  link->receive_datagram(ocu, ack_of(challenge, 1));
  EXPECT_TRUE(take(ocu_socket).empty());
  EXPECT_EQ(link->counters().amplification.endpoints_verified, 0u);
  EXPECT_EQ(link->counters().amplification.wrong_answers, 1u);
  const std::size_t delivered_before = delivered.size();
  link->receive_datagram(ocu, ack_of(challenge));
  EXPECT_EQ(delivered.size(), delivered_before);  // the answer is the link's
  EXPECT_EQ(link->counters().amplification.endpoints_verified, 1u);
  const auto released = take(ocu_socket);
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].size(), 8 + kHeaderSize + 4000);
  EXPECT_EQ(unframe(released[0])->packet.header.command_code, 0x4807);
  // Verified: the next big reply goes at once.
  link->receive_datagram(ocu, query_from(kOcu));
  EXPECT_EQ(take(ocu_socket).size(), 1u);
  EXPECT_EQ(link->counters().amplification.replies_held, 1u);
}

TEST_F(HostileNetwork, TooManyWrongAnswersRetireTheChallenge) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.amplification.unverified_burst_bytes = 0;
  open(options);
  answer_with(4000);
  auto& ocu_socket = peer_socket();
  const Ipv4Endpoint ocu = endpoint_of(ocu_socket);
  link->receive_datagram(ocu, query_from(kOcu));
  const Header challenge = unframe(take(ocu_socket).at(0))->packet.header;
  for (std::uint16_t delta = 1; delta <= 3; ++delta) link->receive_datagram(ocu, ack_of(challenge, delta));
  link->receive_datagram(ocu, ack_of(challenge));  // the right number, too late: a guesser's luck
  EXPECT_EQ(link->counters().amplification.endpoints_verified, 0u);
  // The next challenge (a second later) has a new number, which verifies.
  time.advance(1s);
  link->receive_datagram(ocu, query_from(kOcu));
  const auto got = take(ocu_socket);
  ASSERT_FALSE(got.empty());
  const Header second = unframe(got.back())->packet.header;
  ASSERT_EQ(second.command_code, kChallengeCode);
  EXPECT_NE(second.sequence, challenge.sequence);
  link->receive_datagram(ocu, ack_of(second));
  EXPECT_EQ(link->counters().amplification.endpoints_verified, 1u);
}

TEST_F(HostileNetwork, StaticPeersAreVerifiedFromTheStart) {
  auto& peer = peer_socket();
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.peers = {StaticPeer{endpoint_of(peer), Framing::opc}};
  open(options);
  answer_with(4000);
  link->receive_datagram(endpoint_of(peer), query_from(kOcu));
  const auto got = take(peer);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(unframe(got[0])->packet.header.command_code, 0x4807);
  EXPECT_EQ(link->counters().amplification.challenges_sent, 0u);
}

// Issue 43, where the guarantee is kept (UdpLink::on_datagram): a command
// from an unverified endpoint whose reply could not be sent (here the global
// budget is 0) is not delivered - a Request Control is never granted with
// its Confirm withheld - while a stop always is, and a query is delivered.
TEST_F(HostileNetwork, ACommandWhoseReplyCannotGoIsNotDeliveredButAStopIs) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.amplification.unverified_total_burst_bytes = 0;
  options.amplification.unverified_total_bytes_per_second = 0;
  open(options);
  auto& ocu_socket = peer_socket();
  const Ipv4Endpoint ocu = endpoint_of(ocu_socket);
  const Address driver{1, 1, 33, 1};
  link->receive_datagram(ocu, opc(message(kOcu, driver, msg::RequestComponentControl::code, 1)));
  link->receive_datagram(ocu, opc(message(kOcu, driver, msg::SetWrenchEffort::code, 3)));
  EXPECT_TRUE(delivered.empty());
  EXPECT_EQ(link->counters().amplification.commands_refused, 2u);
  EXPECT_EQ(std::count_if(logs.begin(), logs.end(),
                          [](const std::string& l) { return l.find("command 0x000D from 127.0.0.1:") != l.npos; }),
            1);
  for (const std::uint16_t stop : {msg::SetEmergency::code, msg::Standby::code, msg::Shutdown::code})
    link->receive_datagram(ocu, opc(message(kOcu, driver, stop, stop == msg::SetEmergency::code ? 2 : 0)));
  link->receive_datagram(ocu, query_from(kOcu));
  ASSERT_EQ(delivered.size(), 4u);
  EXPECT_EQ(delivered[0].header.command_code, msg::SetEmergency::code);
  EXPECT_EQ(delivered[3].header.command_code, msg::QueryIdentification::code);
  EXPECT_EQ(link->counters().amplification.commands_refused, 2u);
}

// The held replies are bounded per endpoint (datagrams, bytes) and in
// total; forgetting an endpoint drops what it held.
TEST(AmplificationGuardBounds, HeldRepliesAreBoundedAndGoWithTheEndpoint) {
  AmplificationGuardOptions options;
  options.unverified_burst_bytes = 0;  // no allowance: every reply here is beyond the budget
  options.max_held_per_endpoint = 3;
  options.max_held_bytes_per_endpoint = 10000;
  options.max_held_bytes_total = 12000;
  AmplificationGuard guard(options, {3, 4});
  const Ipv4Endpoint a{0x7F000002, 1}, b{0x7F000003, 1};
  guard.track(a);
  guard.track(b);
  const std::vector<std::uint8_t> big(4000), small(100);
  const rt::TimePoint now{};
  EXPECT_EQ(guard.offer(a, Framing::opc, big, now), AmplificationGuard::Verdict::held);
  EXPECT_EQ(guard.offer(a, Framing::opc, big, now), AmplificationGuard::Verdict::held);
  EXPECT_EQ(guard.offer(a, Framing::opc, big, now), AmplificationGuard::Verdict::dropped);  // 12000 > 10000
  EXPECT_EQ(guard.offer(a, Framing::opc, small, now), AmplificationGuard::Verdict::held);
  EXPECT_EQ(guard.offer(a, Framing::opc, small, now), AmplificationGuard::Verdict::dropped);  // 3 datagrams
  EXPECT_EQ(guard.offer(b, Framing::opc, small, now), AmplificationGuard::Verdict::held);
  EXPECT_EQ(guard.offer(b, Framing::opc, big, now), AmplificationGuard::Verdict::dropped);  // 12200 > 12000 in all
  EXPECT_EQ(guard.held_bytes(), 8200u);
  guard.forget(a);
  EXPECT_EQ(guard.held_bytes(), 100u);
  EXPECT_EQ(guard.counters().replies_dropped_unverified, 3u + 3u);  // 3 refused, 3 held by a
  EXPECT_EQ(guard.offer(Ipv4Endpoint{0x7F000004, 1}, Framing::opc, big, now), AmplificationGuard::Verdict::send);  // untracked
}

// End to end on real sockets: a node with verify_endpoints and an OCU-side
// node (its own Node, which answers ACK requests as every node does): the
// OCU's query is answered after the challenge, without anyone's help.
TEST(HostileNetworkNodes, ARealNodeAnswersTheChallengeAndGetsItsReply) {
  asio::io_context io;
  auto open_host = [&](std::uint8_t subsystem, bool verify) {
    host::HostConfig config;
    config.node.subsystem = subsystem;
    config.node.node = 1;
    config.link.bind = Ipv4Endpoint{kLoopback1, 0};
    config.link.verify_endpoints = verify;
    config.link.amplification.unverified_burst_bytes = 0;  // the reply is beyond the budget: a challenge
    config.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "node manager", {}, 0, {}}};
    auto opened = host::NodeHost::open(config, io);
    EXPECT_TRUE(opened) << opened.error().message();
    return std::move(*opened);
  };
  auto node = open_host(1, true);
  auto ocu = open_host(2, false);
  bool answered = false;
  ocu->watch([&](const PacketView& p) { answered |= p.header.command_code == msg::ReportIdentification::code; });
  Header h;
  h.command_code = msg::QueryIdentification::code;
  h.source = Address{2, 1, 1, 1};
  h.destination = kManager;
  h.data_size = 1;
  // Sent straight to the node (the OCU has no route yet), as a tool does.
  std::vector<std::uint8_t> packet(kHeaderSize);
  encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(packet.data(), kHeaderSize));
  packet.push_back(2);  // Query Identification of the subsystem
  ocu->udp_link()->send_to(node->udp_link()->local_endpoint(), Framing::opc, packet);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!answered && std::chrono::steady_clock::now() < deadline) io.run_for(5ms);
  EXPECT_TRUE(answered);
  const auto& c = node->udp_link()->counters().amplification;
  EXPECT_EQ(c.endpoints_verified, 1u);
  EXPECT_GE(c.replies_held, 1u);
  EXPECT_EQ(c.challenges_sent, 1u);
}

}  // namespace
}  // namespace jaus::transport
