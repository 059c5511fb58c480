// jaus::testing's memory network as a lossy radio link: MemoryLink::set_loss
// drops packets at random each way, the same ones for the same seed.
#include <gtest/gtest.h>

#include "jaus/base/virtual_time.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

Header to(std::uint8_t subsystem, std::uint16_t sequence) {
  Header h;
  h.command_code = 0x0006;
  h.source = Address{1, 1, 40, 1};
  h.destination = Address{subsystem, 1, 33, 1};
  h.sequence = sequence;
  return h;
}

struct TwoLinks {
  explicit TwoLinks(rt::VirtualTime& time) : network(time, time, 1ms) {
    receiver.on_receive([this](std::span<const std::uint8_t> packet) {
      arrived.push_back(decode_header(packet)->sequence);
    });
  }
  // `count` packets from sender to receiver, one header each (no payload).
  void send(std::uint16_t count) {
    for (std::uint16_t i = 0; i < count; ++i) {
      Header h = to(2, i);
      std::array<std::uint8_t, kHeaderSize> bytes{};
      encode_header_unchecked(h, bytes);
      sender.transmit(h, bytes);
    }
  }
  testing::MemoryNetwork network;
  testing::MemoryLink& sender = network.attach(1, 1);
  testing::MemoryLink& receiver = network.attach(2, 1);
  std::vector<std::uint16_t> arrived;
};

TEST(MemoryLinkLoss, DropsAboutTheRequestedShareEachWay) {
  rt::VirtualTime time;
  TwoLinks out(time), in(time);
  out.sender.set_loss(0.1, 0, 7);
  in.receiver.set_loss(0, 0.3, 7);
  out.send(10'000);
  in.send(10'000);
  time.advance(1s);
  EXPECT_NEAR(static_cast<double>(out.sender.packets_lost()), 1000, 150);
  EXPECT_EQ(out.arrived.size() + out.sender.packets_lost(), 10'000u);
  EXPECT_EQ(out.sender.packets_sent(), 10'000u);  // sent, then lost on the way
  EXPECT_NEAR(static_cast<double>(in.receiver.packets_lost()), 3000, 250);
  EXPECT_EQ(in.receiver.packets_received() + in.receiver.packets_lost(), 10'000u);
  EXPECT_EQ(in.receiver.packets_received(), in.arrived.size());
}

TEST(MemoryLinkLoss, TheSameSeedDropsTheSamePackets) {
  rt::VirtualTime time;
  TwoLinks first(time), second(time), other(time);
  first.sender.set_loss(0.2, 0.2, 42);
  second.sender.set_loss(0.2, 0.2, 42);
  other.sender.set_loss(0.2, 0.2, 43);
  for (auto* links : {&first, &second, &other}) links->send(1000);
  time.advance(1s);
  EXPECT_EQ(first.arrived, second.arrived);
  EXPECT_NE(first.arrived, other.arrived);
}

TEST(MemoryLinkLoss, NoLossByDefaultAndEverythingLostAtOne) {
  rt::VirtualTime time;
  TwoLinks lossless(time), cut(time);
  cut.receiver.set_loss(0, 1.0, 1);
  lossless.send(500);
  cut.send(500);
  time.advance(1s);
  EXPECT_EQ(lossless.arrived.size(), 500u);
  EXPECT_EQ(lossless.sender.packets_lost() + lossless.receiver.packets_lost(), 0u);
  EXPECT_TRUE(cut.arrived.empty());
  EXPECT_EQ(cut.receiver.packets_lost(), 500u);
  cut.receiver.set_loss(0, 0, 1);  // healed
  cut.send(10);
  time.advance(1s);
  EXPECT_EQ(cut.arrived.size(), 10u);
}

TEST(MemoryLinkLoss, OutOfRangeProbabilitiesAreClamped) {
  rt::VirtualTime time;
  TwoLinks links(time);
  links.sender.set_loss(-1, 2, 3);
  links.send(20);
  time.advance(1s);
  EXPECT_EQ(links.sender.packets_lost(), 0u);
  EXPECT_EQ(links.receiver.packets_lost(), 0u);  // inbound loss is the receiver's: the sender's 2 drops nothing here
  EXPECT_EQ(links.arrived.size(), 20u);
  links.receiver.set_loss(0, 2, 3);
  links.send(20);
  time.advance(1s);
  EXPECT_EQ(links.arrived.size(), 20u);
}

}  // namespace
}  // namespace jaus::test
