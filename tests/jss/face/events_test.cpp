// Events kept by the face: periodic at the confirmed rate, every change only
// on change, cancel, the v1.1 timeout, Query Events, refusals.
#include "face_node.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;

msg::CreateEvent create_event(std::uint8_t request_id, std::uint8_t type, double rate_hz,
                              const std::vector<std::uint8_t>& query) {
  msg::CreateEvent m;
  m.request_id = request_id;
  m.event_type = type;
  m.requested_rate_hz = rate_hz;
  m.query_message = query;
  return m;
}

TEST(JssFaceEvents, PeriodicAt5HzGivesFiveEventsASecondWithSequenceNumbers) {
  FaceNode node;
  const auto confirm = node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver,
      create_event(7, msg::event_type::kPeriodic, 5.0, jss::encode_contents(msg::QueryHeartbeatPulse{})));
  ASSERT_TRUE(confirm.has_value());
  EXPECT_EQ(confirm->request_id, 7);
  EXPECT_NEAR(confirm->confirmed_rate_hz.value_or(0), 5.0, 0.02);
  node.drop(kClientA, msg::Event::code);
  node.run_for(1s);
  const auto events = node.take_all<msg::Event>(kClientA);
  ASSERT_EQ(events.size(), 5u);
  for (std::size_t i = 1; i < events.size(); ++i) {
    EXPECT_EQ(events[i].second.event_id, confirm->event_id);
    EXPECT_EQ(events[i].second.sequence_number, static_cast<std::uint8_t>(events[i - 1].second.sequence_number + 1));
    EXPECT_EQ(jss::message_id_of(events[i].second.report_message), msg::ReportHeartbeatPulse::code);
  }
}

TEST(JssFaceEvents, PeriodicQueryStatusGoesThroughTheRaComponent) {
  FaceNode node;
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver, create_event(1, msg::event_type::kPeriodic, 10.0, jss::encode_contents(msg::QueryStatus{}))));
  node.drop(kClientA, msg::Event::code);
  node.run_for(1s);
  const auto events = node.take_all<msg::Event>(kClientA);
  EXPECT_GE(events.size(), 9u);
  EXPECT_LE(events.size(), 11u);
  ASSERT_FALSE(events.empty());
  const auto status = jss::decode_contents<msg::ReportStatus>(events.back().second.report_message);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->status, 1);  // Ready
}

TEST(JssFaceEvents, EveryChangeSendsOnlyWhenTheReportChanges) {
  FaceNode node;
  const auto confirm = node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver, create_event(2, msg::event_type::kEveryChange, 0, jss::encode_contents(msg::QueryStatus{})));
  ASSERT_TRUE(confirm.has_value());
  EXPECT_EQ(confirm->confirmed_rate_hz, 0);
  node.run_for(2s);
  EXPECT_EQ(node.take_all<msg::Event>(kClientA).size(), 1u);  // the state when created, then nothing new
  ASSERT_EQ(node.request_control(kClientB, kDriver, 5), msg::confirm_control::kControlAccepted);
  node.send(kClientB, kDriver, msg::Standby{});
  node.run_for(1s);
  const auto changed = node.take_all<msg::Event>(kClientA);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_EQ(jss::decode_contents<msg::ReportStatus>(changed[0].second.report_message)->status, 2);  // Standby
}

TEST(JssFaceEvents, CancelEndsTheEvent) {
  FaceNode node;
  const auto confirm = node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver,
      create_event(3, msg::event_type::kPeriodic, 5.0, jss::encode_contents(msg::QueryHeartbeatPulse{})));
  ASSERT_TRUE(confirm.has_value());
  const auto cancelled = node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, msg::CancelEvent{msg::cancel_event_by_id(4, confirm->event_id)});
  ASSERT_TRUE(cancelled.has_value());
  EXPECT_EQ(cancelled->request_id, 4);
  node.drop(kClientA, msg::Event::code);
  node.run_for(1s);
  EXPECT_EQ(node.count(kClientA, msg::Event::code), 0u);
  // Cancelling again: no such event.
  const auto again = node.ask<msg::RejectEventRequest>(kClientA, kDriver, msg::CancelEvent{msg::cancel_event_by_id(5, confirm->event_id)});
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->response_code, msg::reject_event::kInvalidEventIdForUpdate);
}

TEST(JssFaceEvents, AnEventNotRefreshedTimesOutWithAConfirm) {
  jss_face::FaceConfig config;
  config.event_timeout_min = 1;
  FaceNode node(config);
  const auto timeout = node.ask<msg::ReportEventTimeout>(kClientA, kDriver, msg::QueryEventTimeout{});
  ASSERT_TRUE(timeout.has_value());
  EXPECT_EQ(timeout->timeout_min, 1);
  const auto confirm = node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver,
      create_event(9, msg::event_type::kPeriodic, 1.0, jss::encode_contents(msg::QueryHeartbeatPulse{})));
  ASSERT_TRUE(confirm.has_value());
  // Refreshed by Update Event at 40 s: lives until 100 s.
  node.run_for(40s);
  msg::UpdateEvent update;
  update.request_id = 10;
  update.event_type = msg::event_type::kPeriodic;
  update.requested_rate_hz = 1.0;
  update.event_id = confirm->event_id;
  update.query_message = jss::encode_contents(msg::QueryHeartbeatPulse{});
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, update));
  node.run_for(50s);
  EXPECT_EQ(node.count(kClientA, msg::ConfirmEventRequest::code), 0u);
  node.run_for(15s);
  const auto ended = node.take<msg::ConfirmEventRequest>(kClientA, kDriver);
  ASSERT_TRUE(ended.has_value());
  EXPECT_EQ(ended->event_id, confirm->event_id);
  node.drop(kClientA, msg::Event::code);
  node.run_for(3s);
  EXPECT_EQ(node.count(kClientA, msg::Event::code), 0u);
}

TEST(JssFaceEvents, QueryEventsAndRefusals) {
  FaceNode node;
  const auto heartbeat = jss::encode_contents(msg::QueryHeartbeatPulse{});
  const auto confirm =
      node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, create_event(1, msg::event_type::kPeriodic, 2.0, heartbeat));
  ASSERT_TRUE(confirm.has_value());
  // The same query again is the same event, updated.
  const auto same =
      node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, create_event(2, msg::event_type::kPeriodic, 4.0, heartbeat));
  ASSERT_TRUE(same.has_value());
  EXPECT_EQ(same->event_id, confirm->event_id);

  const auto listed = node.ask<msg::ReportEvents>(kClientA, kDriver, msg::QueryEvents{});
  ASSERT_TRUE(listed.has_value());
  ASSERT_EQ(listed->events.size(), 1u);
  EXPECT_EQ(listed->events[0].query_message, heartbeat);

  // A command is no query; a query no service of the component answers.
  const auto command = node.ask<msg::RejectEventRequest>(
      kClientA, kDriver, create_event(3, msg::event_type::kPeriodic, 1.0, jss::encode_contents(msg::Standby{})));
  ASSERT_TRUE(command.has_value());
  EXPECT_EQ(command->response_code, msg::reject_event::kMessageNotSupported);
  const auto not_here = node.ask<msg::RejectEventRequest>(
      kClientA, kNodeManager, create_event(4, msg::event_type::kPeriodic, 1.0, jss::encode_contents(msg::QueryControl{})));
  ASSERT_TRUE(not_here.has_value());
  EXPECT_EQ(not_here->response_code, msg::reject_event::kMessageNotSupported);
  msg::CreateCommandEvent command_event;
  command_event.request_id = 5;
  command_event.command_message = jss::encode_contents(msg::Standby{});
  const auto command_rejected = node.ask<msg::RejectEventRequest>(kClientA, kDriver, command_event);
  ASSERT_TRUE(command_rejected.has_value());
  EXPECT_EQ(command_rejected->request_id, 5);
}

TEST(JssFaceEvents, TheEventTableIsBoundedPerClient) {
  jss_face::FaceConfig config;
  config.max_events_per_client = 2;
  FaceNode node(config);
  const std::vector<std::vector<std::uint8_t>> queries = {jss::encode_contents(msg::QueryHeartbeatPulse{}),
                                                          jss::encode_contents(msg::QueryStatus{}),
                                                          jss::encode_contents(msg::QueryControl{})};
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, create_event(1, 0, 1.0, queries[0])));
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientA, kDriver, create_event(2, 0, 1.0, queries[1])));
  const auto third = node.ask<msg::RejectEventRequest>(kClientA, kDriver, create_event(3, 0, 1.0, queries[2]));
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(third->response_code, msg::reject_event::kConnectionRefused);
  // Another client has its own.
  EXPECT_TRUE(node.ask<msg::ConfirmEventRequest>(kClientB, kDriver, create_event(1, 0, 1.0, queries[2])));
}

TEST(JssFaceEvents, EventsEndWhenTheirClientIsForgotten) {
  jss_face::FaceConfig config;
  config.event_timeout_min = 0;  // events never time out: only the client's silence ends them
  FaceNode node(config);
  ASSERT_TRUE(node.ask<msg::ConfirmEventRequest>(
      kClientA, kDriver, create_event(1, msg::event_type::kPeriodic, 1.0, jss::encode_contents(msg::QueryStatus{}))));
  node.run_for(4min);
  EXPECT_GT(node.take_all<msg::Event>(kClientA).size(), 200u);
  // Silent for 5 minutes, holding nothing in the node: forgotten, its events end.
  node.run_for(90s);
  node.drop(kClientA, msg::Event::code);
  node.run_for(5s);
  EXPECT_EQ(node.count(kClientA, msg::Event::code), 0u);
}

}  // namespace
}  // namespace jaus::test
