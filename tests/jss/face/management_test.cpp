// Management through the face: the RA component's lifecycle and emergency
// latch, with JSS Report Status; a JSS stop holds until that client clears.
#include "face_node.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;
constexpr std::uint8_t kReady = 1;
constexpr std::uint8_t kStandby = 2;
constexpr std::uint8_t kEmergency = 5;

TEST(JssFaceManagement, StandbyAndResumeFromTheControllerWithReportStatus) {
  FaceNode node;
  EXPECT_EQ(node.status_of(kClientA, kDriver), kReady);
  // Standby only stops: RA obeys it from anyone (JSS would ignore it from a
  // non-controller; the stop wins). Resume is the controller's.
  node.send(kClientA, kDriver, msg::Standby{});
  node.run_for(50ms);
  EXPECT_EQ(node.status_of(kClientA, kDriver), kStandby);
  node.send(kClientA, kDriver, msg::Resume{});
  node.run_for(50ms);
  EXPECT_EQ(node.status_of(kClientA, kDriver), kStandby);

  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  node.send(kClientA, kDriver, msg::Resume{});
  node.run_for(50ms);
  EXPECT_EQ(node.status_of(kClientA, kDriver), kReady);
  node.send(kClientA, kDriver, msg::Standby{});
  node.run_for(50ms);
  EXPECT_EQ(node.status_of(kClientA, kDriver), kStandby);
  node.send(kClientA, kDriver, msg::Resume{});
  node.run_for(50ms);
  EXPECT_EQ(node.status_of(kClientA, kDriver), kReady);
  const auto raw = node.ask<msg::ReportStatus>(kClientA, kDriver, msg::QueryStatus{});
  ASSERT_TRUE(raw.has_value());
  EXPECT_EQ(raw->reserved, 0u);
}

TEST(JssFaceManagement, AJssStopHoldsUntilThatClientClearsIt) {
  FaceNode node;
  node.send(kClientA, kDriver, msg::SetEmergency{{1}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
  EXPECT_EQ(node.status_of(kClientB, kDriver), kEmergency);

  // Another JSS client's Clear does not undo it, nor does an RA peer's.
  node.send(kClientB, kDriver, msg::ClearEmergency{{1}});
  node.send_ra(kRaDriver, jaus::msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);

  // A second component of the same client node (its alias node) is not that sender either.
  node.send(jss::JssId{42, 1, 2}, kDriver, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);

  node.send(kClientA, kDriver, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_NE(node.driver().state(), rt::PrimaryStatus::emergency);
}

// Issue 42: a JSS holder restored at start gets its alias slot back before
// anyone is heard. Another client is given another slot and its Clear
// Emergency releases nothing; the holder's own clear does.
TEST(JssFaceManagement, AReservedSlotIsItsClientsAndNoOtherClientsClearReleasesIt) {
  FaceNode node;
  const Address holder_alias{250, 1, kClientA.component, 1};
  ASSERT_TRUE(node.face().reserve_client(1, kClientA));
  EXPECT_FALSE(node.face().reserve_client(1, kClientB));  // the slot is another client node's
  EXPECT_FALSE(node.face().reserve_client(200, kClientB));  // beyond max_clients
  // The hold as restored at start: held by the alias (the host restores the latch's holders).
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(jaus::msg::SetEmergency{{1}}, payload);
  ASSERT_TRUE(size.has_value());
  Header h;
  h.command_code = jaus::msg::SetEmergency::code;
  h.source = holder_alias;
  h.destination = kRaDriver;
  h.data_size = static_cast<std::uint16_t>(*size);
  node.host().node().receive(PacketView{h, std::span(payload).first(*size)});
  node.run_for(50ms);
  ASSERT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
  node.send(kClientB, kDriver, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
  EXPECT_EQ(node.face().client_of_alias(Address{250, 2, kClientB.component, 1}), kClientB);
  EXPECT_EQ(node.face().client_of_alias(holder_alias), kClientA);
  node.send(kClientA, kDriver, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_NE(node.driver().state(), rt::PrimaryStatus::emergency);
}

TEST(JssFaceManagement, ABroadcastSetEmergencyStopsEveryComponentAndIsNotAcknowledged) {
  FaceNode node;
  node.send(kClientA, kEveryone, msg::SetEmergency{{1}}, /*ack=*/true);
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
  EXPECT_EQ(node.host().node().find(Address{1, 1, 42, 1})->state(), rt::PrimaryStatus::emergency);
  EXPECT_TRUE(node.acks().empty());
  node.send(kClientA, kEveryone, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_NE(node.driver().state(), rt::PrimaryStatus::emergency);
}

TEST(JssFaceManagement, AJssStopHoldsWhileTheClientIsSilent) {
  FaceNode node;
  node.send(kClientA, kDriver, msg::SetEmergency{{1}});
  node.run_for(60s);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
  // Its alias slot is kept (the node holds state for it): its Clear still counts.
  node.send(kClientA, kDriver, msg::ClearEmergency{{1}});
  node.run_for(50ms);
  EXPECT_NE(node.driver().state(), rt::PrimaryStatus::emergency);
}

}  // namespace
}  // namespace jaus::test
