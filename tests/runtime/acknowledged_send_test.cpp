// Node::send_acknowledged: a command that must arrive is sent with an ACK
// request and retransmitted per its own policy (issue 32: every 50 ms, 10
// times) until the destination answers; the outcome is reported once. Two
// nodes on a jaus::testing memory network (1 ms latency) under virtual time.
#include "harness.hpp"
#include "jaus/node/node.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

const node::AckPolicy kFast{50ms, 10};
const Address kOcu{2, 1, 40, 1};

rt::ComponentConfig config_for(const Address& address, const char* name) {
  rt::ComponentConfig c;
  c.address = address;
  c.name = name;
  c.authority = 5;
  return c;
}

template <class M>
std::vector<std::uint8_t> payload_of(const M& m) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(m, payload);
  EXPECT_TRUE(size);
  payload.resize(*size);
  return payload;
}

Header header_to(const Address& from, const Address& to, std::uint16_t code) {
  Header h;
  h.command_code = code;
  h.source = from;
  h.destination = to;
  h.priority = jaus::priority::kSafetyCritical;
  return h;
}

class AcknowledgedSendTest : public ::testing::Test {
 protected:
  AcknowledgedSendTest() {
    node::NodeConfig ca;
    ca.subsystem = 1;
    node::NodeConfig cb;
    cb.subsystem = 2;
    a = std::make_unique<node::Node>(ca, time, time, link_a);
    b = std::make_unique<node::Node>(cb, time, time, link_b,
                                     [this](rt::LogLevel, const std::string& l) { logs.push_back(l); });
    link_a.deliver_to(*a);
    link_b.deliver_to(*b);
    driver = &a->add_as(std::make_unique<TestDriver>(config_for(kDriver, "driver"), a->environment()));
    link_b.on_transmit([this](const Header& h, std::span<const std::uint8_t>) {
      if (h.command_code == msg::SetEmergency::code) emergency_sent_at.push_back(time.now() - start);
    });
  }

  // Set Emergency from the OCU's address on node b to `to`, resolved into `resolutions`.
  void send_emergency(const Address& to, node::AckPolicy policy = kFast) {
    b->send_acknowledged(header_to(kOcu, to, msg::SetEmergency::code), payload_of(msg::SetEmergency{}), policy,
                         [this](const node::AckResolution& r) { resolutions.push_back(r); });
  }

  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time, 1ms};
  testing::MemoryLink& link_a = network.attach(1, 1);
  testing::MemoryLink& link_b = network.attach(2, 1);
  std::unique_ptr<node::Node> a, b;
  TestDriver* driver = nullptr;
  rt::TimePoint start = time.now();
  std::vector<rt::Duration> emergency_sent_at;  // since start
  std::vector<node::AckResolution> resolutions;
  std::vector<std::string> logs;
};

TEST_F(AcknowledgedSendTest, AnAnsweredCommandIsSentOnceAndAcknowledged) {
  send_emergency(kDriver);
  EXPECT_TRUE(resolutions.empty());  // never during the call
  time.advance(1s);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
  EXPECT_EQ(emergency_sent_at, (std::vector<rt::Duration>{0ms}));
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::acknowledged);
  EXPECT_EQ(resolutions[0].transmissions, 1u);
  EXPECT_EQ(resolutions[0].key.peer, kDriver);
  EXPECT_EQ(resolutions[0].key.command_code, msg::SetEmergency::code);
  EXPECT_EQ(b->acks().pending(), 0u);
}

TEST_F(AcknowledgedSendTest, RetransmitsEvery50msThenGivesUp) {
  link_a.set_connected(false);  // nothing reaches the driver's node
  send_emergency(kDriver);
  time.advance(499ms);
  EXPECT_TRUE(resolutions.empty());
  time.advance(1ms);
  std::vector<rt::Duration> expected;
  for (int i = 0; i < 10; ++i) expected.push_back(i * 50ms);
  EXPECT_EQ(emergency_sent_at, expected);
  ASSERT_EQ(resolutions.size(), 1u);  // 50 ms after the last transmission
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::exhausted);
  EXPECT_EQ(resolutions[0].transmissions, 10u);
  time.advance(10s);
  EXPECT_EQ(emergency_sent_at.size(), 10u);
  EXPECT_EQ(resolutions.size(), 1u);
  EXPECT_TRUE(any_line_contains(logs, "no ACK for 0x6 to 1.1.33.1 after 10 transmissions"));
}

TEST_F(AcknowledgedSendTest, TheAckStopsTheRetransmissions) {
  link_a.set_connected(false);
  send_emergency(kDriver);
  time.advance(60ms);  // the transmissions at 0 and 50 ms are lost
  link_a.set_connected(true);
  time.advance(1s);
  EXPECT_EQ(emergency_sent_at, (std::vector<rt::Duration>{0ms, 50ms, 100ms}));
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::acknowledged);
  EXPECT_EQ(resolutions[0].transmissions, 3u);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
}

TEST_F(AcknowledgedSendTest, ANakRefusesTheCommand) {
  send_emergency(Address{1, 1, 50, 1});  // no such component on node a
  time.advance(1s);
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::refused);
  EXPECT_EQ(emergency_sent_at.size(), 1u);
}

TEST_F(AcknowledgedSendTest, ABroadcastIsSettledByTheFirstNodeThatAnswers) {
  send_emergency(Address{1, 255, 33, 1});
  time.advance(1s);
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::acknowledged);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
}

TEST_F(AcknowledgedSendTest, ALocalDestinationIsDeliveredAndAcknowledgedAtOnce) {
  a->send_acknowledged(header_to(Address{1, 1, 40, 1}, kDriver, msg::SetEmergency::code),
                       payload_of(msg::SetEmergency{}), kFast,
                       [this](const node::AckResolution& r) { resolutions.push_back(r); });
  EXPECT_TRUE(resolutions.empty());  // posted, not called during send_acknowledged
  time.run_ready();
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::acknowledged);
  EXPECT_EQ(resolutions[0].transmissions, 0u);
  EXPECT_EQ(link_a.packets_sent(), 0u);
  a->send_acknowledged(header_to(Address{1, 1, 40, 1}, Address{1, 1, 50, 1}, msg::SetEmergency::code),
                       payload_of(msg::SetEmergency{}), kFast,
                       [this](const node::AckResolution& r) { resolutions.push_back(r); });
  time.run_ready();
  ASSERT_EQ(resolutions.size(), 2u);
  EXPECT_EQ(resolutions[1].outcome, node::AckOutcome::refused);
}

TEST_F(AcknowledgedSendTest, WhatCannotBeTrackedIsNotSentAndExhaustedAtOnce) {
  std::vector<std::uint8_t> large(kMaxPayloadSize + 1);
  b->send_acknowledged(header_to(kOcu, kDriver, msg::SetEmergency::code), large, kFast,
                       [this](const node::AckResolution& r) { resolutions.push_back(r); });
  time.run_ready();
  ASSERT_EQ(resolutions.size(), 1u);
  EXPECT_EQ(resolutions[0].outcome, node::AckOutcome::exhausted);
  EXPECT_EQ(resolutions[0].transmissions, 0u);
  EXPECT_EQ(link_b.packets_sent(), 0u);
  EXPECT_EQ(b->counters().send_failures, 1u);
}

TEST_F(AcknowledgedSendTest, ATableFullOfPendingMessagesRefusesMore) {
  node::NodeConfig config;
  config.subsystem = 3;
  config.acks.max_pending = 1;
  testing::MemoryLink& link_c = network.attach(3, 1);
  node::Node c(config, time, time, link_c);
  std::vector<node::AckOutcome> outcomes;
  for (int i = 0; i < 2; ++i)
    c.send_acknowledged(header_to(Address{3, 1, 40, 1}, Address{9, 1, 33, 1}, msg::SetEmergency::code),
                        payload_of(msg::SetEmergency{}), kFast,
                        [&](const node::AckResolution& r) { outcomes.push_back(r.outcome); });
  time.run_ready();
  EXPECT_EQ(outcomes, (std::vector<node::AckOutcome>{node::AckOutcome::exhausted}));  // the second one
  EXPECT_EQ(link_c.packets_sent(), 1u);
  time.advance(1s);
  EXPECT_EQ(outcomes.size(), 2u);  // the first one, unanswered
}

TEST_F(AcknowledgedSendTest, TheCallbackMaySendAgain) {
  link_a.set_connected(false);
  int attempts = 0;
  std::function<void()> attempt = [&] {
    ++attempts;
    b->send_acknowledged(header_to(kOcu, kDriver, msg::SetEmergency::code), payload_of(msg::SetEmergency{}),
                         node::AckPolicy{50ms, 2}, [&](const node::AckResolution& r) {
                           resolutions.push_back(r);
                           if (r.outcome == node::AckOutcome::exhausted && attempts < 3) attempt();
                         });
  };
  attempt();
  time.advance(1s);
  EXPECT_EQ(attempts, 3);
  EXPECT_EQ(resolutions.size(), 3u);
  EXPECT_EQ(emergency_sent_at.size(), 6u);
  link_a.set_connected(true);
  attempt();
  time.advance(1s);
  ASSERT_EQ(resolutions.size(), 4u);
  EXPECT_EQ(resolutions[3].outcome, node::AckOutcome::acknowledged);
}

TEST_F(AcknowledgedSendTest, NoCallbackAfterTheNodeIsGone) {
  link_a.set_connected(false);
  send_emergency(kDriver);
  b->send_acknowledged(header_to(kOcu, Address{2, 1, 50, 1}, msg::SetEmergency::code), payload_of(msg::SetEmergency{}),
                       kFast, [this](const node::AckResolution& r) { resolutions.push_back(r); });  // posted
  link_b.on_receive({});
  b.reset();
  time.advance(2s);
  EXPECT_TRUE(resolutions.empty());
}

TEST_F(AcknowledgedSendTest, PlainAckRequestsKeepTheNodeWideDefault) {
  link_a.set_connected(false);
  Header h = header_to(kOcu, kDriver, msg::SetEmergency::code);
  h.ack_nak = AckNak::ack_requested;
  b->send(h, payload_of(msg::SetEmergency{}));
  time.advance(10s);
  EXPECT_EQ(emergency_sent_at, (std::vector<rt::Duration>{0s, 1s, 2s}));
  EXPECT_EQ(b->acks().counters().exhausted, 1u);
  EXPECT_TRUE(any_line_contains(logs, "after 3 transmissions"));
}

TEST_F(AcknowledgedSendTest, EachPeerCountsItsPacketsAndHowItsAckRequestsEnded) {
  send_emergency(kDriver);                  // ACKed
  send_emergency(Address{1, 1, 99, 1});     // no such component there: NAKed
  time.advance(100ms);
  link_a.set_connected(false);
  send_emergency(kDriver);                  // never answered: 10 transmissions
  time.advance(1s);
  ASSERT_EQ(resolutions.size(), 3u);
  const auto& peers = b->peer_counters().peers();
  ASSERT_EQ(peers.size(), 1u);
  const node::PeerCounts& a_seen_from_b = peers.at({1, 1});
  EXPECT_EQ(a_seen_from_b.packets_sent, 12u);
  EXPECT_EQ(a_seen_from_b.packets_received, 2u);  // the ACK and the NAK
  EXPECT_EQ(a_seen_from_b.acknowledged, 1u);
  EXPECT_EQ(a_seen_from_b.refused, 1u);
  EXPECT_EQ(a_seen_from_b.unacknowledged, 1u);
  EXPECT_EQ(a_seen_from_b.retransmissions, 9u);
  const node::PeerCounts& b_seen_from_a = a->peer_counters().peers().at({2, 1});
  EXPECT_EQ(b_seen_from_a.packets_received, 2u);  // the third never reached it
  EXPECT_EQ(b_seen_from_a.packets_sent, 2u);
}

TEST_F(AcknowledgedSendTest, CopiesOfACommandAlreadyHandledAreCountedForTheirSender) {
  link_b.set_loss(0, 1, 1);  // a's ACKs never reach b: b sends every copy
  b->send_acknowledged(header_to(kOcu, kDriver, msg::Resume::code), {}, kFast, {});
  time.advance(1s);
  const node::PeerCounts& b_seen_from_a = a->peer_counters().peers().at({2, 1});
  EXPECT_EQ(b_seen_from_a.packets_received, 10u);
  EXPECT_EQ(b_seen_from_a.duplicates, 9u);  // acted on once, ACKed ten times
  EXPECT_EQ(a->counters().duplicates_filtered, 9u);
}

TEST(PeerCounters, BeyondItsPeersItCountsTheRestTogetherAndBroadcastsAreNobodys) {
  node::PeerCounters counters(2);
  ++counters.of(Address{1, 1, 33, 1})->packets_received;
  ++counters.of(Address{1, 2, 1, 1})->packets_received;
  ++counters.of(Address{3, 1, 1, 1})->packets_received;  // a third node: the rest
  ++counters.of(Address{4, 1, 1, 1})->packets_received;
  ++counters.of(Address{1, 1, 1, 1})->packets_received;  // a known node's other component
  EXPECT_EQ(counters.peers().size(), 2u);
  EXPECT_EQ(counters.peers().at({1, 1}).packets_received, 2u);
  EXPECT_EQ(counters.others().packets_received, 2u);
  EXPECT_EQ(counters.of(Address{1, 255, 255, 255}), nullptr);
  EXPECT_EQ(counters.of(Address{255, 255, 255, 255}), nullptr);
}

}  // namespace
}  // namespace jaus::test
