// The face's transport part: ACK, duplicates, large messages both ways,
// malformed input, the bounded alias slots.
#include <algorithm>

#include "face_node.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;

TEST(JssFaceTransport, AnAckRequestedMessageIsAnsweredAfterDelivery) {
  FaceNode node;
  const std::uint16_t sequence = node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, /*ack=*/true);
  node.run_for(20ms);
  ASSERT_EQ(node.acks().size(), 1u);
  const jss::JudpHeader& ack = node.acks()[0];
  EXPECT_EQ(ack.sequence, sequence);
  EXPECT_EQ(ack.destination, kClientA);
  EXPECT_EQ(ack.source, kDriver);
  EXPECT_EQ(node.counters().acks_sent, 1u);
  EXPECT_TRUE(node.take<msg::ReportHeartbeatPulse>(kClientA, kDriver).has_value());
  // Broadcasts are not acknowledged (as JRM).
  node.send(kClientA, kEveryone, msg::QueryHeartbeatPulse{}, /*ack=*/true);
  node.run_for(20ms);
  EXPECT_EQ(node.acks().size(), 1u);
}

TEST(JssFaceTransport, ACopyIsAcknowledgedButNotActedOnExceptAStop) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  const std::uint16_t sequence = node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true);
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, sequence);
  node.run_for(20ms);
  EXPECT_EQ(node.counters().duplicates, 1u);
  EXPECT_EQ(node.acks().size(), 2u);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientA).size(), 1u);

  // The same sequence number from another client is no copy.
  node.send(kClientB, kDriver, msg::QueryHeartbeatPulse{}, false, sequence);
  node.run_for(20ms);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientB).size(), 1u);

  // A copy of Set Emergency is acted on (the stop is never lost to the filter).
  const auto to_ra = node.counters().messages_to_ra;
  const std::uint16_t stop = node.send(kClientA, kDriver, msg::SetEmergency{{1}});
  node.send(kClientA, kDriver, msg::SetEmergency{{1}}, false, stop);
  node.run_for(20ms);
  EXPECT_EQ(node.counters().messages_to_ra, to_ra + 2);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
}

// Issue 43: Jr numbers from 1 on every start. A client restarted within
// the window is a new session: its messages act at once, never ACKed and dropped.
TEST(JssFaceTransport, AClientRestartedWithSequenceOneWithinTheWindowHasItsRequestControlObeyed) {
  FaceNode node;
  const auto confirmed = [&] { return node.take<msg::ConfirmControl>(kClientA, kDriver); };
  // The first run: control, a query, control released.
  node.send(kClientA, kDriver, msg::RequestControl{{5}}, /*ack=*/true, 1);
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 2);
  node.send(kClientA, kDriver, msg::ReleaseControl{}, true, 3);
  node.run_for(50ms);
  ASSERT_TRUE(confirmed().has_value());
  ASSERT_FALSE(node.driver().control().controller().has_value());
  node.clear();
  // Restarted half a second later: the same messages under the same numbers.
  node.run_for(500ms);
  node.send(kClientA, kDriver, msg::RequestControl{{5}}, true, 1);
  node.run_for(50ms);
  const auto confirm = confirmed();
  ASSERT_TRUE(confirm.has_value()) << "the restarted client's Request Control was dropped as a copy";
  EXPECT_EQ(confirm->response_code, msg::confirm_control::kControlAccepted);
  EXPECT_TRUE(node.driver().control().controller().has_value());
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 2);
  node.run_for(50ms);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientA).size(), 1u);
  EXPECT_EQ(node.counters().duplicates, 0u);
  EXPECT_EQ(node.counters().new_sessions, 1u);
  EXPECT_EQ(node.acks().size(), 5u);  // every one ACKed
}

// A number reused for another message within the window is a new session too.
TEST(JssFaceTransport, AMessageDifferingFromTheOneRememberedUnderItsNumberIsActedOn) {
  FaceNode node;
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 7);
  node.send(kClientA, kDriver, msg::RequestControl{{5}}, true, 7);
  node.run_for(50ms);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientA).size(), 1u);
  EXPECT_TRUE(node.take<msg::ConfirmControl>(kClientA, kDriver).has_value());
  EXPECT_EQ(node.counters().duplicates, 0u);
  EXPECT_EQ(node.counters().new_sessions, 1u);
}

TEST(JssFaceTransport, ATrueRetransmissionWithin3sIsAcknowledgedAndNotDeliveredAgain) {
  FaceNode node;
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 40);
  node.run_for(1s);
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 40);
  // A copy still comes after newer messages of the same sender (the ACK of
  // 40 lost, 41 sent meanwhile): not delivered again either.
  node.send(kClientA, kDriver, msg::QueryStatus{}, true, 41);
  node.run_for(1s);
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 40);
  node.run_for(50ms);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientA).size(), 1u);
  EXPECT_EQ(node.counters().duplicates, 2u);
  EXPECT_EQ(node.acks().size(), 4u);
  const bool logged = std::any_of(node.log().begin(), node.log().end(), [](const std::string& line) {
    return line.find("JSS client 42.1.1") != std::string::npos &&
           line.find("sequence number 40: a copy of one delivered; acknowledged, not acted on") != std::string::npos;
  });
  EXPECT_TRUE(logged) << "the drop is not logged";
  // The window is 3 s (Jr's own): after it the same number and contents are a new message.
  node.run_for(3s);
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, true, 40);
  node.run_for(50ms);
  EXPECT_EQ(node.take_all<msg::ReportHeartbeatPulse>(kClientA).size(), 1u);
  EXPECT_EQ(node.counters().duplicates, 2u);
}

// Safety before the restart rule: a copy that a stop followed never acts,
// even under a number a restarted client would use.
TEST(JssFaceTransport, ALateCopyOfAResumeDoesNotActAfterALaterStandby) {
  for (const std::uint16_t first : {std::uint16_t{1}, std::uint16_t{300}}) {
    SCOPED_TRACE("Resume's sequence number " + std::to_string(first));
    FaceNode node;
    ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
    node.send(kClientA, kDriver, msg::Standby{}, true, static_cast<std::uint16_t>(first + 100));
    ASSERT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::standby; }));
    node.send(kClientA, kDriver, msg::Resume{}, true, first);
    ASSERT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::ready; }));
    node.send(kClientA, kDriver, msg::Standby{}, true, static_cast<std::uint16_t>(first + 1));
    ASSERT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::standby; }));
    // The Resume's ACK was lost: its copy arrives after the Standby.
    const auto acks = node.acks().size();
    node.send(kClientA, kDriver, msg::Resume{}, true, first);
    node.run_for(200ms);
    EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::standby);
    EXPECT_EQ(node.acks().size(), acks + 1);  // still acknowledged: the sender stops retransmitting
    EXPECT_EQ(node.counters().duplicates, 1u);
    // A copy of the Standby is acted on (a stop is never taken for a copy).
    node.send(kClientA, kDriver, msg::Standby{}, true, static_cast<std::uint16_t>(first + 1));
    node.run_for(50ms);
    EXPECT_EQ(node.counters().duplicates, 1u);
    // A Resume the client sends now (a new number) acts.
    node.send(kClientA, kDriver, msg::Resume{}, true, static_cast<std::uint16_t>(first + 2));
    EXPECT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::ready; }));
  }
}

// A new session forgets what its client sent before, except what a stop
// followed: a copy of that still never acts.
TEST(JssFaceTransport, ARestartDoesNotLetALateCopyAct) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  node.send(kClientA, kDriver, msg::Standby{}, true, 20);
  node.send(kClientA, kDriver, msg::Resume{}, true, 21);
  ASSERT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::ready; }));
  node.send(kClientA, kDriver, msg::Standby{}, true, 22);
  ASSERT_TRUE(node.run_until([&] { return node.driver().state() == rt::PrimaryStatus::standby; }));
  node.send(kClientA, kDriver, msg::QueryHeartbeatPulse{}, false, 0);  // numbering from 0 again: a new session
  node.send(kClientA, kDriver, msg::Resume{}, true, 21);                // the first run's Resume, late
  node.run_for(200ms);
  EXPECT_EQ(node.counters().new_sessions, 1u);
  EXPECT_EQ(node.counters().duplicates, 1u);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::standby);
}

// The datagrams of a Register Services from client A to the node manager,
// 200 bytes of contents each (several), numbered from `sequence`.
std::vector<std::vector<std::uint8_t>> registration_pieces(std::uint16_t sequence) {
  msg::RegisterServices registration;
  for (int i = 0; i < 40; ++i) registration.services.push_back({"urn:example:service:" + std::to_string(i), 1, 0});
  jss::JudpHeader h;
  h.source = kClientA;
  h.destination = kNodeManager;
  h.sequence = sequence;
  auto datagrams = jss::make_judp_datagrams(h, jss::encode_contents(registration), 200);
  EXPECT_TRUE(datagrams.has_value());
  EXPECT_GT(datagrams->size(), 3u);
  return datagrams ? std::move(*datagrams) : std::vector<std::vector<std::uint8_t>>{};
}

TEST(JssFaceTransport, LargeMessagesBothWays) {
  jss_face::FaceConfig config;
  config.max_packet_contents = 64;  // Report Services is several packets
  FaceNode node(config);
  const auto before = node.datagrams_sent();
  const auto report = node.ask<msg::ReportServices>(kClientA, kNodeManager, msg::QueryServices{});
  ASSERT_TRUE(report.has_value());  // put back together by the test's reassembler
  EXPECT_GT(node.datagrams_sent() - before, 2u);
  EXPECT_EQ(node.counters().large_messages_sent, 1u);

  // In: a Register Services over several packets.
  for (const auto& d : registration_pieces(500)) node.receive(d);
  EXPECT_EQ(node.counters().large_messages_received, 1u);
  EXPECT_EQ(node.counters().malformed, 0u);
  EXPECT_EQ(node.counters().unsupported, 0u);

  // A middle packet with no first is held for its first (pieces come in any
  // order), never acted on; a second last piece contradicts its set: dropped.
  const auto later = registration_pieces(900);
  ASSERT_GT(later.size(), 1u);
  node.receive(later[1]);
  EXPECT_EQ(node.counters().large_messages_received, 1u);
  EXPECT_EQ(node.counters().malformed, 0u);
  EXPECT_EQ(node.face().large_message_counters().completed, 1u);
  jss::JudpHeader stray;
  stray.source = kClientA;
  stray.destination = kNodeManager;
  stray.data_flag = jss::JudpDataFlag::last;
  stray.sequence = 910;
  node.receive(jss::make_judp_datagram(stray, std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(node.counters().malformed, 0u);
  stray.sequence = 911;
  node.receive(jss::make_judp_datagram(stray, std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(node.counters().malformed, 1u);
  EXPECT_EQ(node.face().large_message_counters().stray, 1u);
}

// JSS peers are taken as RA peers are: the pieces of a large message in any
// order, a copied piece taken once; and a stop between them acts at once.
TEST(JssFaceTransport, ALargeMessageIsTakenInAnyOrderOnceAndAStopNeverWaitsForIt) {
  FaceNode node;
  const auto pieces = registration_pieces(500);
  ASSERT_GT(pieces.size(), 3u);
  node.receive(pieces.back());
  node.send(kClientA, kDriver, msg::SetEmergency{{1}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);  // the set still incomplete
  for (std::size_t i = pieces.size() - 2; i >= 1; --i) node.receive(pieces[i]);
  node.receive(pieces[1]);  // a copy (no ACK asked: past the duplicate filter)
  EXPECT_EQ(node.counters().large_messages_received, 0u);
  node.receive(pieces.front());  // the first piece, last
  EXPECT_EQ(node.counters().large_messages_received, 1u);
  node.receive(pieces.front());  // a late copy
  node.run_for(50ms);
  EXPECT_EQ(node.counters().large_messages_received, 1u);
  EXPECT_EQ(node.counters().malformed, 0u);
  EXPECT_EQ(node.counters().unsupported, 0u);
  EXPECT_EQ(node.face().large_message_counters().completed, 1u);
  EXPECT_EQ(node.face().large_message_counters().duplicates, 2u);
  EXPECT_EQ(node.counters().duplicates, 2u);
}

// A large message is as trusted as its least trusted piece, whichever piece
// completes it (as an RA large data set: StandingNodeTest.ALargeDataSetTakes
// TheLeastStandingOfItsPackets): a Request Control whose first piece came from
// outside transport.control_from takes no control, though its last piece was trusted.
TEST(JssFaceTransport, ALargeMessageIsAsTrustedAsItsLeastTrustedPiece) {
  FaceNode node;
  jss::JudpHeader h;
  h.source = kClientA;
  h.destination = kDriver;
  h.sequence = 70;
  // Request Control (message ID, authority) in two pieces: the ID, then the authority.
  auto pieces = jss::make_judp_datagrams(h, jss::encode_contents(msg::RequestControl{{5}}), 2);
  ASSERT_TRUE(pieces);
  ASSERT_EQ(pieces->size(), 2u);
  node.receive(pieces->front(), rt::SenderStanding::observer);
  node.receive(pieces->back(), rt::SenderStanding::trusted);
  ASSERT_TRUE(node.run_until([&] { return node.count(kClientA, msg::ConfirmControl::code) > 0; }));
  EXPECT_EQ(node.take<msg::ConfirmControl>(kClientA, kDriver)->response_code, msg::confirm_control::kNotAvailable);
  EXPECT_FALSE(node.driver().control().controller().has_value());
  EXPECT_EQ(node.counters().large_messages_received, 1u);

  // The same message, every piece trusted: control.
  h.sequence = 80;
  pieces = jss::make_judp_datagrams(h, jss::encode_contents(msg::RequestControl{{5}}), 2);
  ASSERT_TRUE(pieces);
  for (const auto& piece : *pieces) node.receive(piece, rt::SenderStanding::trusted);
  ASSERT_TRUE(node.run_until([&] { return node.count(kClientA, msg::ConfirmControl::code) > 0; }));
  EXPECT_EQ(node.take<msg::ConfirmControl>(kClientA, kDriver)->response_code, msg::confirm_control::kControlAccepted);
  EXPECT_TRUE(node.driver().control().controller().has_value());
}

TEST(JssFaceTransport, MalformedInputIsCountedLoggedAndNeverActedOn) {
  FaceNode node;
  const std::vector<std::uint8_t> not_as5669a = {0x01, 0x00, 0x11};
  node.receive(not_as5669a);
  jss::JudpHeader h;
  h.source = kClientA;
  h.destination = kDriver;
  // Request Control with two bytes of body.
  node.receive(jss::make_judp_datagram(h, std::vector<std::uint8_t>{0x0D, 0x00, 5, 5}));
  // A source that is a wildcard.
  h.source = jss::JssId{42, 1, 255};
  node.receive(jss::make_judp_datagram(h, jss::encode_contents(msg::RequestControl{{5}})));
  // One byte of contents.
  h.source = kClientA;
  node.receive(jss::make_judp_datagram(h, std::vector<std::uint8_t>{0x0D}));
  node.run_for(50ms);
  EXPECT_EQ(node.counters().malformed, 4u);
  EXPECT_EQ(node.counters().datagrams_received, 4u);
  EXPECT_FALSE(node.driver().control().controller().has_value());
  EXPECT_TRUE(node.received().empty());
  EXPECT_FALSE(node.log().empty());

  // Not for us, and a message no service handles.
  node.send(kClientA, jss::JssId{1, 1, 99}, msg::QueryHeartbeatPulse{});
  node.send(kClientA, kDriver, msg::QueryElementCount{});
  EXPECT_EQ(node.counters().not_for_us, 1u);
  EXPECT_EQ(node.counters().unsupported, 1u);
}

TEST(JssFaceTransport, AFullSlotTableRefusesANewClientButNeverItsStop) {
  jss_face::FaceConfig config;
  config.max_clients = 2;
  FaceNode node(config);
  // Two clients hold state (control): their slots are kept.
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  ASSERT_EQ(node.request_control(kClientB, kVelocity, 5), msg::confirm_control::kControlAccepted);
  // A third is refused what needs an alias, and told nothing.
  EXPECT_FALSE(node.request_control(kClientC, kDriver, 9).has_value());
  EXPECT_EQ(node.counters().clients_refused, 1u);
  EXPECT_EQ(node.driver().control().controller()->authority, 5);
  // What the face answers itself needs no slot.
  EXPECT_TRUE(node.ask<msg::ReportHeartbeatPulse>(kClientC, kDriver, msg::QueryHeartbeatPulse{}));
  // Its stop is obeyed all the same.
  node.send(kClientC, kDriver, msg::SetEmergency{{1}});
  node.run_for(20ms);
  EXPECT_EQ(node.driver().state(), rt::PrimaryStatus::emergency);
}

TEST(JssFaceTransport, AClientHoldsStateWhileItControlsOrHasEvents) {
  FaceNode node;
  EXPECT_FALSE(node.face().holds_state_for(kClientA.subsystem, kClientA.node));
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  EXPECT_TRUE(node.face().holds_state_for(kClientA.subsystem, kClientA.node));
  ASSERT_TRUE(node.ask<msg::RejectControl>(kClientA, kDriver, msg::ReleaseControl{}));
  node.run_for(20ms);
  EXPECT_FALSE(node.face().holds_state_for(kClientA.subsystem, kClientA.node));
  msg::CreateEvent event;
  event.request_id = 1;
  event.requested_rate_hz = 1;
  event.query_message = jss::encode_contents(msg::QueryHeartbeatPulse{});
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, event));
  EXPECT_TRUE(node.face().holds_state_for(kClientA.subsystem, kClientA.node));
  // A client whose only state is an event the face answers alone (no alias slot).
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientB, kDriver, event));
  EXPECT_TRUE(node.face().holds_state_for(kClientB.subsystem, kClientB.node));
}

TEST(JssFaceTransport, ASlotWithNoStateGoesToANewClient) {
  jss_face::FaceConfig config;
  config.max_clients = 1;
  FaceNode node(config);
  ASSERT_TRUE(node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{}));
  node.run_for(1s);
  // A holds nothing: B takes the slot, and A is forgotten.
  EXPECT_EQ(node.request_control(kClientB, kDriver, 5), msg::confirm_control::kControlAccepted);
  EXPECT_EQ(node.counters().clients_refused, 0u);
  // Now B holds control: A cannot get its slot back.
  EXPECT_FALSE(node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{}).has_value());
  EXPECT_EQ(node.counters().clients_refused, 1u);
}

}  // namespace
}  // namespace jaus::test
