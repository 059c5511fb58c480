// SAE JAUS (AS5669A) on the UDP link (issue 33; docs/jss.md, "Transport: one
// port, three framings"): the three framings share one socket, AS5669A
// datagrams are checked, filtered and given a standing as RA ones, their JSS
// sources' endpoints learnt, the face's datagrams routed by JssId (learnt
// endpoint, else the JSS group and static peers), and JSS endpoints verified
// by an AS5669A challenge and its ACK. The link runs on virtual time;
// datagrams are injected with receive_datagram() or sent from real sockets on
// loopback, what it sends is read back from real sockets (loopback delivers
// during send).
#include <gtest/gtest.h>

#include <boost/asio/ip/udp.hpp>
#include <deque>
#include <functional>
#include <unistd.h>

#include "jaus/base/virtual_time.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::transport {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

constexpr std::uint32_t kLoopback1 = 0x7F000001;
constexpr std::uint32_t kLoopback2 = 0x7F000002;
const jss::JssId kSelf{1, 1, 1};       // our node manager
const jss::JssId kClient{42, 1, 1};    // a JSS operator unit
const jss::JssId kClientTool{42, 1, 7};
const Address kManager{1, 1, 1, 1};
const Address kOcu{2, 1, 40, 1};

// An AS5669A datagram: `contents` (message ID and body) from `from` to `to`.
std::vector<std::uint8_t> jss_datagram(const jss::JssId& from, const jss::JssId& to,
                                       std::vector<std::uint8_t> contents, std::uint16_t sequence = 0,
                                       jss::JudpAckNak ack_nak = jss::JudpAckNak::none) {
  jss::JudpHeader h;
  h.source = from;
  h.destination = to;
  h.sequence = sequence;
  h.ack_nak = ack_nak;
  return jss::make_judp_datagram(h, contents);
}
// Query Identification (0x2B00), type 2: the worked example of docs/jss.md,
// "The bytes on the wire".
std::vector<std::uint8_t> query_identification(const jss::JssId& from, const jss::JssId& to = kSelf) {
  return jss_datagram(from, to, {0x00, 0x2B, 0x02});
}

std::vector<std::uint8_t> ra_packet(const Address& from, const Address& to, std::uint16_t code) {
  std::vector<std::uint8_t> out(kHeaderSize, 0);
  Header h;
  h.command_code = code;
  h.source = from;
  h.destination = to;
  encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(out.data(), kHeaderSize));
  return out;
}
std::vector<std::uint8_t> framed(Framing framing, std::span<const std::uint8_t> packet) {
  const FramePrefix prefix = frame_prefix(framing, packet.size());
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), packet.begin(), packet.end());
  return out;
}

Ipv4Endpoint endpoint_of(const udp::socket& socket) {
  const auto e = socket.local_endpoint();
  return Ipv4Endpoint{e.address().to_v4().to_uint(), e.port()};
}

struct JssDelivered {
  std::vector<std::uint8_t> datagram;
  rt::SenderStanding standing;
};

class JssLink : public ::testing::Test {
 protected:
  void SetUp() override { open({}); }

  void open(UdpLinkOptions options, bool with_handler = true) {
    options.subsystem = 1;
    options.node = 1;
    options.bind = Ipv4Endpoint{kLoopback1, 0};
    options.challenge_key = std::array<std::uint64_t, 2>{1, 2};
    auto opened = UdpLink::open(io, time, time, options,
                                [this](rt::LogLevel, const std::string& line) { logs.push_back(line); });
    ASSERT_TRUE(opened) << opened.error().message();
    link = std::move(*opened);
    link->on_packet([this](const PacketView& p, Framing framing, rt::SenderStanding standing) {
      ra.push_back({p.header, framing, standing});
    });
    if (with_handler)
      link->on_jss_packets([this](const Inbound& inbound, rt::SenderStanding standing) {
        jss.push_back({{inbound.bytes.begin(), inbound.bytes.end()}, standing});
        if (reply) reply(inbound.bytes);
      });
    link->start();
  }

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
  bool logged(std::string_view text) const {
    return std::any_of(logs.begin(), logs.end(), [&](const auto& l) { return l.find(text) != std::string::npos; });
  }

  struct RaDelivered {
    Header header;
    Framing framing;
    rt::SenderStanding standing;
  };
  asio::io_context io;
  rt::VirtualTime time;
  std::unique_ptr<UdpLink> link;
  std::vector<RaDelivered> ra;
  std::vector<JssDelivered> jss;
  std::function<void(std::span<const std::uint8_t>)> reply;
  std::vector<std::string> logs;
  std::deque<udp::socket> sockets;
};

TEST_F(JssLink, TheThreeFramingsShareOneSocket) {
  auto& peer = peer_socket();
  const udp::endpoint to(asio::ip::address_v4(kLoopback1), link->local_endpoint().port);
  const auto query = ra_packet(kOcu, kManager, msg::QueryIdentification::code);
  for (const auto& datagram : {framed(Framing::opc, query), framed(Framing::judp, query), query_identification(kClient)})
    peer.send_to(asio::buffer(datagram), to);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (ra.size() + jss.size() < 3 && std::chrono::steady_clock::now() < deadline) io.run_for(5ms);
  ASSERT_EQ(ra.size(), 2u);
  EXPECT_EQ(ra[0].framing, Framing::opc);
  EXPECT_EQ(ra[1].framing, Framing::judp);
  ASSERT_EQ(jss.size(), 1u);
  EXPECT_EQ(jss[0].datagram, query_identification(kClient));
  EXPECT_EQ(link->counters().jss.datagrams_received, 1u);
  EXPECT_EQ(link->counters().dropped_total(), 0u);
  // Each dialect's route in its own table.
  EXPECT_TRUE(link->routes().route(kOcu.subsystem, kOcu.node));
  ASSERT_TRUE(link->jss_routes().route(kClient.subsystem, kClient.node));
  EXPECT_EQ(link->jss_routes().route(kClient.subsystem, kClient.node)->endpoint, endpoint_of(peer));
}

TEST_F(JssLink, ADatagramLargerThanAnyRaOneArrivesWhole) {
  // A JSS node may pack up to 64 KiB into one datagram (JRM cuts at 4 KiB,
  // others need not); an RA datagram that large is still dropped as oversized.
  auto& peer = peer_socket();
  const udp::endpoint to(asio::ip::address_v4(kLoopback1), link->local_endpoint().port);
  std::vector<std::uint8_t> contents = {0x02, 0x22};  // Query Heartbeat Pulse, then padding
  contents.resize(7000, 0x5A);
  const auto big = jss_datagram(kClient, kSelf, contents);
  ASSERT_GT(big.size(), kMaxDatagramSize);
  peer.send_to(asio::buffer(big), to);
  const std::vector<std::uint8_t> ra_big(kMaxDatagramSize + 100, 0x4A);
  peer.send_to(asio::buffer(ra_big), to);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while ((jss.empty() || link->counters().dropped_for(DropReason::oversized) == 0) &&
         std::chrono::steady_clock::now() < deadline)
    io.run_for(5ms);
  ASSERT_EQ(jss.size(), 1u);
  EXPECT_EQ(jss[0].datagram, big);
  EXPECT_EQ(link->counters().dropped_for(DropReason::oversized), 1u);
}

TEST_F(JssLink, AMalformedDatagramIsCountedWithItsReasonAndNotDelivered) {
  const Ipv4Endpoint from{kLoopback2, 4000};
  auto bad = query_identification(kClient);
  bad[2] = 0x40;  // data size 64: beyond the datagram
  link->receive_datagram(from, bad);
  link->receive_datagram(from, std::vector<std::uint8_t>{0x02, 0x00});  // cut short
  auto compressed = query_identification(kClient);
  compressed[1] = 0x40;  // header compression: never guessed
  link->receive_datagram(from, compressed);
  EXPECT_TRUE(jss.empty());
  EXPECT_EQ(link->counters().dropped_for(DropReason::jss_malformed), 3u);
  EXPECT_EQ(link->jss_routes().route_count(), 0u);  // nothing learnt from a bad datagram
  EXPECT_TRUE(logged("malformed AS5669A datagram")) << (logs.empty() ? "" : logs.back());
  EXPECT_TRUE(logged("offset 2")) << (logs.empty() ? "" : logs.back());
  // Invalid and broadcast sources are refused like RA ones.
  link->receive_datagram(from, query_identification(jss::JssId{42, 0, 1}));
  link->receive_datagram(from, query_identification(jss::JssId{65535, 1, 1}));
  EXPECT_EQ(link->counters().dropped_for(DropReason::invalid_source), 2u);
  EXPECT_TRUE(jss.empty());
}

TEST_F(JssLink, WithoutAFaceAs5669aIsDroppedAsJssOff) {
  open({}, /*with_handler=*/false);
  link->receive_datagram(Ipv4Endpoint{kLoopback2, 4000}, query_identification(kClient));
  EXPECT_EQ(link->counters().dropped_for(DropReason::jss_off), 1u);
  EXPECT_EQ(link->jss_routes().route_count(), 0u);
}

TEST_F(JssLink, AllowAndControlFromGiveTheStanding) {
  UdpLinkOptions options;
  options.allow = {*parse_cidr("127.0.0.0/8")};
  options.control_from = {*parse_cidr("127.0.0.2/32")};
  open(options);
  link->receive_datagram(Ipv4Endpoint{0x0A000005, 4000}, query_identification(kClient));  // 10.0.0.5
  EXPECT_EQ(link->counters().dropped_for(DropReason::not_allowed), 1u);
  link->receive_datagram(Ipv4Endpoint{kLoopback1, 4000}, query_identification(kClient));
  link->receive_datagram(Ipv4Endpoint{kLoopback2, 4000}, query_identification(jss::JssId{43, 1, 1}));
  ASSERT_EQ(jss.size(), 2u);
  EXPECT_EQ(jss[0].standing, rt::SenderStanding::observer);
  EXPECT_EQ(jss[1].standing, rt::SenderStanding::trusted);
  EXPECT_EQ(link->counters().jss.delivered_observer, 1u);
}

TEST_F(JssLink, AFullTableDeliversUnrecordedAndAClaimFromAnotherHostIsRefused) {
  UdpLinkOptions options;
  options.routes.max_entries = 1;
  open(options);
  link->receive_datagram(Ipv4Endpoint{kLoopback1, 4000}, query_identification(kClient));
  link->receive_datagram(Ipv4Endpoint{kLoopback2, 4001}, query_identification(jss::JssId{43, 1, 1}));
  ASSERT_EQ(jss.size(), 2u);
  EXPECT_EQ(jss[0].standing, rt::SenderStanding::trusted);
  EXPECT_EQ(jss[1].standing, rt::SenderStanding::unrecorded);
  // 42.1 is live at 127.0.0.1:4000: another host claiming it is dropped, full table or not.
  link->receive_datagram(Ipv4Endpoint{kLoopback2, 4000}, query_identification(kClient));
  EXPECT_EQ(link->counters().dropped_for(DropReason::route_claim), 1u);
  EXPECT_EQ(jss.size(), 2u);
  // A pinned ID (its alias holds control) stays with its host even after a long silence.
  link->pin_jss_routes_while([](std::uint16_t subsystem, std::uint8_t node) { return subsystem == 42 && node == 1; });
  time.advance(10s);
  link->receive_datagram(Ipv4Endpoint{kLoopback2, 4000}, query_identification(kClient));
  EXPECT_EQ(link->counters().dropped_for(DropReason::route_claim), 2u);
  time.advance(60s);  // beyond route_timeout: pinned, so kept
  EXPECT_EQ(link->jss_routes().route(42, 1)->endpoint, (Ipv4Endpoint{kLoopback1, 4000}));
}

TEST_F(JssLink, RepliesGoToTheLearntEndpointOfTheirJssNode) {
  auto& client = peer_socket();
  link->receive_datagram(endpoint_of(client), query_identification(kClient));
  // Any component of the learnt node: the endpoint is the node's.
  const auto report = jss_datagram(kSelf, kClientTool, {0x00, 0x4B, 0x02});
  link->transmit_jss(kClientTool, report);
  const auto got = take(client);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], report);  // sent as it is: no prefix
  EXPECT_EQ(link->counters().jss.unrouted, 0u);
}

TEST_F(JssLink, UnknownIdsAndBroadcastsGoToStaticPeersAndWithNowhereToGoAreCounted) {
  link->transmit_jss(jss::JssId{77, 1, 1}, query_identification(kSelf, jss::JssId{77, 1, 1}));
  EXPECT_EQ(link->counters().jss.unrouted, 1u);
  EXPECT_EQ(link->counters().jss.no_route, 1u);
  auto& peer = peer_socket();
  UdpLinkOptions options;
  options.peers = {StaticPeer{endpoint_of(peer), Framing::opc}};
  open(options);
  link->transmit_jss(jss::JssId{77, 1, 1}, query_identification(kSelf, jss::JssId{77, 1, 1}));
  link->transmit_jss(jss::JssId{65535, 255, 255}, query_identification(kSelf, jss::JssId{65535, 255, 255}));
  const auto got = take(peer);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0][0], jss::kAs5669aVersion);  // AS5669A whatever the peer's RA framing
  EXPECT_EQ(link->counters().jss.no_route, 0u);
}

TEST(JssLinks, UnknownIdsGoToTheJssGroupAndOwnDatagramsAreNotTakenBack) {
  asio::io_context io;
  AsioRuntime runtime(io);
  const auto port = static_cast<std::uint16_t>(30000 + (::getpid() + 7) % 20000);
  const Ipv4Endpoint group{*parse_ipv4("239.255.0.1"), port};
  std::vector<std::string> logs;
  std::vector<std::vector<std::uint8_t>> at_a, at_b;
  auto open_member = [&](std::uint8_t subsystem, const char* address, auto& received) {
    UdpLinkOptions options;
    options.subsystem = subsystem;
    options.node = 1;
    options.bind = Ipv4Endpoint{*parse_ipv4(address), 0};
    options.jss_multicast = group;
    auto link = UdpLink::open(io, runtime, runtime, options,
                              [&](rt::LogLevel, const std::string& line) { logs.push_back(line); });
    if (link)
      (*link)->on_jss_packets([&received](const Inbound& inbound, rt::SenderStanding) {
        received.emplace_back(inbound.bytes.begin(), inbound.bytes.end());
      });
    return link;
  };
  auto a = open_member(1, "127.0.0.1", at_a);
  auto b = open_member(2, "127.0.0.2", at_b);
  ASSERT_TRUE(a && b);
  for (const auto& line : logs)
    if (line.find("JSS broadcasts go to static peers only") != std::string::npos)
      GTEST_SKIP() << "no multicast on this host's loopback: " << line;
  (*a)->start();
  (*b)->start();
  // To 2.1.1, never heard of: the group (JRM and fkie's node manager do the same).
  const auto query = query_identification(jss::JssId{1, 1, 1}, jss::JssId{2, 1, 1});
  (*a)->transmit_jss(jss::JssId{2, 1, 1}, query);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while ((at_b.empty() || (*a)->counters().dropped_for(DropReason::from_self) == 0) &&
         std::chrono::steady_clock::now() < deadline)
    io.run_for(5ms);
  ASSERT_EQ(at_b.size(), 1u);
  EXPECT_EQ(at_b[0], query);
  EXPECT_TRUE(at_a.empty());  // its own, looped back: dropped
  EXPECT_EQ((*a)->counters().dropped_for(DropReason::from_self), 1u);
  ASSERT_TRUE((*b)->jss_routes().route(1, 1));
  EXPECT_EQ((*b)->jss_routes().route(1, 1)->endpoint, (*a)->local_endpoint());
}

// verify_endpoints: the reply to a learnt JSS endpoint that exceeds what it
// sent and its allowance (none here) is held, the endpoint challenged with
// an AS5669A Query Heartbeat Pulse (ACK requested) from our node manager,
// and verified by the ACK.
TEST_F(JssLink, AJssEndpointIsChallengedAndVerifiedByItsAck) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  options.amplification.unverified_burst_bytes = 0;  // the allowance's part: AmplificationBudget tests
  open(options);
  reply = [this](std::span<const std::uint8_t> datagram) {
    const auto packets = jss::decode_judp_datagram(datagram);
    if (jss::message_id_of(packets->front().contents) != 0x2B00) return;  // a wrong ACK is the face's to ignore
    const auto big = jss_datagram(kSelf, packets->front().header.source, std::vector<std::uint8_t>(1000, 0x4B));
    link->transmit_jss(packets->front().header.source, big);
  };
  auto& client_socket = peer_socket();
  const Ipv4Endpoint client = endpoint_of(client_socket);
  link->receive_datagram(client, query_identification(kClient));  // 18 bytes
  auto got = take(client_socket);
  ASSERT_EQ(got.size(), 1u);  // the challenge, not the 1015-byte reply
  EXPECT_EQ(got[0].size(), kJssChallengeSize);
  const auto challenge = jss::decode_judp_datagram(got[0]);
  ASSERT_TRUE(challenge) << challenge.error().message();
  const jss::JudpHeader& h = challenge->front().header;
  EXPECT_EQ(h.ack_nak, jss::JudpAckNak::ack_requested);
  EXPECT_EQ(h.source, kSelf);
  EXPECT_EQ(h.destination, kClient);
  EXPECT_EQ(std::vector<std::uint8_t>(challenge->front().contents.begin(), challenge->front().contents.end()),
            (std::vector<std::uint8_t>{0x02, 0x22}));
  EXPECT_EQ(link->counters().jss.amplification.replies_held, 1u);
  EXPECT_EQ(link->counters().amplification.challenges_sent, 0u);  // the RA guard is not involved

  // A wrong sequence number does not verify; the ACK with the right one does, and is the link's.
  link->receive_datagram(client, jss_datagram(kClient, kSelf, {}, h.sequence + 1, jss::JudpAckNak::ack));
  EXPECT_TRUE(take(client_socket).empty());
  EXPECT_EQ(link->counters().jss.amplification.wrong_answers, 1u);
  const std::size_t delivered = jss.size();
  link->receive_datagram(client, jss_datagram(kClient, kSelf, {}, h.sequence, jss::JudpAckNak::ack));
  EXPECT_EQ(jss.size(), delivered);
  EXPECT_EQ(link->counters().jss.amplification.endpoints_verified, 1u);
  got = take(client_socket);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].size(), 1u + jss::kTransportHeaderSize + 1000 + jss::kSequenceSize);
  // Verified: the next big reply goes at once.
  link->receive_datagram(client, query_identification(kClient));
  EXPECT_EQ(take(client_socket).size(), 1u);
  EXPECT_EQ(link->counters().jss.amplification.replies_held, 1u);
}

// A JSS client is challenged at its first datagram, even when the reply fits
// what it sent: it may send nothing more for a half timeout (it keeps control
// by re-requesting it every 1.5 s), and a later unsolicited message (Reject
// Control when another client takes over) must not wait for that.
TEST_F(JssLink, AJssEndpointIsChallengedAtItsFirstDatagramSoLaterMessagesAreNotHeld) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  open(options);
  auto& client_socket = peer_socket();
  const Ipv4Endpoint client = endpoint_of(client_socket);
  link->receive_datagram(client, query_identification(kClient));  // 18 bytes
  auto got = take(client_socket);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].size(), kJssChallengeSize);
  const auto challenge = jss::decode_judp_datagram(got[0]);
  ASSERT_TRUE(challenge) << challenge.error().message();
  link->receive_datagram(client,
                         jss_datagram(kClient, kSelf, {}, challenge->front().header.sequence, jss::JudpAckNak::ack));
  EXPECT_EQ(link->counters().jss.amplification.endpoints_verified, 1u);
  // Later, unasked: sent at once.
  link->transmit_jss(kClient, jss_datagram(kSelf, kClient, {0x10, 0x00, 0x00}));
  EXPECT_EQ(take(client_socket).size(), 1u);
  EXPECT_EQ(link->counters().jss.amplification.replies_held, 0u);
}

// Issue 43: a JSS client that never ACKs is answered within what it sent
// plus its allowance (a 4 KiB burst, 1 KiB a second): two 1015-byte replies a
// second are more than that, so some are dropped (and their commands would
// not act), never more bytes than the allowance.
TEST_F(JssLink, AnEndpointThatNeverAcksGetsNoMoreThanItSentPlusItsAllowance) {
  UdpLinkOptions options;
  options.verify_endpoints = true;
  open(options);
  reply = [this](std::span<const std::uint8_t>) {
    link->transmit_jss(kClient, jss_datagram(kSelf, kClient, std::vector<std::uint8_t>(1000, 0)));
  };
  auto& client_socket = peer_socket();
  std::size_t sent = 0, received = 0, replies = 0;
  for (int i = 0; i < 20; ++i) {
    const auto query = query_identification(kClient);
    sent += query.size();
    link->receive_datagram(endpoint_of(client_socket), query);
    for (const auto& d : take(client_socket)) {
      received += d.size();
      replies += d.size() > kJssChallengeSize;
    }
    time.advance(500ms);
  }
  const auto& a = options.amplification;
  EXPECT_LE(received, sent + a.unverified_burst_bytes + 10 * a.unverified_bytes_per_second);
  EXPECT_GE(replies, 10u);  // answered within the allowance, without ever answering a challenge
  EXPECT_EQ(link->counters().jss.amplification.endpoints_verified, 0u);
  EXPECT_GT(link->counters().jss.amplification.replies_dropped_unverified, 0u);
}

}  // namespace
}  // namespace jaus::transport
