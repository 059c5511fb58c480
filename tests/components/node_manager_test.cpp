// Node manager (discovery, heartbeats, configuration events) and communicator.
#include "harness.hpp"
#include "jaus/components/communicator.hpp"
#include "jaus/components/node_manager.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

const Address kNodeManager{1, 1, 1, 1};

class FakeDirectory : public rt::NodeDirectory {
 public:
  std::vector<const rt::Component*> local_components() const override { return components; }
  std::vector<Address> known_subsystems() const override { return subsystems; }
  bool hosts_component(std::uint8_t id) const override {
    return std::any_of(components.begin(), components.end(),
                       [&](const auto* c) { return c->address().component == id; });
  }
  std::vector<const rt::Component*> components;
  std::vector<Address> subsystems;
};

class NodeManagerTest : public ::testing::Test {
 protected:
  NodeManagerTest() {
    outbox.clock = &time;
    rt::ComponentConfig nm_config;
    nm_config.name = "node manager";
    nm_config.address = kNodeManager;
    components::NodeManagerConfig nm;
    nm.subsystem_name = "Husky A200";
    nm.node_name = "onboard";
    manager = std::make_unique<components::NodeManager>(nm_config, rt::Environment{time, time, outbox}, directory, nm);
    rt::ComponentConfig driver_config;
    driver_config.name = "primitive driver";
    driver_config.address = kDriver;
    driver = std::make_unique<TestDriver>(driver_config, rt::Environment{time, time, outbox});
    directory.components = {manager.get(), driver.get()};
    directory.subsystems = {kNodeManager, Address{7, 2, 1, 1}};
    manager->start();
    driver->start();
  }

  template <class M>
  void deliver(const Address& from, const M& message, rt::SenderStanding standing = rt::SenderStanding::trusted) {
    std::vector<std::uint8_t> payload(kMaxPayloadSize);
    const auto size = wire::encode_payload(message, payload);
    ASSERT_TRUE(size);
    Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = kNodeManager;
    manager->receive(h, std::span(payload).first(*size), wire::Dialect::ra, standing);
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  FakeDirectory directory;
  std::unique_ptr<components::NodeManager> manager;
  std::unique_ptr<TestDriver> driver;
};

const Address kEverySubsystem{255, 255, 1, 1};

TEST_F(NodeManagerTest, SendsHeartbeatsToTheSubsystemAndTheNode) {
  outbox.clear();
  time.advance(3500ms);
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(Address{1, 255, 1, 1}).size(), 3u);
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(Address{1, 1, 255, 255}).size(), 3u);
  // No communicator on this node to announce the subsystem: the node manager does.
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(kEverySubsystem).size(), 3u);
}

TEST_F(NodeManagerTest, LeavesOtherSubsystemsToTheCommunicator) {
  rt::ComponentConfig config;
  config.address = Address{1, 1, 35, 1};
  components::Communicator communicator(config, rt::Environment{time, time, outbox});
  directory.components.push_back(&communicator);
  communicator.start();
  outbox.clear();
  time.advance(3500ms);
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(Address{1, 255, 1, 1}).size(), 3u);
  // From the communicator only: one a second, as from the node manager before.
  const auto announced = outbox.to<msg::ReportHeartbeatPulse>(kEverySubsystem);
  EXPECT_EQ(announced.size(), 3u);
  for (const auto& sent : outbox.sent) {
    if (sent.header.destination == kEverySubsystem) {
      EXPECT_EQ(sent.header.source, config.address);
    }
  }
}

TEST_F(NodeManagerTest, AnswersIdentificationAtEachLevel) {
  deliver(kOcuA, msg::QueryIdentification{{msg::identification::kSubsystem}});
  deliver(kOcuA, msg::QueryIdentification{{msg::identification::kNode}});
  deliver(kOcuA, msg::QueryIdentification{{msg::identification::kComponent}});
  deliver(kOcuA, msg::QueryIdentification{{msg::identification::kSystem}});
  const auto reports = outbox.to<msg::ReportIdentification>(kOcuA);
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[0].identification, "Husky A200");
  EXPECT_EQ(reports[0].type, 10001);
  EXPECT_EQ(reports[1].identification, "onboard");
  EXPECT_EQ(reports[1].type, 40001);
  EXPECT_EQ(reports[2].identification, "node manager");
}

TEST_F(NodeManagerTest, AnswersConfigurationSubsystemListAndServices) {
  deliver(kOcuA, msg::QueryConfiguration{{msg::identification::kNode}});
  deliver(kOcuA, msg::QuerySubsystemList{});
  deliver(kOcuA, msg::QueryServices{});
  const auto config = outbox.to<msg::ReportConfiguration>(kOcuA).at(0);
  ASSERT_EQ(config.nodes.size(), 1u);
  EXPECT_EQ(config.nodes[0].node_id, 1);
  ASSERT_EQ(config.nodes[0].components.size(), 2u);
  EXPECT_EQ(config.nodes[0].components[1].component_id, 33);
  EXPECT_EQ(outbox.to<msg::ReportSubsystemList>(kOcuA).at(0).subsystems, directory.subsystems);
  const auto services = outbox.to<msg::ReportServices>(kOcuA).at(0).services;
  ASSERT_EQ(services.size(), 2u);
  EXPECT_EQ(services[1].type, 33);
  bool takes_wrench = false;
  for (const auto& in : services[1].inputs) takes_wrench |= in.command_code == msg::SetWrenchEffort::code;
  EXPECT_TRUE(takes_wrench);
  // Outputs by code: every component's status, and the driver's pose.
  ASSERT_EQ(services[1].outputs.size(), 2u);
  EXPECT_EQ(services[1].outputs[0].command_code, msg::ReportComponentStatus::code);
  EXPECT_EQ(services[1].outputs[1].command_code, msg::ReportGlobalPose::code);
  EXPECT_EQ(services[1].outputs[1].presence_vector, 0x017Fu);
}

TEST_F(NodeManagerTest, ConfigurationEventsOnEveryChange) {
  msg::CreateEvent create;
  create.request_id = 9;
  create.report_code = msg::ReportConfiguration::code;
  create.event_type = 1;
  create.query_message = std::vector<std::uint8_t>{msg::identification::kSubsystem};
  deliver(kOcuA, create);
  const auto confirm = outbox.to<msg::ConfirmEventRequest>(kOcuA).at(0);
  EXPECT_EQ(confirm.request_id, 9);
  EXPECT_EQ(confirm.response_code, msg::event_response::kSuccessful);
  EXPECT_EQ(manager->event_subscriptions(), 1u);

  directory.components = {manager.get()};  // the driver went away
  manager->configuration_changed();
  const auto events = outbox.to<msg::Event>(kOcuA);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].event_id, confirm.event_id);
  EXPECT_EQ(events[0].report_code, msg::ReportConfiguration::code);
  auto config = wire::decode_payload<msg::ReportConfiguration>(events[0].report_message);
  ASSERT_TRUE(config);
  EXPECT_EQ(config->nodes.at(0).components.size(), 1u);

  msg::CancelEvent cancel;
  cancel.request_id = 10;
  cancel.message_code = msg::ReportConfiguration::code;
  cancel.event_id = confirm.event_id;
  deliver(kOcuA, cancel);
  EXPECT_EQ(manager->event_subscriptions(), 0u);
  manager->configuration_changed();
  EXPECT_EQ(outbox.to<msg::Event>(kOcuA).size(), 1u);
}

// The subsystem list changes with the network (a subsystem heard or silent),
// not with this node: its own events, at most 10 a second whatever the churn.
TEST_F(NodeManagerTest, SubsystemListEventsOnEveryChangeAtABoundedRate) {
  msg::CreateEvent create;
  create.request_id = 3;
  create.report_code = msg::ReportSubsystemList::code;
  create.event_type = 1;
  deliver(kOcuA, create);
  const auto confirm = outbox.to<msg::ConfirmEventRequest>(kOcuA).at(0);
  EXPECT_EQ(confirm.message_code, msg::ReportSubsystemList::code);
  EXPECT_EQ(confirm.response_code, msg::event_response::kSuccessful);

  const auto subsystems_in = [](const msg::Event& event) {
    EXPECT_EQ(event.report_code, msg::ReportSubsystemList::code);
    const auto list = wire::decode_payload<msg::ReportSubsystemList>(event.report_message);
    EXPECT_TRUE(list);
    return list ? list->subsystems : std::vector<Address>{};
  };
  manager->configuration_changed();  // this node's components: not the subsystem list
  EXPECT_TRUE(outbox.to<msg::Event>(kOcuA).empty());

  directory.subsystems.push_back(Address{3, 1, 35, 1});
  manager->subsystems_changed();
  auto events = outbox.to<msg::Event>(kOcuA);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].event_id, confirm.event_id);
  EXPECT_EQ(subsystems_in(events[0]), directory.subsystems);

  // A burst of changes within 100 ms: one Event when the rate allows, with the last list.
  directory.subsystems.pop_back();
  manager->subsystems_changed();
  directory.subsystems.pop_back();
  manager->subsystems_changed();
  EXPECT_EQ(outbox.to<msg::Event>(kOcuA).size(), 1u);
  time.advance(100ms);
  events = outbox.to<msg::Event>(kOcuA);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(subsystems_in(events[1]), (std::vector<Address>{kNodeManager}));
  EXPECT_EQ(events[1].sequence_number, events[0].sequence_number + 1);
  time.advance(1s);
  EXPECT_EQ(outbox.to<msg::Event>(kOcuA).size(), 2u);  // nothing changed since
}

TEST_F(NodeManagerTest, PeriodicConfigurationEventsAndRefusals) {
  msg::CreateEvent periodic;
  periodic.request_id = 1;
  periodic.report_code = msg::ReportConfiguration::code;
  periodic.event_type = 0;
  periodic.requested_rate_hz = 2;
  deliver(kOcuA, periodic);
  time.advance(2200ms);
  EXPECT_EQ(outbox.to<msg::Event>(kOcuA).size(), 5u);  // at 0, 0.5, 1, 1.5, 2 s

  msg::CreateEvent other = periodic;
  other.report_code = msg::ReportGlobalPose::code;
  deliver(kOcuB, other);
  EXPECT_EQ(outbox.to<msg::ConfirmEventRequest>(kOcuB).at(0).response_code, msg::event_response::kMessageNotSupported);
}

// Events are bounded like service connections: a capped rate, a few per
// requester, and none left for a requester that is gone.
TEST_F(NodeManagerTest, EventsAreCappedPerRequesterAndEndWithTheirRequester) {
  msg::CreateEvent periodic;
  periodic.report_code = msg::ReportConfiguration::code;
  periodic.event_type = 0;
  periodic.requested_rate_hz = 1092;
  for (std::uint8_t i = 0; i < 6; ++i) {
    periodic.request_id = i;
    deliver(kOcuA, periodic);
  }
  const auto confirms = outbox.to<msg::ConfirmEventRequest>(kOcuA);
  ASSERT_EQ(confirms.size(), 6u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(confirms[i].response_code, msg::event_response::kSuccessful);
    ASSERT_TRUE(confirms[i].confirmed_rate_hz);
    EXPECT_NEAR(*confirms[i].confirmed_rate_hz, 10, 0.01);  // NodeManagerConfig::max_event_rate_hz
  }
  EXPECT_EQ(confirms[4].response_code, msg::event_response::kRefused);
  EXPECT_EQ(confirms[5].response_code, msg::event_response::kRefused);
  periodic.request_id = 7;
  deliver(kOcuB, periodic);  // another requester still gets one
  EXPECT_EQ(outbox.to<msg::ConfirmEventRequest>(kOcuB).at(0).response_code, msg::event_response::kSuccessful);
  EXPECT_EQ(manager->event_subscriptions(), 5u);

  manager->peer_lost(kOcuA);
  EXPECT_EQ(manager->event_subscriptions(), 1u);
  outbox.clear();
  time.advance(1s);
  EXPECT_TRUE(outbox.to<msg::Event>(kOcuA).empty());
  EXPECT_EQ(outbox.to<msg::Event>(kOcuB).size(), 10u);  // 10 Hz
}

// Issue 28: a requester the node could not record (its tables full) would
// keep an event nothing ends: refused (response 3), stored nowhere.
TEST_F(NodeManagerTest, AnUnrecordedRequestersCreateEventIsRefusedAndStoredNowhere) {
  msg::CreateEvent create;
  create.request_id = 4;
  create.report_code = msg::ReportConfiguration::code;
  create.event_type = 1;
  deliver(kOcuA, create, rt::SenderStanding::unrecorded);
  const auto confirms = outbox.to<msg::ConfirmEventRequest>(kOcuA);
  ASSERT_EQ(confirms.size(), 1u);
  EXPECT_EQ(confirms[0].request_id, 4);
  EXPECT_EQ(confirms[0].message_code, msg::ReportConfiguration::code);
  EXPECT_EQ(confirms[0].response_code, msg::event_response::kRefused);
  EXPECT_EQ(manager->event_subscriptions(), 0u);
  EXPECT_EQ(manager->counters().refused_unrecorded, 1u);
  EXPECT_FALSE(manager->keeps_state_for(Address{kOcuA.subsystem, kOcuA.node, 0, 0}));
  manager->configuration_changed();
  time.advance(2s);
  EXPECT_TRUE(outbox.to<msg::Event>(kOcuA).empty());
  // Its queries are answered.
  deliver(kOcuA, msg::QueryConfiguration{{msg::identification::kNode}}, rt::SenderStanding::unrecorded);
  EXPECT_EQ(outbox.to<msg::ReportConfiguration>(kOcuA).size(), 1u);
}

// An observer (outside transport.control_from) may subscribe; its event is
// state the node keeps for its node until it cancels.
TEST_F(NodeManagerTest, AnObserverSubscribesAndItsNodeIsKeptUntilItCancels) {
  const Address node_of_a{kOcuA.subsystem, kOcuA.node, 0, 0};
  msg::CreateEvent create;
  create.request_id = 5;
  create.report_code = msg::ReportSubsystemList::code;
  create.event_type = 1;
  deliver(kOcuA, create, rt::SenderStanding::observer);
  const auto confirm = outbox.to<msg::ConfirmEventRequest>(kOcuA).at(0);
  EXPECT_EQ(confirm.response_code, msg::event_response::kSuccessful);
  EXPECT_EQ(manager->event_subscriptions(), 1u);
  EXPECT_TRUE(manager->keeps_state_for(node_of_a));
  EXPECT_FALSE(manager->keeps_state_for(Address{kOcuB.subsystem, kOcuB.node, 0, 0}));
  EXPECT_FALSE(driver->keeps_state_for(node_of_a));  // the events are the node manager's
  msg::CancelEvent cancel;
  cancel.request_id = 6;
  cancel.message_code = msg::ReportSubsystemList::code;
  cancel.event_id = confirm.event_id;
  deliver(kOcuA, cancel, rt::SenderStanding::observer);
  EXPECT_EQ(manager->event_subscriptions(), 0u);
  EXPECT_FALSE(manager->keeps_state_for(node_of_a));
}

TEST(Communicator, ReportsAndSetsDataLinks) {
  rt::VirtualTime time;
  RecordingOutbox outbox;
  rt::ComponentConfig config;
  config.address = Address{1, 1, 35, 1};
  config.authority = 0;
  components::Communicator communicator(config, rt::Environment{time, time, outbox}, components::CommunicatorConfig{2});
  communicator.start();
  auto deliver = [&](const Address& from, auto message) {
    std::vector<std::uint8_t> payload(64);
    const auto size = wire::encode_payload(message, payload);
    Header h;
    h.command_code = decltype(message)::code;
    h.source = from;
    h.destination = config.address;
    communicator.receive(h, std::span(payload).first(*size));
  };
  deliver(kOcuA, msg::SetDataLinkSelect{{1}});  // not the controller
  EXPECT_EQ(communicator.selected_link(), 0);
  deliver(kOcuA, msg::RequestComponentControl{{10}});
  deliver(kOcuA, msg::SetDataLinkSelect{{1}});
  deliver(kOcuA, msg::SetDataLinkStatus{{components::data_link::kStandby}});
  deliver(kOcuA, msg::SetDataLinkSelect{{7}});  // no such link
  EXPECT_EQ(communicator.selected_link(), 1);
  deliver(kOcuB, msg::QueryDataLinkStatus{{1}});
  deliver(kOcuB, msg::QuerySelectedDataLinkStatus{});
  EXPECT_EQ(outbox.to<msg::ReportDataLinkStatus>(kOcuB).at(0).state, components::data_link::kStandby);
  EXPECT_EQ(outbox.to<msg::ReportSelectedDataLinkStatus>(kOcuB).at(0).data_link_id, 1);
}

// Other subsystems' node managers accept only their own subsystem and 255:
// the communicator announces its subsystem to (255, 255, 1, 1), and to
// nothing addressed to its own subsystem.
TEST(Communicator, HeartbeatsToEverySubsystemAtItsRate) {
  rt::VirtualTime time;
  RecordingOutbox outbox;
  rt::ComponentConfig config;
  config.address = Address{2, 1, 35, 1};
  components::Communicator communicator(config, rt::Environment{time, time, outbox},
                                        components::CommunicatorConfig{1, 500ms});
  communicator.start();
  time.advance(2200ms);
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(Address{255, 255, 1, 1}).size(), 5u);  // at 0, 0.5, ... 2 s
  for (const auto& sent : outbox.sent) EXPECT_NE(sent.header.destination.subsystem, 2);
  // A Reset runs Initialize again: still one heartbeat per period.
  deliver_to(communicator, time, kOcuA, msg::RequestComponentControl{{10}});
  deliver_to(communicator, time, kOcuA, msg::Reset{});
  EXPECT_EQ(communicator.state(), msg::PrimaryStatus::ready);
  outbox.clear();
  time.advance(1000ms);
  EXPECT_EQ(outbox.to<msg::ReportHeartbeatPulse>(Address{255, 255, 1, 1}).size(), 2u);
}

}  // namespace
}  // namespace jaus::test
