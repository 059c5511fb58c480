// ocu::JssSession, the JSS operator unit, against a node's JSS face under
// virtual time: discovery, queries resent under loss, commands resent until
// ACKed, a control hold kept past the component's timeout and lost to a
// higher authority, events, and the transport part (ACK answers, Query
// Heartbeat Pulse, large messages).
#include <algorithm>

#include "jaus/ocu/jss_control.hpp"
#include "jaus/ocu/jss_discovery.hpp"
#include "jaus/ocu/jss_events.hpp"
#include "jss_fixture.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;

TEST_F(JssOcuTest, DiscoversTheSubsystemItsComponentsTheirNamesAndServices) {
  auto system = ocu::discover_jss(*session);
  ASSERT_TRUE(system) << system.error().message();
  ASSERT_EQ(system->subsystems.size(), 1u);
  const auto& subsystem = system->subsystems[0];
  EXPECT_EQ(subsystem.id, 1);
  EXPECT_EQ(subsystem.name, "jss-ocu-test");
  EXPECT_TRUE(subsystem.services_listed);
  const auto* driver = system->find(kJssDriver);
  ASSERT_NE(driver, nullptr);
  EXPECT_EQ(driver->name, "driver");
  EXPECT_TRUE(driver->has("urn:jaus:jss:mobility:PrimitiveDriver"));
  EXPECT_TRUE(driver->has("AccessControl"));
  EXPECT_FALSE(driver->has("VelocityStateSensor"));
  const auto velocity = subsystem.with("VelocityStateSensor");
  ASSERT_EQ(velocity.size(), 1u);
  EXPECT_EQ(velocity[0]->id, kJssVelocity);
  ASSERT_EQ(subsystem.nodes.size(), 1u);
  EXPECT_EQ(subsystem.nodes[0].name, "vehicle");
  ASSERT_NE(system->find(kJssNodeManager), nullptr);
  EXPECT_TRUE(system->find(kJssNodeManager)->has("urn:jaus:jss:core:Discovery"));
}

TEST_F(JssOcuTest, DiscoveryAsksAgainEveryPeriodUntilASubsystemAnswers) {
  session_to_face_loss = 1;  // nothing reaches the node at first
  ocu::JssDiscoveryOptions options;
  options.identification_period = 5s;
  options.timeout = 20s;
  time.call_at(time.now() + 7s, [this] { session_to_face_loss = 0; });
  const auto started = time.now();
  auto system = ocu::discover_jss(*session, options);
  ASSERT_TRUE(system) << system.error().message();
  // Asked at 0 and 5 s (lost), answered at 10 s.
  EXPECT_GE(time.now() - started, 10s);
  EXPECT_LT(time.now() - started, 15s);
  EXPECT_EQ(system->subsystems.size(), 1u);
}

TEST_F(JssOcuTest, DiscoveryOfNothingIsATimeoutError) {
  session_to_face_loss = 1;
  ocu::JssDiscoveryOptions options;
  options.timeout = 3s;
  auto system = ocu::discover_jss(*session, options);
  ASSERT_FALSE(system);
  EXPECT_EQ(system.error().code, ErrorCode::timeout);
  EXPECT_EQ(system.error().message(), "no JSS subsystem answered Query Identification within 3 s");
}

TEST_F(JssOcuTest, QueriesAreResentUntilAnsweredUnderLoss) {
  set_loss(0.3, 7);
  int answered = 0;
  for (int i = 0; i < 20; ++i) {
    auto status = session->query<msg::ReportStatus>(kJssDriver, msg::QueryStatus{}, 5s);
    if (status && status->status == static_cast<std::uint8_t>(rt::PrimaryStatus::ready)) ++answered;
  }
  EXPECT_EQ(answered, 20);
  // 30 % loss each way: about half the round trips fail, and each costs a resend.
  EXPECT_GT(session_datagrams[ocu::kDefaultJssOcuId].size(), 25u);
}

TEST_F(JssOcuTest, AQueryNobodyAnswersIsATimeoutNamingTheTarget) {
  const auto started = time.now();
  auto status = session->query<msg::ReportStatus>(jss::JssId{1, 1, 99}, msg::QueryStatus{}, 1s);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().message(), "no reply from 1.1.99 within 1 s");
  EXPECT_EQ(time.now() - started, 1s);
  EXPECT_EQ(session_datagrams[ocu::kDefaultJssOcuId].size(), 4u);  // at 0, 250, 500 and 750 ms
}

TEST_F(JssOcuTest, SetEmergencyIsResentUntilAckedAndStopsTheDriverUnderLoss) {
  set_loss(0.4, 3);
  msg::SetEmergency stop;
  stop.emergency_code = 1;
  // A stop at the pace of the measured round trip; the clear at a fixed one (both timings).
  const auto arrival = session->send_must_arrive(kJssDriver, stop, jss::JudpPriority::safety_critical,
                                                 ocu::MustArrivePolicy::emergency());
  EXPECT_EQ(arrival.outcome, ocu::Arrival::acknowledged);
  EXPECT_EQ(ra_driver().state(), rt::PrimaryStatus::emergency);
  msg::ClearEmergency clear;
  clear.emergency_code = 1;
  const auto cleared =
      session->send_must_arrive(kJssDriver, clear, jss::JudpPriority::normal, ocu::MustArrivePolicy::every(50ms, 40));
  EXPECT_EQ(cleared.outcome, ocu::Arrival::acknowledged);
  EXPECT_NE(ra_driver().state(), rt::PrimaryStatus::emergency);
}

TEST_F(JssOcuTest, ACommandToNobodyIsUnacknowledgedAtItsDeadline) {
  // As an RA session's (MustArriveTest.EverythingLostGivesUpAtTheDeadline): again
  // after 100, 200, 400, 800 ms, then every second; given up 3 s after the first.
  const auto arrival = session->send_must_arrive(jss::JssId{1, 1, 99}, msg::Resume{});
  EXPECT_EQ(arrival.outcome, ocu::Arrival::unacknowledged);
  EXPECT_EQ(arrival.transmissions, 6u);
  EXPECT_EQ(arrival.elapsed, 3s);
}

TEST_F(JssOcuTest, WithoutAPolicyAStopToNobodyKeepsTryingAsTheSettingsSay) {
  // Its ID picks the stop's policy (SessionOptions::must_arrive's defaults):
  // every 50 ms (nothing measured), never doubled, for 10 s.
  msg::SetEmergency stop;
  stop.emergency_code = 1;
  const auto arrival = session->send_must_arrive(jss::JssId{1, 1, 99}, stop, jss::JudpPriority::safety_critical);
  EXPECT_EQ(arrival.outcome, ocu::Arrival::unacknowledged);
  EXPECT_EQ(arrival.transmissions, 200u);
  EXPECT_EQ(arrival.elapsed, 10s);
}

TEST_F(JssOcuTest, AnInterruptedCommandIsNotSentAgain) {
  // Stopped while it waits for its ACK (Ctrl-C): interrupted after the
  // transmissions so far, and no retransmission of it follows (the ACK
  // tracker forgets it), not even while a clean-up command waits for its own.
  time.call_at(time.now() + 120ms, [&] { session->request_stop(); });
  const auto arrival = session->send_must_arrive(jss::JssId{1, 1, 99}, msg::Resume{});
  EXPECT_EQ(arrival.outcome, ocu::Arrival::interrupted);
  EXPECT_EQ(arrival.transmissions, 2u) << "at 0 and 100 ms";
  const auto sent = session->counters().datagrams_sent;
  const auto contents = jss::encode_contents(msg::Resume{});
  const auto cleanup = session->send_contents_must_arrive_through_stop(
      jss::JssId{1, 1, 98}, contents, jss::JudpPriority::normal, ocu::MustArrivePolicy::every(50ms, 4));
  EXPECT_EQ(cleanup.outcome, ocu::Arrival::unacknowledged);
  EXPECT_EQ(cleanup.transmissions, 4u);
  EXPECT_EQ(session->counters().datagrams_sent, sent + 4) << "only the clean-up's own";
}

TEST_F(JssOcuTest, ABroadcastIsRepeatedAndNeverAcknowledgedAsInRa) {
  // The same rule as an RA session's (MustArriveTest.ABroadcastIsRepeatedAndNeverAcknowledged):
  // sent max_transmissions times, retransmit_after apart, no ACK asked.
  msg::SetEmergency stop;
  stop.emergency_code = 1;
  const auto arrival = session->send_must_arrive(jss::JssId{1, 1, jss::JssId::kAll}, stop,
                                                 jss::JudpPriority::safety_critical, ocu::MustArrivePolicy::every(50ms, 4));
  EXPECT_EQ(arrival.outcome, ocu::Arrival::unacknowledged);
  EXPECT_EQ(arrival.transmissions, 4u);
  EXPECT_EQ(arrival.elapsed, 150ms);
  EXPECT_TRUE(testing::run_until(time, [&] { return ra_driver().state() == rt::PrimaryStatus::emergency; }, 1s));
}

TEST_F(JssOcuTest, AControlHoldKeepsControlPastTheTimeoutAndReleases) {
  ocu::JssControlHold::Options options;
  options.authority = 5;
  auto hold = ocu::JssControlHold::take(*session, kJssDriver, options);
  ASSERT_TRUE(hold) << hold.error().message();
  EXPECT_EQ((*hold)->timeout_s(), 3);
  EXPECT_EQ((*hold)->refresh_period(), 1500ms);
  EXPECT_TRUE((*hold)->hold_for(10s));  // more than three timeouts
  EXPECT_GE((*hold)->refreshes(), 6u);
  auto control = ocu::query_jss_control(*session, kJssDriver);
  ASSERT_TRUE(control) << control.error().message();
  EXPECT_EQ(control->controller, session->self());
  EXPECT_EQ(control->authority, 5);
  ASSERT_TRUE((*hold)->release());
  EXPECT_EQ((*hold)->state(), ocu::JssControlHold::State::released);
  control = ocu::query_jss_control(*session, kJssDriver);
  ASSERT_TRUE(control);
  EXPECT_FALSE(control->controlled());
}

TEST_F(JssOcuTest, AControlHoldKeepsControlUnderLoss) {
  ocu::JssControlHold::Options options;
  options.authority = 5;
  options.request_timeout = 5s;
  auto hold = ocu::JssControlHold::take(*session, kJssDriver, options);
  ASSERT_TRUE(hold) << hold.error().message();
  set_loss(0.3, 11);  // a re-request or its Confirm lost is sent again after 250 ms
  EXPECT_TRUE((*hold)->hold_for(30s)) << (*hold)->lost_reason();
  set_loss(0, 11);
  auto control = ocu::query_jss_control(*session, kJssDriver);
  ASSERT_TRUE(control);
  EXPECT_EQ(control->controller, session->self());
}

TEST_F(JssOcuTest, ASilentClientLosesControlWithinTheTimeout) {
  auto granted = ocu::request_jss_control(*session, kJssDriver, 5);
  ASSERT_TRUE(granted) << granted.error().message();
  EXPECT_EQ(*granted, ocu::JssControlResponse::accepted);
  session->run_for(4s);  // never requested again
  auto control = ocu::query_jss_control(*session, kJssDriver);
  ASSERT_TRUE(control);
  EXPECT_FALSE(control->controlled());
}

TEST_F(JssOcuTest, AHoldIsLostWhenAHigherAuthorityTakesControl) {
  ocu::JssControlHold::Options low;
  low.authority = 2;
  auto hold = ocu::JssControlHold::take(*session, kJssDriver, low);
  ASSERT_TRUE(hold) << hold.error().message();
  std::string reason;
  (*hold)->on_lost([&](const std::string& why) { reason = why; });
  ocu::JssSession* other = open(jss::JssId{201, 1, 1});
  auto taken = ocu::request_jss_control(*other, kJssDriver, 9);
  ASSERT_TRUE(taken) << taken.error().message();
  EXPECT_EQ(*taken, ocu::JssControlResponse::accepted);
  EXPECT_FALSE((*hold)->hold_for(2s));
  EXPECT_EQ((*hold)->state(), ocu::JssControlHold::State::lost);
  EXPECT_EQ(reason, "Reject Control: CONTROL_RELEASED");
  // The lower authority asking again is refused.
  auto again = ocu::request_jss_control(*session, kJssDriver, 2);
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, ocu::JssControlResponse::insufficient_authority);
  EXPECT_FALSE(ocu::JssControlHold::take(*session, kJssDriver, low));
}

TEST_F(JssOcuTest, PeriodicEventsDeliverTheReportsUntilCancelled) {
  std::vector<ocu::JssEventReport> reports;
  msg::QueryVelocityState query;
  query.presence_vector = 0x0001;  // velocity x
  ocu::JssEventOptions options;
  options.rate_hz = 5;
  auto event = ocu::JssEvent::create(*session, kJssVelocity, query, options,
                                     [&](const ocu::JssEventReport& r) { reports.push_back(r); });
  ASSERT_TRUE(event) << event.error().message();
  EXPECT_NEAR((*event)->confirmed_rate_hz(), 5, 0.05);
  session->run_for(2s);
  EXPECT_GE(reports.size(), 9u);
  EXPECT_LE(reports.size(), 11u);
  ASSERT_FALSE(reports.empty());
  auto report = reports.back().decode<msg::ReportVelocityState>();
  ASSERT_TRUE(report) << report.error().message();
  EXPECT_TRUE(report->velocity_x_mps.has_value());
  EXPECT_EQ((*event)->events_missed(), 0u);
  ASSERT_TRUE((*event)->cancel());
  const auto count = reports.size();
  session->run_for(1s);
  EXPECT_EQ(reports.size(), count);
}

TEST_F(JssOcuTest, TwoEventsOfOneProviderEachGetTheirOwnReports) {
  int velocity = 0;
  int status = 0;
  ocu::JssEventOptions options;
  options.rate_hz = 5;
  auto first = ocu::JssEvent::create(
      *session, kJssVelocity, msg::QueryVelocityState{}, options,
      [&](const ocu::JssEventReport& r) { velocity += r.report_id() == msg::ReportVelocityState::code; });
  ASSERT_TRUE(first) << first.error().message();
  options.rate_hz = 2;
  auto second =
      ocu::JssEvent::create(*session, kJssVelocity, msg::QueryStatus{}, options,
                            [&](const ocu::JssEventReport& r) { status += r.report_id() == msg::ReportStatus::code; });
  ASSERT_TRUE(second) << second.error().message();
  EXPECT_NE((*first)->event_id(), (*second)->event_id());
  session->run_for(2s);
  EXPECT_GE(velocity, 9);
  EXPECT_GE(status, 3);
  EXPECT_LE(status, 5);
  ASSERT_TRUE((*second)->cancel());
  EXPECT_TRUE((*first)->open());
}

TEST_F(JssOcuTest, AnEventOnAQueryTheProviderLacksIsRejected) {
  auto event = ocu::JssEvent::create(*session, kJssVelocity, msg::QueryGlobalPose{}, {}, [](const auto&) {});
  ASSERT_FALSE(event);
  EXPECT_EQ(event.error().code, ErrorCode::refused);
  EXPECT_NE(event.error().message().find("1.1.42 rejected the event"), std::string::npos) << event.error().message();
}

// The transport part, on datagrams written here.
class JssSessionTransport : public JssOcuTest {
 protected:
  const jss::JssId peer{7, 1, 1};
  void deliver(const jss::JudpHeader& header, std::span<const std::uint8_t> contents) {
    session->receive_datagram(jss::make_judp_datagram(header, contents));
  }
  std::vector<jss::JudpPacket> sent_packets() {
    std::vector<jss::JudpPacket> out;
    for (const auto& datagram : session_datagrams[session->self()])
      if (auto packets = jss::decode_judp_datagram(datagram)) out.insert(out.end(), packets->begin(), packets->end());
    return out;
  }
};

TEST_F(JssSessionTransport, AnAckRequestIsAnsweredWithTheSameSequenceAndTheMessageDelivered) {
  std::vector<std::uint16_t> heard;
  session->listen([&](const ocu::JssReceived& m) { heard.push_back(m.message_id()); });
  jss::JudpHeader h;
  h.source = peer;
  h.destination = session->self();
  h.ack_nak = jss::JudpAckNak::ack_requested;
  h.sequence = 4711;
  deliver(h, jss::encode_contents(msg::QueryHeartbeatPulse{}));
  ASSERT_EQ(heard, std::vector<std::uint16_t>{msg::QueryHeartbeatPulse::code});
  const auto packets = sent_packets();
  const auto ack = std::find_if(packets.begin(), packets.end(),
                                [](const auto& p) { return p.header.ack_nak == jss::JudpAckNak::ack; });
  ASSERT_NE(ack, packets.end());
  EXPECT_EQ(ack->header.sequence, 4711);
  EXPECT_EQ(ack->header.destination, peer);
  EXPECT_EQ(ack->header.source, session->self());
  EXPECT_TRUE(ack->contents.empty());
  // And the heartbeat query is answered.
  EXPECT_TRUE(std::any_of(packets.begin(), packets.end(), [](const auto& p) {
    return jss::message_id_of(p.contents) == msg::ReportHeartbeatPulse::code;
  }));
  EXPECT_EQ(session->counters().acks_sent, 1u);
}

TEST_F(JssSessionTransport, MessagesForOthersAndMalformedDatagramsAreCountedNotDelivered) {
  int heard = 0;
  session->listen([&](const ocu::JssReceived&) { ++heard; });
  jss::JudpHeader h;
  h.source = peer;
  h.destination = jss::JssId{9, 9, 9};
  deliver(h, jss::encode_contents(msg::QueryHeartbeatPulse{}));
  const std::vector<std::uint8_t> junk{0x02, 0x00, 0x01};
  session->receive_datagram(junk);
  EXPECT_EQ(heard, 0);
  EXPECT_EQ(session->counters().not_for_us, 1u);
  EXPECT_EQ(session->counters().malformed, 1u);
}

TEST_F(JssSessionTransport, ALargeMessageIsReassembledAndOneIsSentInPieces) {
  std::vector<std::uint8_t> contents = jss::encode_contents(msg::ReportHeartbeatPulse{});
  contents.resize(5000, 0xAB);
  std::vector<std::vector<std::uint8_t>> heard;
  session->listen([&](const ocu::JssReceived& m) { heard.push_back(m.contents); });
  jss::JudpHeader h;
  h.source = peer;
  h.destination = session->self();
  h.sequence = 100;
  auto datagrams = jss::make_judp_datagrams(h, contents, 1400);
  ASSERT_TRUE(datagrams);
  ASSERT_EQ(datagrams->size(), 4u);
  for (const auto& d : *datagrams) session->receive_datagram(d);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0], contents);
  EXPECT_EQ(session->counters().large_messages_received, 1u);

  session->send_contents(peer, contents);
  const auto packets = sent_packets();
  ASSERT_EQ(packets.size(), 4u);
  EXPECT_EQ(packets.front().header.data_flag, jss::JudpDataFlag::first);
  EXPECT_EQ(packets.back().header.data_flag, jss::JudpDataFlag::last);
  for (std::size_t i = 1; i < packets.size(); ++i)
    EXPECT_EQ(packets[i].header.sequence, static_cast<std::uint16_t>(packets[0].header.sequence + i));
}

TEST_F(JssSessionTransport, QueryIdentificationIsAnsweredWithTheOperatorUnitsName) {
  jss::JudpHeader h;
  h.source = peer;
  h.destination = session->self();
  msg::QueryIdentification query;
  query.query_type = msg::identification::kSubsystem;
  deliver(h, jss::encode_contents(query));
  const auto packets = sent_packets();
  ASSERT_EQ(packets.size(), 1u);
  auto report = jss::decode_contents<msg::ReportIdentification>(packets[0].contents);
  ASSERT_TRUE(report) << report.error().message();
  EXPECT_EQ(report->type, msg::identification_type::kOcu);
  EXPECT_EQ(report->identification, "jausctl");
}

TEST(JssSessionOptions, AnInvalidOrBroadcastIdIsRefused) {
  rt::VirtualTime time;
  ocu::JssSessionOptions options;
  options.self = jss::JssId{200, 255, 1};
  ocu::JssEnvironment env{&time, &time, [](const jss::JssId&, std::span<const std::uint8_t>) {}, [](auto) {},
                          testing::stepper(time)};
  auto session = ocu::JssSession::attach(options, env);
  ASSERT_FALSE(session);
  EXPECT_EQ(session.error().code, ErrorCode::invalid_argument);
}

}  // namespace
}  // namespace jaus::test
