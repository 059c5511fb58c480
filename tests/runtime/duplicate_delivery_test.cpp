// The node's receive path and the duplicate filter: a retransmitted copy of
// an ACK-requested message is ACKed again but not delivered again, except
// stops (issue 32). Packets are handed to the node as the network would.
#include "harness.hpp"
#include "jaus/node/node.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

const Address kOcu{2, 1, 40, 1};

class DuplicateDeliveryTest : public ::testing::Test {
 protected:
  DuplicateDeliveryTest() {
    node::NodeConfig config;
    config.subsystem = 1;
    a = std::make_unique<node::Node>(config, time, time, link_a);
    link_a.deliver_to(*a);
    rt::ComponentConfig driver_config;
    driver_config.address = kDriver;
    driver_config.name = "driver";
    driver_config.authority = 5;
    driver = &a->add_as(std::make_unique<TestDriver>(driver_config, a->environment()));
    link_a.on_transmit([this](const Header& h, std::span<const std::uint8_t>) {
      if (h.ack_nak == AckNak::ack || h.ack_nak == AckNak::nak) replies.push_back(h);
    });
  }

  template <class M>
  void receive(const M& m, std::uint16_t sequence, AckNak ack = AckNak::ack_requested, const Address& from = kOcu) {
    std::vector<std::uint8_t> bytes(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(m, std::span(bytes).subspan(kHeaderSize));
    ASSERT_TRUE(size);
    Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = kDriver;
    h.ack_nak = ack;
    h.sequence = sequence;
    h.data_size = static_cast<std::uint16_t>(*size);
    encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(bytes.data(), kHeaderSize));
    bytes.resize(kHeaderSize + *size);
    a->receive_bytes(bytes);
    time.advance(1ms);
  }

  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time, 1ms};
  testing::MemoryLink& link_a = network.attach(1, 1);
  std::unique_ptr<node::Node> a;
  TestDriver* driver = nullptr;
  std::vector<Header> replies;  // ACKs and NAKs node a sent
};

TEST_F(DuplicateDeliveryTest, ALateCopyOfAResumeCannotUndoALaterStandby) {
  receive(msg::RequestComponentControl{{10}}, 0, AckNak::none);
  ASSERT_TRUE(driver->control().is_controller(kOcu));
  receive(msg::Standby{}, 1);
  receive(msg::Resume{}, 2);  // its ACK is lost on the way back: the OCU sends it again...
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  receive(msg::Standby{}, 3);  // ...but meanwhile it has sent Standby
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::standby);
  const auto delivered = a->counters().delivered;
  receive(msg::Resume{}, 2);  // the late copy
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::standby);
  EXPECT_EQ(a->counters().delivered, delivered);
  EXPECT_EQ(a->counters().duplicates_filtered, 1u);
  // ACKed again: the sender stops retransmitting.
  ASSERT_EQ(replies.size(), 4u);
  EXPECT_EQ(replies.back().ack_nak, AckNak::ack);
  EXPECT_EQ(replies.back().command_code, msg::Resume::code);
  EXPECT_EQ(replies.back().sequence, 2);
  EXPECT_EQ(replies.back().source, kDriver);
  EXPECT_EQ(replies.back().destination, kOcu);
}

TEST_F(DuplicateDeliveryTest, StopsAreDeliveredEveryTime) {
  receive(msg::SetEmergency{}, 0);
  receive(msg::ClearEmergency{}, 1);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  // A restarted OCU reusing its ID starts again at sequence 0: its Set Emergency still stops.
  receive(msg::SetEmergency{}, 0);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
  EXPECT_EQ(a->counters().duplicates_filtered, 0u);
  EXPECT_EQ(a->counters().acks_sent, 3u);
}

TEST_F(DuplicateDeliveryTest, DifferentPayloadsAndLateCopiesAreDelivered) {
  receive(msg::QueryComponentStatus{}, 5);
  receive(msg::SetEmergency{}, 6);
  receive(msg::ClearEmergency{}, 7);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  receive(msg::SetEmergency{}, 8);
  msg::ClearEmergency other;
  other.emergency_code = 3;  // same sequence, another payload: another message
  receive(other, 7);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  receive(msg::SetEmergency{}, 9);
  time.advance(3s);  // outside the 2 s window: delivered
  receive(other, 7);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_EQ(a->counters().duplicates_filtered, 0u);
}

TEST_F(DuplicateDeliveryTest, OnlyAckRequestedMessagesAreFiltered) {
  receive(msg::SetEmergency{}, 0, AckNak::none);
  receive(msg::ClearEmergency{}, 1, AckNak::none);
  receive(msg::SetEmergency{}, 2, AckNak::none);
  receive(msg::ClearEmergency{}, 1, AckNak::none);  // not retransmitted by a node: delivered
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_EQ(a->counters().duplicates_filtered, 0u);
}

TEST_F(DuplicateDeliveryTest, ACopyForNoComponentIsNakedAgain) {
  std::vector<std::uint8_t> bytes(kHeaderSize);
  Header h;
  h.command_code = msg::QueryComponentStatus::code;
  h.source = kOcu;
  h.destination = Address{1, 1, 50, 1};
  h.ack_nak = AckNak::ack_requested;
  encode_header_unchecked(h, std::span(bytes).first<kHeaderSize>());
  a->receive_bytes(bytes);
  a->receive_bytes(bytes);  // both queued together: the second is the copy
  time.advance(1ms);
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_EQ(replies[0].ack_nak, AckNak::nak);
  EXPECT_EQ(replies[1].ack_nak, AckNak::nak);
  EXPECT_EQ(a->counters().duplicates_filtered, 1u);
  EXPECT_EQ(a->counters().undeliverable, 1u);
}

}  // namespace
}  // namespace jaus::test
