// An OcuSession attached to an injected link and clock (OcuSession::attach),
// and jaus::testing's memory network and virtual time helpers it runs on:
// waiting advances the virtual clock, exactly and without real time passing.
#include <chrono>

#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

using jaus::msg::QueryComponentStatus;
using jaus::msg::ReportComponentStatus;

TEST_F(VirtualOcuTest, ARequestIsAnsweredWithoutVirtualTimeLeftToRunDown) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  EXPECT_FALSE(ocu->on_udp());
  const auto start = time.now();
  auto reply = ocu->request(kCommunicator, QueryComponentStatus{}, {ReportComponentStatus::code}, 5s);
  ASSERT_TRUE(reply) << reply.error().message();
  EXPECT_EQ(reply->header.source, kCommunicator);
  EXPECT_LE(time.now() - start, 2ms);  // a step or two of virtual time, not the timeout
}

TEST_F(VirtualOcuTest, ATimeoutTakesExactlyItsVirtualTimeAndNoRealTime) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  const auto start = time.now();
  const auto real_start = std::chrono::steady_clock::now();
  auto reply = ocu->request(kNobody, QueryComponentStatus{}, {ReportComponentStatus::code}, 30s);
  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().code, jaus::ErrorCode::timeout);
  EXPECT_EQ(reply.error().message(), "no reply from 1.1.42.1 within 30 s");
  EXPECT_EQ(time.now() - start, 30s);
  EXPECT_LT(std::chrono::steady_clock::now() - real_start, 10s);  // 30 000 steps, no sleeping
}

TEST_F(VirtualOcuTest, AStopRequestEndsAWaitAndEveryLaterOne) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  const auto start = time.now();
  time.call_at(start + 250ms, [&] { ocu->request_stop(); });
  auto reply = ocu->request(kNobody, QueryComponentStatus{}, {ReportComponentStatus::code}, 30s);
  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().code, jaus::ErrorCode::interrupted);
  EXPECT_EQ(time.now() - start, 250ms);
  EXPECT_TRUE(ocu->interrupted());
  EXPECT_FALSE(ocu->run_until([] { return false; }, 1s));
  EXPECT_EQ(time.now() - start, 250ms);
}

TEST_F(VirtualOcuTest, AnAttachedSessionHasNoUdpLinkNorIoContext) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  EXPECT_EQ(ocu->udp_link(), nullptr);
  EXPECT_EQ(ocu->io_context(), nullptr);
  EXPECT_FALSE(ocu->on_udp());
}

TEST_F(VirtualOcuTest, AttachRefusesAnIncompleteEnvironmentAndABadAddress) {
  ocu::SessionOptions options;
  auto missing = ocu::OcuSession::attach(options, ocu::SessionEnvironment{&time, &time, nullptr, {}, {}});
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, jaus::ErrorCode::invalid_argument);
  options.self = jaus::Address{254, 1, 1, 1};  // component 1 is its node manager
  auto& link = network.attach(254, 1);
  auto manager = ocu::OcuSession::attach(
      options, ocu::SessionEnvironment{&time, &time, &link, [&](auto r) { link.on_receive(std::move(r)); },
                                       jaus::testing::stepper(time)});
  ASSERT_FALSE(manager);
  EXPECT_EQ(manager.error().code, jaus::ErrorCode::invalid_argument);
}

TEST_F(VirtualOcuTest, TheOcusNodeManagerAnswersForTheOcuNode) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto other = open_ocu(jaus::Address{254, 2, 40, 1});
  ASSERT_TRUE(other);
  auto reply = other->request(jaus::Address{254, 1, 1, 1}, jaus::msg::QueryIdentification{{2}},
                              {jaus::msg::ReportIdentification::code}, 1s);
  ASSERT_TRUE(reply) << reply.error().message();
  const auto id = jaus::wire::decode_payload<jaus::msg::ReportIdentification>(reply->payload);
  ASSERT_TRUE(id);
  EXPECT_EQ(id->identification, "jausctl");
}

TEST_F(VirtualOcuTest, APulledCableIsATimeout) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  target->go_silent();
  auto reply = ocu->request(kCommunicator, QueryComponentStatus{}, {ReportComponentStatus::code}, 1s);
  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().code, jaus::ErrorCode::timeout);
}

// The memory network on its own: addressing, latency, the cable, the helpers.
TEST(MemoryNetwork, DeliversByDestinationNodeAfterItsLatencyAndBroadcastsToEveryOtherNode) {
  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time, 5ms);
  auto& a = network.attach(1, 1);
  auto& b = network.attach(1, 2);
  auto& c = network.attach(2, 1);
  std::vector<std::pair<char, jaus::rt::TimePoint>> arrived;
  b.on_receive([&](std::span<const std::uint8_t>) { arrived.emplace_back('b', time.now()); });
  c.on_receive([&](std::span<const std::uint8_t>) { arrived.emplace_back('c', time.now()); });
  a.on_receive([&](std::span<const std::uint8_t>) { arrived.emplace_back('a', time.now()); });
  const std::vector<std::uint8_t> packet(jaus::kHeaderSize, 0);
  jaus::Header h;
  h.destination = jaus::Address{1, 2, 33, 1};
  a.transmit(h, packet);
  EXPECT_TRUE(arrived.empty());  // never during transmit()
  time.advance(4ms);
  EXPECT_TRUE(arrived.empty());
  time.advance(1ms);
  ASSERT_EQ(arrived.size(), 1u);
  EXPECT_EQ(arrived[0].first, 'b');

  arrived.clear();
  h.destination = jaus::Address{255, 255, 255, 255};
  a.transmit(h, packet);
  time.advance(5ms);
  ASSERT_EQ(arrived.size(), 2u);  // b and c, not the sender
  EXPECT_EQ(a.packets_sent(), 2u);
  EXPECT_EQ(b.packets_received() + c.packets_received(), 3u);

  arrived.clear();
  c.set_connected(false);
  a.transmit(h, packet);
  time.advance(5ms);
  ASSERT_EQ(arrived.size(), 1u);
  EXPECT_EQ(arrived[0].first, 'b');
}

TEST(VirtualTimeHelpers, RunUntilStopsWhenDoneOrAtTheLimit) {
  jaus::rt::VirtualTime time;
  bool flag = false;
  time.call_at(time.now() + 42ms, [&] { flag = true; });
  EXPECT_TRUE(jaus::testing::run_until(time, [&] { return flag; }, 1s));
  EXPECT_EQ(time.now().time_since_epoch(), 42ms);
  EXPECT_FALSE(jaus::testing::run_until(time, [] { return false; }, 100ms, 30ms));
  EXPECT_EQ(time.now().time_since_epoch(), 142ms);
  jaus::testing::run_for(time, 8ms);
  EXPECT_EQ(time.now().time_since_epoch(), 150ms);
  auto wait = jaus::testing::stepper(time, 10ms);
  wait(time.now() + 3ms);
  EXPECT_EQ(time.now().time_since_epoch(), 153ms);  // never beyond `until`
}

}  // namespace
}  // namespace jausctl::test
