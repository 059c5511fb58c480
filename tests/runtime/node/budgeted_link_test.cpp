// The budgeted link (issue 45, step 2) under virtual time: the rate it keeps,
// the order its classes leave in, and what it drops or replaces.
#include "jaus/node/budgeted_link.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/core/stop_commands.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::node {
namespace {

using namespace std::chrono_literals;

const Address kVehicle{1, 1, 33, 1};
const Address kOcu{2, 1, 40, 1};
const Address kOtherComponent{1, 1, 37, 1};

// What reached the link below, and when.
struct Handed {
  Header header;
  std::size_t size;
  rt::TimePoint at;
  std::uint8_t first_byte;  // of the payload: which copy it was
};

class RecordingLink final : public Link {
 public:
  explicit RecordingLink(rt::Clock& clock) : clock_(clock) {}
  void transmit(const Header& header, std::span<const std::uint8_t> packet) override {
    handed.push_back({header, packet.size(), clock_.now(), packet.size() > kHeaderSize ? packet[kHeaderSize] : std::uint8_t{0}});
  }
  std::vector<Handed> handed;

 private:
  rt::Clock& clock_;
};

Header header_of(std::uint16_t code, Address to = kOcu, Address from = kVehicle) {
  Header h;
  h.command_code = code;
  h.destination = to;
  h.source = from;
  return h;
}

// The messages' own codes (their descriptions), never literals.
constexpr std::uint16_t kReportPose = msg::ReportGlobalPose::code;
constexpr std::uint16_t kReportVelocity = msg::ReportVelocityState::code;
constexpr std::uint16_t kReportImage = msg::ReportImage::code;
constexpr std::uint16_t kSetWrenchEffort = msg::SetWrenchEffort::code;
constexpr std::uint16_t kQueryStatus = msg::QueryComponentStatus::code;
constexpr std::uint16_t kSetEmergency = msg::SetEmergency::code;

class BudgetedLinkTest : public ::testing::Test {
 protected:
  // 256 kbit/s: 32,000 bytes a second; a 968-byte packet costs 1,000 with its overhead.
  SendBudgetOptions radio() {
    SendBudgetOptions o;
    o.bits_per_second = 256'000;
    o.burst_bytes = 1000;
    o.overhead_bytes = 32;
    return o;
  }
  void send(BudgetedLink& link, Header h, std::size_t size, std::uint8_t mark = 0) {
    std::vector<std::uint8_t> packet(size, 0);
    if (size > kHeaderSize) packet[kHeaderSize] = mark;
    link.transmit(h, packet);
  }
  std::vector<std::uint16_t> codes() const {
    std::vector<std::uint16_t> out;
    for (const auto& h : below.handed) out.push_back(h.header.command_code);
    return out;
  }

  rt::VirtualTime time;
  RecordingLink below{time};
};

TEST_F(BudgetedLinkTest, WithoutARateEverythingGoesThroughAtOnce) {
  BudgetedLink link(below, time, time, SendBudgetOptions{});
  for (int i = 0; i < 100; ++i) send(link, header_of(kReportImage), 4000);
  EXPECT_EQ(below.handed.size(), 100u);
  EXPECT_EQ(link.counters().queued_packets, 0u);
}

TEST_F(BudgetedLinkTest, HandsTheLinkNoMoreThanTheRate) {
  BudgetedLink link(below, time, time, radio());
  for (int i = 0; i < 100; ++i) send(link, header_of(kQueryStatus), 968);
  // The burst (1,000 bytes) lets one go at once, and a second into debt.
  EXPECT_EQ(below.handed.size(), 2u);
  time.advance(1s);
  // 32,000 bytes a second: 32 more packets of 1,000.
  EXPECT_GE(below.handed.size(), 33u);
  EXPECT_LE(below.handed.size(), 35u);
  // Evenly: each 1,000-byte packet 31.25 ms after the one before.
  const auto gap = below.handed[10].at - below.handed[9].at;
  EXPECT_GE(gap, 31ms);
  EXPECT_LE(gap, 32ms);
  time.advance(3s);
  EXPECT_EQ(below.handed.size(), 100u);
  EXPECT_EQ(link.counters().of(SendClass::status).waited, 98u);
  EXPECT_EQ(link.counters().queued_bytes, 0u);
}

TEST_F(BudgetedLinkTest, AStopNeverWaitsAndDropsTheCommandsWaitingForItsComponent) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kReportImage), 4000);  // the budget is in debt now
  send(link, header_of(kSetWrenchEffort, kVehicle, kOcu), 100, 1);
  send(link, header_of(kSetWrenchEffort, kOtherComponent, kOcu), 100, 2);
  send(link, header_of(kSetWrenchEffort, kVehicle, kOcu), 100, 3);
  ASSERT_EQ(below.handed.size(), 1u);
  auto stop = header_of(kSetEmergency, kVehicle, kOcu);
  stop.priority = priority::kSafetyCritical;
  send(link, stop, 17);
  ASSERT_EQ(below.handed.size(), 2u);
  EXPECT_EQ(below.handed[1].header.command_code, kSetEmergency);
  EXPECT_EQ(below.handed[1].at, below.handed[0].at);
  // The efforts to the stopped component were issued before the stop: arriving after it, they must not go.
  time.advance(2s);
  ASSERT_EQ(below.handed.size(), 3u);
  EXPECT_EQ(below.handed[2].header.destination, kOtherComponent);
  EXPECT_EQ(link.counters().of(SendClass::command).superseded, 2u);
  EXPECT_EQ(link.counters().of(SendClass::stop).waited, 0u);
}

TEST_F(BudgetedLinkTest, TheAckOfAStopIsNotAStopAndDropsNothing) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kReportImage), 4000);
  send(link, header_of(kSetWrenchEffort, kOcu, kVehicle), 100);
  auto ack = header_of(kSetEmergency, kOcu, kVehicle);
  ack.ack_nak = AckNak::ack;
  send(link, ack, 16);
  EXPECT_EQ(below.handed.size(), 2u);  // the ACK went at once
  time.advance(1s);
  EXPECT_EQ(below.handed.size(), 3u);  // and the command waiting for the OCU still went
}

TEST_F(BudgetedLinkTest, ClassesLeaveCommandsFirstImagesLast) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kReportImage), 4000);  // into debt
  send(link, header_of(kReportImage, kOcu, kOtherComponent), 3000);
  auto pose = header_of(kReportPose);
  pose.service_connection = true;
  send(link, pose, 60);
  send(link, header_of(kReportPose), 60);
  send(link, header_of(kSetWrenchEffort, kVehicle, kOcu), 60);
  time.advance(2s);
  EXPECT_EQ(codes(),
            (std::vector<std::uint16_t>{kReportImage, kSetWrenchEffort, kReportPose, kReportPose, kReportImage}));
  EXPECT_FALSE(below.handed[2].header.service_connection);  // status before connection reports
  EXPECT_TRUE(below.handed[3].header.service_connection);
}

TEST_F(BudgetedLinkTest, OnlyTheNewestReportOfAConnectionWaitsInTheOldestsPlace) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kReportImage), 4000);  // into debt
  auto pose = header_of(kReportPose);
  pose.service_connection = true;
  auto velocity = header_of(kReportVelocity);
  velocity.service_connection = true;
  for (std::uint8_t i = 1; i <= 5; ++i) {
    send(link, pose, 60, i);
    if (i == 1) send(link, velocity, 60, 9);  // after the first pose: goes after the newest
  }
  time.advance(1s);
  ASSERT_EQ(below.handed.size(), 3u);
  EXPECT_EQ(below.handed[1].header.command_code, kReportPose);
  EXPECT_EQ(below.handed[1].first_byte, 5);  // the newest
  EXPECT_EQ(below.handed[2].first_byte, 9);
  EXPECT_EQ(link.counters().of(SendClass::connection).superseded, 4u);
}

TEST_F(BudgetedLinkTest, AFrameOnItsWayIsFinishedAndOnlyTheNewestWaits) {
  BudgetedLink link(below, time, time, radio());
  auto packet_of = [&](DataFlag flag, std::uint8_t frame) {
    auto h = header_of(kReportImage);
    h.data_flag = flag;
    send(link, h, 4000, frame);
  };
  // Three frames of three packets each, handed over at once: the first
  // starts, the second is replaced by the third while waiting.
  for (std::uint8_t frame = 1; frame <= 3; ++frame) {
    packet_of(DataFlag::first, frame);
    packet_of(DataFlag::middle, frame);
    packet_of(DataFlag::last, frame);
  }
  time.advance(2s);
  ASSERT_EQ(below.handed.size(), 6u);
  const std::vector<std::uint8_t> frames{1, 1, 1, 3, 3, 3};
  for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(below.handed[i].first_byte, frames[i]) << i;
  EXPECT_EQ(below.handed[3].header.data_flag, DataFlag::first);
  EXPECT_EQ(below.handed[5].header.data_flag, DataFlag::last);
  EXPECT_EQ(link.counters().of(SendClass::bulk).superseded, 3u);
}

TEST_F(BudgetedLinkTest, NothingWaitsBehindAFrame) {
  BudgetedLink link(below, time, time, radio());
  auto h = header_of(kReportImage);
  h.data_flag = DataFlag::first;
  send(link, h, 4000);
  h.data_flag = DataFlag::middle;
  for (int i = 0; i < 10; ++i) send(link, h, 4000);
  ASSERT_EQ(below.handed.size(), 1u);
  send(link, header_of(kReportPose), 60);
  // The report goes as soon as the debt of the one packet already sent is
  // paid (3,032 bytes beyond the burst: 95 ms), before the frame's next packet.
  time.advance(96ms);
  ASSERT_GE(below.handed.size(), 2u);
  EXPECT_EQ(below.handed[1].at - below.handed[0].at, 94750us);
  EXPECT_EQ(below.handed[1].header.command_code, kReportPose);
}

TEST_F(BudgetedLinkTest, AFullClassDropsWhatDoesNotFitAndCountsIt) {
  auto options = radio();
  options.queue_bytes = 1000;
  BudgetedLink link(below, time, time, options);
  send(link, header_of(kSetEmergency), 4000);  // into debt (a stop is charged, never queued)
  for (int i = 0; i < 20; ++i) send(link, header_of(kQueryStatus), 100);
  EXPECT_EQ(link.counters().of(SendClass::status).dropped, 10u);
  EXPECT_EQ(link.counters().queued_packets, 10u);
  time.advance(1s);
  EXPECT_EQ(below.handed.size(), 11u);
  EXPECT_GE(link.counters().longest_wait, 30ms);
}

// The one list of stops names the messages' own codes.
static_assert(is_stop_command(msg::SetEmergency::code) && is_stop_command(msg::Standby::code) &&
              is_stop_command(msg::Shutdown::code));
static_assert(!is_stop_command(msg::Resume::code) && !is_stop_command(msg::ClearEmergency::code));

TEST_F(BudgetedLinkTest, ClassifiesByHeader) {
  const SendBudgetOptions o;
  EXPECT_EQ(send_class_of(header_of(msg::ClearEmergency::code), 20, o), SendClass::stop);
  EXPECT_EQ(send_class_of(header_of(msg::Resume::code), 16, o), SendClass::stop);  // never overtakes a Standby
  auto urgent = header_of(kReportPose);
  urgent.priority = 12;
  EXPECT_EQ(send_class_of(urgent, 60, o), SendClass::stop);
  EXPECT_EQ(send_class_of(header_of(msg::RequestComponentControl::code), 20, o), SendClass::command);
  EXPECT_EQ(send_class_of(header_of(kQueryStatus), 16, o), SendClass::status);
  EXPECT_EQ(send_class_of(header_of(kReportImage), 900, o), SendClass::status);
  EXPECT_EQ(send_class_of(header_of(kReportImage), 2000, o), SendClass::bulk);
  auto part = header_of(kReportPose);
  part.data_flag = DataFlag::last;
  EXPECT_EQ(send_class_of(part, 60, o), SendClass::bulk);
  // A large command (a long path, say) is a command: never replaced by a newer one.
  auto path = header_of(kSetWrenchEffort);
  path.data_flag = DataFlag::first;
  EXPECT_EQ(send_class_of(path, 4000, o), SendClass::command);
}

TEST_F(BudgetedLinkTest, LargeCommandsAllGoInOrderNoneReplaced) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kReportImage), 4000);  // into debt
  for (std::uint8_t i = 1; i <= 3; ++i) {
    auto h = header_of(kSetWrenchEffort, kVehicle, kOcu);
    h.data_flag = DataFlag::first;
    send(link, h, 2000, i);
    h.data_flag = DataFlag::last;
    send(link, h, 500, i);
  }
  time.advance(2s);
  ASSERT_EQ(below.handed.size(), 7u);
  const std::vector<std::uint8_t> order{1, 1, 2, 2, 3, 3};
  for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(below.handed[i + 1].first_byte, order[i]) << i;
  EXPECT_EQ(link.counters().of(SendClass::command).superseded, 0u);
}

TEST_F(BudgetedLinkTest, APacketSentAgainOnRequestReplacesNoFrame) {
  BudgetedLink link(below, time, time, radio());
  send(link, header_of(kQueryStatus), 968);
  send(link, header_of(kQueryStatus), 968);  // into debt
  auto frame = header_of(kReportImage);
  send(link, frame, 3000, 1);  // a whole frame, waiting
  auto again = frame;
  again.data_flag = DataFlag::retransmitted;
  send(link, again, 3000, 2);
  time.advance(2s);
  ASSERT_EQ(below.handed.size(), 4u);
  EXPECT_EQ(below.handed[2].first_byte, 1);
  EXPECT_EQ(below.handed[3].first_byte, 2);
  EXPECT_EQ(link.counters().of(SendClass::bulk).superseded, 0u);
}

}  // namespace
}  // namespace jaus::node
