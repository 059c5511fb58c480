// The node: routing between local components and the network, priority
// dispatch, ACK/NAK, large data sets, liveness. Two nodes are joined by a
// jaus::testing memory network under virtual time.
#include "harness.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/node/node.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

// What a node handed its link, in order (the link is jaus::testing's: nodes
// on one memory network, a packet arriving 1 ms after it left).
class LinkTransmissions {
 public:
  explicit LinkTransmissions(testing::MemoryLink& link) {
    link.on_transmit([this](const Header& header, std::span<const std::uint8_t> packet) {
      EXPECT_EQ(header, *decode_header(packet));  // the node hands over the header it wrote
      packets.emplace_back(packet.begin(), packet.end());
    });
  }
  std::vector<Header> headers() const {
    std::vector<Header> out;
    for (const auto& p : packets) out.push_back(*decode_header(p));
    return out;
  }
  std::vector<std::vector<std::uint8_t>> packets;
};

class ImageSink : public rt::Component {
 public:
  ImageSink(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<msg::ReportImage>(Access::anyone, false,
                             [this](const Header&, const msg::ReportImage& m) { images.push_back(m.data); });
  }
  std::vector<std::vector<std::uint8_t>> images;
  template <class M>
  void send_to(const Address& to, const M& m, std::uint8_t priority = jaus::priority::kDefault) {
    send(to, m, priority);
  }
};

rt::ComponentConfig config_for(const Address& address, const char* name) {
  rt::ComponentConfig c;
  c.address = address;
  c.name = name;
  c.authority = 5;
  return c;
}

class NodeTest : public ::testing::Test {
 protected:
  NodeTest() {
    node::NodeConfig ca;
    ca.subsystem = 1;
    ca.node = 1;
    node::NodeConfig cb;
    cb.subsystem = 2;
    cb.node = 1;
    a = std::make_unique<node::Node>(ca, time, time, link_a, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); });
    b = std::make_unique<node::Node>(cb, time, time, link_b, [this](rt::LogLevel, const std::string& l) { logs.push_back(l); });
    link_a.deliver_to(*a);
    link_b.deliver_to(*b);
    driver = static_cast<TestDriver*>(&a->add(std::make_unique<TestDriver>(config_for(kDriver, "driver"), a->environment())));
    ocu = static_cast<ImageSink*>(&b->add(std::make_unique<ImageSink>(config_for(kOcu, "ocu"), b->environment())));
  }

  std::vector<std::uint8_t> packet(const Header& header, std::span<const std::uint8_t> payload) {
    std::vector<std::uint8_t> out(kHeaderSize + payload.size());
    Header h = header;
    h.data_size = static_cast<std::uint16_t>(payload.size());
    encode_header_unchecked(h, std::span(out).first<kHeaderSize>());
    std::copy(payload.begin(), payload.end(), out.begin() + kHeaderSize);
    return out;
  }
  template <class M>
  std::vector<std::uint8_t> packet_of(const Address& from, const Address& to, const M& m,
                                      std::uint8_t priority = jaus::priority::kDefault,
                                      AckNak ack = AckNak::none) {
    std::vector<std::uint8_t> payload(kMaxPayloadSize);
    const auto size = wire::encode_payload(m, payload);
    Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = to;
    h.priority = priority;
    h.ack_nak = ack;
    return packet(h, std::span(payload).first(*size));
  }
  bool logged(const std::string& text) const { return any_line_contains(logs, text); }

  static inline const Address kOcu{2, 1, 40, 1};
  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time, 1ms};
  testing::MemoryLink& link_a = network.attach(1, 1);
  testing::MemoryLink& link_b = network.attach(2, 1);
  LinkTransmissions sent_a{link_a}, sent_b{link_b};
  std::vector<std::string> logs;
  std::unique_ptr<node::Node> a, b;
  TestDriver* driver = nullptr;
  ImageSink* ocu = nullptr;
};

TEST_F(NodeTest, RoutesBetweenNodesAndStampsSequenceNumbers) {
  ocu->send_to(kDriver, msg::RequestComponentControl{{10}});
  ocu->send_to(kDriver, msg::QueryComponentControl{});
  time.advance(10ms);
  EXPECT_TRUE(driver->control().is_controller(kOcu));
  const auto sent = sent_b.headers();
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].sequence, 0);
  EXPECT_EQ(sent[1].sequence, 1);
  // The replies came back over a's link.
  std::size_t confirms = 0;
  for (const auto& h : sent_a.headers()) confirms += h.command_code == msg::ConfirmComponentControl::code;
  EXPECT_EQ(confirms, 1u);
  EXPECT_TRUE(b->liveness().find_component(kDriver).has_value());
}

TEST_F(NodeTest, BroadcastReachesEveryLocalComponentButTheSender) {
  auto& second = a->add(std::make_unique<TestDriver>(config_for(Address{1, 1, 33, 2}, "driver 2"), a->environment()));
  a->receive_bytes(packet_of(kOcu, Address{1, 1, 255, 255}, msg::SetEmergency{}));
  time.advance(1ms);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::emergency);
  EXPECT_EQ(second.state(), msg::PrimaryStatus::emergency);
  // Another subsystem's broadcast is not for this node.
  a->receive_bytes(packet_of(kOcu, Address{3, 255, 255, 255}, msg::Standby{}));
  time.advance(1ms);
  EXPECT_EQ(a->counters().not_for_this_node, 1u);
}

TEST_F(NodeTest, SafetyCriticalMessagesOvertakeQueuedOnes) {
  sent_a.packets.clear();
  a->receive_bytes(packet_of(kOcu, kDriver, msg::QueryComponentStatus{}, 6));
  a->receive_bytes(packet_of(kOcu, kDriver, msg::QueryComponentStatus{}, 6));
  a->receive_bytes(packet_of(kOcu, kDriver, msg::SetEmergency{}, 12));
  time.advance(1ms);
  // Both status reports were produced after the emergency was handled.
  std::size_t in_emergency = 0;
  for (const auto& p : sent_a.packets) {
    auto view = decode_packet(p);
    if (view->header.command_code != msg::ReportComponentStatus::code) continue;
    auto report = wire::decode_payload<msg::ReportComponentStatus>(view->payload);
    in_emergency += report->primary_status == static_cast<std::uint8_t>(msg::PrimaryStatus::emergency);
  }
  EXPECT_EQ(in_emergency, 2u);
}

TEST_F(NodeTest, AnswersAckRequestsWithAckOrNak) {
  sent_a.packets.clear();
  a->receive_bytes(packet_of(kOcu, kDriver, msg::QueryComponentStatus{}, 6, AckNak::ack_requested));
  a->receive_bytes(packet_of(kOcu, Address{1, 1, 50, 1}, msg::QueryComponentStatus{}, 6, AckNak::ack_requested));
  time.advance(1ms);
  std::vector<AckNak> replies;
  for (const auto& h : sent_a.headers())
    if (h.command_code == msg::QueryComponentStatus::code) replies.push_back(h.ack_nak);
  EXPECT_EQ(replies, (std::vector<AckNak>{AckNak::ack, AckNak::nak}));
  EXPECT_EQ(a->counters().acks_sent, 1u);
  EXPECT_EQ(a->counters().naks_sent, 1u);
}

TEST_F(NodeTest, RetransmitsItsOwnAckRequestsABoundedNumberOfTimes) {
  link_b.set_connected(false);  // nothing reaches node a
  std::vector<std::uint8_t> payload(8);
  Header h;
  h.command_code = msg::QueryComponentStatus::code;
  h.source = kOcu;
  h.destination = kDriver;
  h.ack_nak = AckNak::ack_requested;
  b->send(h, {});
  time.advance(10s);
  std::size_t transmissions = 0;
  for (const auto& sent : sent_b.headers()) transmissions += sent.command_code == msg::QueryComponentStatus::code;
  EXPECT_EQ(transmissions, 3u);
  EXPECT_TRUE(logged("no ACK for 0x2002 to 1.1.33.1 after 3 transmissions"));
}

TEST_F(NodeTest, LargePayloadsTravelAsLargeDataSets) {
  msg::ReportImage image;
  image.data.resize(10'000);
  for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = static_cast<std::uint8_t>(i * 7);
  auto* camera = static_cast<ImageSink*>(
      &a->add(std::make_unique<ImageSink>(config_for(Address{1, 1, 37, 1}, "camera"), a->environment())));
  sent_a.packets.clear();
  camera->send_to(kOcu, image);
  time.advance(10ms);
  const auto sent = sent_a.headers();
  ASSERT_EQ(sent.size(), 3u);
  EXPECT_EQ(sent[0].data_flag, DataFlag::first);
  EXPECT_EQ(sent[1].data_flag, DataFlag::middle);
  EXPECT_EQ(sent[2].data_flag, DataFlag::last);
  EXPECT_EQ(sent[1].sequence, static_cast<std::uint16_t>(sent[0].sequence + 1));
  ASSERT_EQ(ocu->images.size(), 1u);
  EXPECT_EQ(ocu->images[0], image.data);
}

// On a slow radio (a send budget) large payloads go in smaller pieces; a
// message that must arrive stays one packet, as its copies are.
TEST(NodePieces, SmallerPiecesForLargePayloadsButAMustArriveMessageStaysWhole) {
  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time, 1ms};
  auto& link_a = network.attach(1, 1);
  auto& link_b = network.attach(2, 1);
  node::NodeConfig ca;
  ca.subsystem = 1;
  ca.node = 1;
  ca.large_data_set_piece = 1000;
  node::NodeConfig cb;
  cb.subsystem = 2;
  cb.node = 1;
  node::Node a(ca, time, time, link_a);
  node::Node b(cb, time, time, link_b);
  link_a.deliver_to(a);
  link_b.deliver_to(b);
  const Address camera_address{1, 1, 37, 1};
  const Address ocu_address{2, 1, 40, 1};
  auto& camera = static_cast<ImageSink&>(a.add(std::make_unique<ImageSink>(config_for(camera_address, "camera"), a.environment())));
  auto& ocu = static_cast<ImageSink&>(b.add(std::make_unique<ImageSink>(config_for(ocu_address, "ocu"), b.environment())));
  LinkTransmissions sent{link_a};
  msg::ReportImage image;
  image.data.resize(2500);
  for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = static_cast<std::uint8_t>(i * 13);
  camera.send_to(ocu_address, image);
  time.advance(10ms);
  auto headers = sent.headers();
  ASSERT_EQ(headers.size(), 3u);  // 2,503 bytes of payload in pieces of 1,000
  for (const auto& h : headers) EXPECT_LE(h.data_size, 1000u);
  EXPECT_EQ(headers[2].data_flag, DataFlag::last);
  ASSERT_EQ(ocu.images.size(), 1u);
  EXPECT_EQ(ocu.images[0], image.data);

  sent.packets.clear();
  Header must_arrive;
  must_arrive.command_code = msg::ReportImage::code;
  must_arrive.source = camera_address;
  must_arrive.destination = ocu_address;
  must_arrive.ack_nak = AckNak::ack_requested;
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  payload.resize(*wire::encode_payload(image, payload));
  a.send(must_arrive, payload);
  time.advance(10ms);
  headers = sent.headers();
  ASSERT_EQ(headers.size(), 1u);
  EXPECT_EQ(headers[0].data_flag, DataFlag::single);
  EXPECT_EQ(headers[0].data_size, payload.size());
  EXPECT_EQ(ocu.images.size(), 2u);
}

TEST_F(NodeTest, AShutDownComponentLeavesTheNode) {
  ocu->send_to(kDriver, msg::RequestComponentControl{{10}});
  ocu->send_to(kDriver, msg::Shutdown{});
  time.advance(10ms);
  EXPECT_EQ(a->find(kDriver), nullptr);
  EXPECT_EQ(a->local_components().size(), 0u);
}

TEST_F(NodeTest, BadPacketsAreCountedNeverDelivered) {
  a->receive_bytes(std::vector<std::uint8_t>{0x06, 0x02, 0x02});
  auto wrong_size = packet_of(kOcu, kDriver, msg::SetEmergency{});
  wrong_size.push_back(0);
  a->receive_bytes(wrong_size);
  a->receive_bytes(packet_of(Address{0, 1, 40, 1}, kDriver, msg::SetEmergency{}));
  time.advance(1ms);
  EXPECT_EQ(driver->state(), msg::PrimaryStatus::ready);
  EXPECT_EQ(a->counters().malformed, 2u);
  EXPECT_EQ(a->counters().invalid_source, 1u);
}

TEST_F(NodeTest, SilentPeersLoseControlAndServiceConnections) {
  rt::ComponentConfig config = config_for(Address{1, 1, 33, 3}, "patient driver");
  config.controller_timeout = rt::Duration::zero();  // only the node's liveness table can notice
  auto& patient = a->add(std::make_unique<TestDriver>(config, a->environment()));
  ocu->send_to(patient.address(), msg::RequestComponentControl{{10}});
  msg::CreateServiceConnection sc;
  sc.command_code = msg::ReportGlobalPose::code;
  sc.periodic_rate_hz = 5;
  sc.presence_vector = 0x1FF;
  ocu->send_to(patient.address(), sc);
  time.advance(100ms);
  ASSERT_TRUE(patient.control().is_controller(kOcu));
  ASSERT_EQ(patient.service_connections().active(), 1u);
  link_b.set_connected(false);  // the OCU's node falls silent
  time.advance(4s);  // the component's 3 s are over, its node's 5 s are not
  EXPECT_TRUE(patient.control().is_controller(kOcu));
  time.advance(2s);
  EXPECT_FALSE(patient.control().controller());
  EXPECT_EQ(patient.service_connections().active(), 0u);
  EXPECT_TRUE(logged("node 2.1.0.0 silent: lost"));
}

TEST_F(NodeTest, AReceivingOnlyComponentOnALiveNodeKeepsItsServiceConnection) {
  msg::CreateServiceConnection sc;
  sc.command_code = msg::ReportGlobalPose::code;
  sc.periodic_rate_hz = 5;
  sc.presence_vector = 0x1FF;
  ocu->send_to(kDriver, sc);
  // Another component of the OCU's node keeps talking (as its node manager's
  // heartbeats would); the subscriber itself only listens.
  const Address other{2, 1, 1, 1};
  for (int second = 0; second < 10; ++second) {
    a->receive_bytes(packet_of(other, Address{1, 255, 1, 1}, msg::ReportHeartbeatPulse{}));
    time.advance(1s);
  }
  EXPECT_EQ(driver->service_connections().active(), 1u);
}

TEST_F(NodeTest, OwnLoopedBackBroadcastsAreDropped) {
  a->receive_bytes(packet_of(Address{1, 1, 40, 1}, Address{1, 255, 255, 255}, msg::QueryHeartbeatPulse{}));
  time.advance(1ms);
  EXPECT_EQ(a->counters().from_self, 1u);
  EXPECT_EQ(driver->counters().received, 0u);
}

// A driver whose stop commands outlive it (shutdown destroys components).
class WatchedDriver : public TestDriver {
 public:
  WatchedDriver(rt::ComponentConfig config, rt::Environment env, std::vector<std::string>& stops_out)
      : TestDriver(std::move(config), std::move(env)), stops_out_(stops_out) {}
  void command_stop(std::string_view why) override {
    TestDriver::command_stop(why);
    stops_out_.emplace_back(why);
  }
  std::vector<std::string>& stops_out_;
};

TEST_F(NodeTest, ShutdownStopsThePlatformDropsControlAndEndsServiceConnections) {
  std::vector<std::string> stops;
  const Address watched_address{1, 1, 33, 4};
  a->add(std::make_unique<WatchedDriver>(config_for(watched_address, "watched"), a->environment(), stops));
  ocu->send_to(watched_address, msg::RequestComponentControl{{10}});
  msg::CreateServiceConnection sc;
  sc.command_code = msg::ReportGlobalPose::code;
  sc.periodic_rate_hz = 5;
  sc.presence_vector = 0x1FF;
  ocu->send_to(watched_address, sc);
  time.advance(100ms);
  ASSERT_TRUE(a->find(watched_address)->control().is_controller(kOcu));
  ASSERT_EQ(a->find(watched_address)->service_connections().active(), 1u);
  stops.clear();
  sent_a.packets.clear();
  a->shutdown("test over");
  EXPECT_FALSE(stops.empty());  // the platform was commanded to stop
  EXPECT_TRUE(a->local_components().empty());
  bool told_controller = false;
  for (const auto& h : sent_a.headers())
    told_controller |= h.command_code == msg::RejectComponentControl::code && h.destination == kOcu;
  EXPECT_TRUE(told_controller);
  const std::size_t sent = sent_a.packets.size();
  time.advance(2s);  // no reports (or anything else) after the shutdown
  EXPECT_EQ(sent_a.packets.size(), sent);
}

TEST(NodeWithManager, PeersDiscoverEachOtherFromHeartbeats) {
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time, 1ms);
  node::NodeConfig ca, cb;
  cb.subsystem = 2;
  auto& link_a = network.attach(ca.subsystem, ca.node);
  auto& link_b = network.attach(cb.subsystem, cb.node);
  node::Node a(ca, time, time, link_a), b(cb, time, time, link_b);
  link_a.deliver_to(a);
  link_b.deliver_to(b);
  for (auto* n : {&a, &b}) {
    rt::ComponentConfig config;
    config.name = "node manager";
    config.address = Address{n == &a ? std::uint8_t{1} : std::uint8_t{2}, 1, 1, 1};
    n->add(std::make_unique<components::NodeManager>(config, n->environment(), *n, components::NodeManagerConfig{}));
  }
  time.advance(2500ms);
  EXPECT_EQ(b.known_subsystems(), (std::vector<Address>{{2, 1, 1, 1}, {1, 1, 1, 1}}));
}

}  // namespace
}  // namespace jaus::test

namespace jaus::test {
namespace {

// A subsystem heard (from its communicator, then its node manager) joins the
// node manager's subsystem list, with an Event to its subscriber; silent for
// the subsystem timeout, it leaves the list, with another Event.
TEST(NodeWithManager, SubsystemsFoundAndLostChangeTheListWithAnEvent) {
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time, 1ms);
  node::NodeConfig config;
  config.subsystem = 2;
  auto& link = network.attach(config.subsystem, config.node);
  LinkTransmissions sent(link);
  node::Node node(config, time, time, link);
  rt::ComponentConfig manager_config;
  manager_config.name = "node manager";
  manager_config.address = Address{2, 1, 1, 1};
  node.add(std::make_unique<components::NodeManager>(manager_config, node.environment(), node,
                                                     components::NodeManagerConfig{}));
  const auto receive = [&](const Address& from, const Address& to, const auto& message) {
    std::vector<std::uint8_t> bytes(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(message, std::span(bytes).subspan(kHeaderSize));
    ASSERT_TRUE(size);
    Header h;
    h.command_code = std::decay_t<decltype(message)>::code;
    h.source = from;
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    encode_header_unchecked(h, std::span(bytes).template first<kHeaderSize>());
    node.receive_bytes(std::span(bytes).first(kHeaderSize + *size));
  };
  const auto events_to = [&](const Address& requester) {
    std::vector<std::vector<Address>> lists;
    for (const auto& p : sent.packets) {
      const auto h = *decode_header(p);
      if (h.command_code != msg::Event::code || h.destination != requester) continue;
      const auto event = wire::decode_payload<msg::Event>(std::span(p).subspan(kHeaderSize));
      EXPECT_TRUE(event);
      if (!event) continue;
      const auto list = wire::decode_payload<msg::ReportSubsystemList>(event->report_message);
      EXPECT_TRUE(list);
      if (list) lists.push_back(list->subsystems);
    }
    return lists;
  };
  const Address ocu{9, 1, 40, 1}, everyone{255, 255, 1, 1};
  msg::CreateEvent create;
  create.report_code = msg::ReportSubsystemList::code;
  create.event_type = 1;
  receive(ocu, manager_config.address, create);
  time.advance(10ms);
  ASSERT_TRUE(events_to(ocu).empty());

  receive(Address{5, 3, 35, 1}, everyone, msg::ReportHeartbeatPulse{});  // a communicator announces subsystem 5
  time.advance(10ms);
  ASSERT_EQ(events_to(ocu).size(), 1u);
  EXPECT_EQ(events_to(ocu).back(), (std::vector<Address>{{2, 1, 1, 1}, {5, 3, 35, 1}, {9, 1, 1, 1}}));
  receive(Address{5, 2, 1, 1}, Address{5, 255, 1, 1}, msg::ReportHeartbeatPulse{});  // and one of its node managers
  EXPECT_EQ(node.known_subsystems()[1], (Address{5, 2, 1, 1}));

  for (int second = 0; second < 7; ++second) {  // subsystem 5 falls silent; the OCU keeps heartbeating
    receive(Address{9, 1, 1, 1}, everyone, msg::ReportHeartbeatPulse{});
    time.advance(1s);
  }
  ASSERT_EQ(events_to(ocu).size(), 2u);
  EXPECT_EQ(events_to(ocu).back(), (std::vector<Address>{{2, 1, 1, 1}, {9, 1, 1, 1}}));
  EXPECT_EQ(node.known_subsystems(), (std::vector<Address>{{2, 1, 1, 1}, {9, 1, 1, 1}}));
}

}  // namespace
}  // namespace jaus::test
