// Issue 28, "Hostile network": what a sender may do by its standing. A
// sender the node cannot record gets refusals it understands and leaves no
// state behind; Set Emergency is obeyed from anyone, an unrecorded sender's
// as a hold only the local clear releases; an observer (outside
// transport.control_from) may query, subscribe and set/clear its own hold.
#include "harness.hpp"
#include "jaus/node/node.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using S = msg::PrimaryStatus;
using Standing = rt::SenderStanding;

msg::CreateServiceConnection pose_connection(double rate_hz = 10) {
  msg::CreateServiceConnection m;
  m.command_code = msg::ReportGlobalPose::code;
  m.periodic_rate_hz = rate_hz;
  m.presence_vector = 0x1FF;
  return m;
}

msg::CreateServiceConnection wrench_connection() {
  msg::CreateServiceConnection m;
  m.command_code = msg::SetWrenchEffort::code;
  m.periodic_rate_hz = 10;
  return m;
}

// ---- unrecorded --------------------------------------------------------------

TEST_F(ComponentTest, AnUnrecordedRequesterIsRefusedAServiceConnectionAndGetsNoReports) {
  outbox.clear();
  deliver_as(Standing::unrecorded, kOcuA, pose_connection());
  const auto confirms = outbox.to<msg::ConfirmServiceConnection>(kOcuA);
  ASSERT_EQ(confirms.size(), 1u);
  EXPECT_EQ(confirms[0].command_code, msg::ReportGlobalPose::code);
  EXPECT_EQ(confirms[0].response_code, msg::sc_response::kRefused);
  EXPECT_EQ(driver->service_connections().active(), 0u);
  EXPECT_EQ(driver->service_connections().counters().refused, 1u);
  EXPECT_EQ(driver->counters().refused_unrecorded, 1u);
  time.advance(2s);
  EXPECT_EQ(outbox.count<msg::ReportGlobalPose>(), 0u);  // no reports flow
  EXPECT_FALSE(driver->keeps_state_for(Address{2, 1, 0, 0}));
  // Its queries are answered as usual.
  deliver_as(Standing::unrecorded, kOcuA, msg::QueryComponentStatus{});
  EXPECT_EQ(outbox.to<msg::ReportComponentStatus>(kOcuA).size(), 1u);
}

TEST_F(ComponentTest, AnUnrecordedRequesterIsRefusedControl) {
  EXPECT_EQ(request_control(kOcuA, 10, Standing::unrecorded), msg::control_response::kNotAccepted);
  EXPECT_FALSE(driver->control().controller());
  EXPECT_EQ(driver->counters().refused_unrecorded, 1u);
  // Configured to reject refused requests: it is rejected the same way.
  make(5, 3s, /*reject=*/true);
  outbox.clear();
  deliver_as(Standing::unrecorded, kOcuA, msg::RequestComponentControl{{10}});
  EXPECT_EQ(outbox.to<msg::RejectComponentControl>(kOcuA).size(), 1u);
  EXPECT_TRUE(outbox.to<msg::ConfirmComponentControl>(kOcuA).empty());
  EXPECT_FALSE(driver->control().controller());
}

TEST_F(ComponentTest, AnUnrecordedSendersStandbyIsObeyed) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  drive(kOcuA, 40);
  ASSERT_TRUE(driver->moving);
  deliver_as(Standing::unrecorded, kOcuB, msg::Standby{});
  EXPECT_EQ(driver->state(), S::standby);
  EXPECT_FALSE(driver->moving);
}

// The hold of a sender the node cannot tie to an ID: its own Clear Emergency
// (or anyone's under its address) does not release it; the local clear does.
TEST(UnrecordedEmergency, IsObeyedAndOnlyTheLocalClearReleasesIt) {
  rt::VirtualTime time;
  RecordingOutbox outbox;
  rt::EmergencyLatch latch;  // the host's, for the local clear
  rt::ComponentConfig config;
  config.address = kDriver;
  TestDriver driver(config, rt::Environment{time, time, outbox});
  driver.share_emergency(latch);
  driver.start();
  deliver_to(driver, time, kOcuA, msg::SetEmergency{}, Standing::unrecorded);
  EXPECT_EQ(driver.state(), S::emergency);
  EXPECT_FALSE(driver.stops.empty());
  EXPECT_TRUE(latch.overflowed());
  EXPECT_TRUE(latch.holders().empty());  // no ID recorded for it
  EXPECT_EQ(latch.unrecorded(), 1u);
  EXPECT_EQ(driver.counters().unrecorded_emergencies, 1u);

  deliver_to(driver, time, kOcuA, msg::ClearEmergency{}, Standing::unrecorded);
  EXPECT_EQ(driver.state(), S::emergency);
  EXPECT_EQ(driver.counters().refused_unrecorded, 1u);
  EXPECT_EQ(driver.counters().refused_clears, 1u);
  deliver_to(driver, time, kOcuA, msg::ClearEmergency{});  // the same ID, recorded now: it holds nothing
  EXPECT_EQ(driver.state(), S::emergency);

  EXPECT_EQ(latch.clear_jaus_holders(), 1u);  // the local clear
  EXPECT_EQ(driver.state(), S::ready);
}

// Issue 42: while the host cannot persist its holds, a holder's Clear
// Emergency is refused (its status still says Emergency); a Set is obeyed,
// the local clear still clears, and once the holds can be written the
// holder's clear is taken again.
TEST(EmergencyClearsRefused, WhileHoldsCannotBePersistedTheHoldStays) {
  rt::VirtualTime time;
  RecordingOutbox outbox;
  rt::EmergencyLatch latch;
  rt::ComponentConfig config;
  config.address = kDriver;
  TestDriver driver(config, rt::Environment{time, time, outbox});
  driver.share_emergency(latch);
  driver.start();
  deliver_to(driver, time, kOcuA, msg::SetEmergency{});
  latch.refuse_clears(true);
  deliver_to(driver, time, kOcuB, msg::SetEmergency{});  // a stop is always taken
  deliver_to(driver, time, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver.state(), S::emergency);
  EXPECT_EQ(latch.holders(), (std::vector<Address>{kOcuA, kOcuB}));
  EXPECT_EQ(driver.counters().refused_clears, 1u);
  EXPECT_EQ(latch.clear(kOcuB), rt::EmergencyLatch::ClearResult::refused);
  EXPECT_EQ(latch.clear(kOcuC), rt::EmergencyLatch::ClearResult::not_a_holder);  // not a holder comes first
  latch.refuse_clears(false);
  deliver_to(driver, time, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver.state(), S::emergency);  // kOcuB holds on
  latch.refuse_clears(true);
  EXPECT_EQ(latch.clear_jaus_holders(), 1u);  // the local clear is never refused
  EXPECT_EQ(driver.state(), S::ready);
}

// A recorded holder's hold cannot be cleared by an unrecorded sender naming it.
TEST_F(ComponentTest, AnUnrecordedClearEmergencyReleasesNobodysHold) {
  deliver(kOcuA, msg::SetEmergency{});
  deliver_as(Standing::unrecorded, kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  deliver(kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
}

// A controller whose standing drops (its host moved outside control_from, or
// its route lost to a full table) commands nothing more.
TEST_F(ComponentTest, AControllerNoLongerTrustedCommandsNothing) {
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  msg::SetWrenchEffort effort;
  effort.propulsive_linear_effort_x_percent = 30;
  deliver_as(Standing::observer, kOcuA, effort);
  deliver_as(Standing::unrecorded, kOcuA, effort);
  EXPECT_TRUE(driver->executed.empty());
  EXPECT_EQ(driver->counters().refused_observer, 1u);
  EXPECT_EQ(driver->counters().refused_unrecorded, 1u);
  // Nor does it announce a command service connection.
  outbox.clear();
  deliver_as(Standing::observer, kOcuA, wrench_connection());
  EXPECT_EQ(outbox.to<msg::ConfirmServiceConnection>(kOcuA).at(0).response_code,
            msg::sc_response::kInsufficientAuthority);
  outbox.clear();
  deliver_as(Standing::unrecorded, kOcuA, wrench_connection());
  EXPECT_EQ(outbox.to<msg::ConfirmServiceConnection>(kOcuA).at(0).response_code, msg::sc_response::kRefused);
  EXPECT_EQ(driver->service_connections().active(), 0u);
  drive(kOcuA, 30);
  EXPECT_EQ(driver->executed.size(), 1u);
}

TEST_F(ComponentTest, RefusalsForStandingWriteABoundedLog) {
  logs.clear();
  for (int i = 0; i < 500; ++i) {
    const Address from{static_cast<std::uint8_t>(10 + i % 200), static_cast<std::uint8_t>(1 + i / 200), 40, 1};
    deliver_as(Standing::unrecorded, from, pose_connection());
    deliver_as(Standing::unrecorded, from, msg::RequestComponentControl{{10}});
    deliver_as(Standing::observer, from, msg::RequestComponentControl{{10}});
  }
  EXPECT_EQ(driver->counters().refused_unrecorded, 1000u);
  EXPECT_EQ(driver->counters().refused_observer, 500u);
  EXPECT_LE(logs.size(), 10u);
}

// ---- observer ----------------------------------------------------------------

TEST_F(ComponentTest, AnObserverCannotTakeControlStandbyOrCommandButMaySubscribe) {
  EXPECT_EQ(request_control(kOcuB, 200, Standing::observer), msg::control_response::kNotAccepted);
  EXPECT_FALSE(driver->control().controller());
  deliver_as(Standing::observer, kOcuB, msg::Standby{});
  EXPECT_EQ(driver->state(), S::ready);
  EXPECT_EQ(driver->counters().refused_observer, 2u);

  // No command service connection (response 3, as for any non-controller);
  // an inform one is fine.
  outbox.clear();
  deliver_as(Standing::observer, kOcuB, wrench_connection());
  EXPECT_EQ(outbox.to<msg::ConfirmServiceConnection>(kOcuB).at(0).response_code,
            msg::sc_response::kInsufficientAuthority);
  EXPECT_EQ(driver->counters().refused_observer, 3u);
  outbox.clear();
  deliver_as(Standing::observer, kOcuB, pose_connection());
  EXPECT_EQ(outbox.to<msg::ConfirmServiceConnection>(kOcuB).at(0).response_code, msg::sc_response::kCreated);
  time.advance(1s);
  EXPECT_GE(outbox.to<msg::ReportGlobalPose>(kOcuB).size(), 10u);  // reports flow
  // Queries are answered.
  deliver_as(Standing::observer, kOcuB, msg::QueryComponentControl{});
  EXPECT_EQ(outbox.to<msg::ReportComponentControl>(kOcuB).size(), 1u);
}

TEST_F(ComponentTest, AnObserverSetsAndClearsItsOwnEmergencyOnly) {
  deliver_as(Standing::observer, kOcuB, msg::SetEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  EXPECT_EQ(driver->emergency().holders(), std::vector<Address>{kOcuB});
  deliver_as(Standing::observer, kOcuB, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
  // Another's hold is not its to clear.
  deliver(kOcuA, msg::SetEmergency{});
  deliver_as(Standing::observer, kOcuB, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  deliver(kOcuA, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::ready);
}

// ---- what the component keeps, for the transport's routes ------------------------

TEST_F(ComponentTest, KeepsStateForItsControllerItsHoldersAndItsRequesters) {
  const Address node_a{2, 1, 0, 0}, node_b{3, 1, 0, 0}, node_c{4, 1, 0, 0};
  EXPECT_FALSE(driver->keeps_state_for(node_a));
  ASSERT_EQ(request_control(kOcuA, 10), 0);
  deliver(kOcuB, msg::SetEmergency{});
  deliver(kOcuC, pose_connection());
  EXPECT_TRUE(driver->keeps_state_for(node_a));
  EXPECT_TRUE(driver->keeps_state_for(node_b));
  EXPECT_TRUE(driver->keeps_state_for(node_c));
  EXPECT_FALSE(driver->keeps_state_for(Address{2, 2, 0, 0}));
  EXPECT_FALSE(driver->keeps_state_for(Address{5, 1, 0, 0}));
  deliver(kOcuA, msg::ReleaseComponentControl{});
  deliver(kOcuB, msg::ClearEmergency{});
  deliver(kOcuC, msg::TerminateServiceConnection{{msg::ReportGlobalPose::code, 0}});
  EXPECT_FALSE(driver->keeps_state_for(node_a));
  EXPECT_FALSE(driver->keeps_state_for(node_b));
  EXPECT_FALSE(driver->keeps_state_for(node_c));
}

// ---- through the node ------------------------------------------------------------

class RecordingLink : public node::Link {
 public:
  void transmit(const Header&, std::span<const std::uint8_t> packet) override {
    packets.emplace_back(packet.begin(), packet.end());
  }
  template <class M>
  std::vector<M> to(const Address& destination) const {
    std::vector<M> out;
    for (const auto& p : packets) {
      const auto decoded = decode_packet(p);
      if (!decoded || decoded->header.command_code != M::code || decoded->header.destination != destination) continue;
      auto message = wire::decode_payload<M>(decoded->payload);
      EXPECT_TRUE(message) << M::name;
      if (message) out.push_back(*message);
    }
    return out;
  }
  std::vector<std::vector<std::uint8_t>> packets;
};

class StandingNodeTest : public ::testing::Test {
 protected:
  explicit StandingNodeTest(std::size_t liveness_entries = 1024) {
    node::NodeConfig config;
    config.liveness.max_entries = liveness_entries;
    n = std::make_unique<node::Node>(config, time, time, link);
    rt::ComponentConfig c;
    c.name = "driver";
    c.address = kDriver;
    c.authority = 5;
    driver = &n->add_as(std::make_unique<TestDriver>(c, n->environment()));
  }

  template <class M>
  void from(const Address& source, const M& message, Standing standing = Standing::trusted) {
    std::vector<std::uint8_t> bytes(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(message, std::span(bytes).subspan(kHeaderSize));
    ASSERT_TRUE(size);
    Header h;
    h.command_code = M::code;
    h.source = source;
    h.destination = kDriver;
    h.data_size = static_cast<std::uint16_t>(*size);
    encode_header_unchecked(h, std::span(bytes).template first<kHeaderSize>());
    bytes.resize(kHeaderSize + *size);
    const auto packet = decode_packet(bytes);
    ASSERT_TRUE(packet);
    n->receive(*packet, standing);
    time.run_ready();
  }

  rt::VirtualTime time;
  RecordingLink link;
  std::unique_ptr<node::Node> n;
  TestDriver* driver = nullptr;
};

// Two peers fill a table of six entries (subsystem, node and component each).
class FullLivenessTest : public StandingNodeTest {
 protected:
  FullLivenessTest() : StandingNodeTest(6) {
    from(kOcuA, msg::QueryComponentStatus{});
    from(kOcuB, msg::QueryComponentStatus{});
  }
};

TEST_F(FullLivenessTest, ANewcomerIsUnrecordedAndLeavesNoState) {
  ASSERT_EQ(n->liveness().size(), 6u);
  from(kOcuC, pose_connection());
  EXPECT_EQ(link.to<msg::ConfirmServiceConnection>(kOcuC).at(0).response_code, msg::sc_response::kRefused);
  from(kOcuC, msg::RequestComponentControl{{10}});
  EXPECT_EQ(link.to<msg::ConfirmComponentControl>(kOcuC).at(0).response_code, msg::control_response::kNotAccepted);
  from(kOcuC, msg::SetEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);
  from(kOcuC, msg::ClearEmergency{});
  EXPECT_EQ(driver->state(), S::emergency);  // only the local clear releases it
  EXPECT_EQ(driver->service_connections().active(), 0u);
  EXPECT_FALSE(driver->control().controller());
  EXPECT_TRUE(driver->emergency().holders().empty());
  EXPECT_FALSE(n->holds_state_for(4, 1));
  EXPECT_EQ(n->counters().unrecorded_senders, 4u);
  EXPECT_EQ(driver->counters().refused_unrecorded, 3u);
  // It is still answered.
  from(kOcuC, msg::QueryComponentStatus{});
  EXPECT_EQ(link.to<msg::ReportComponentStatus>(kOcuC).size(), 1u);
}

// Known peers keep their standing under a full table, and so does a new
// component of a known node: its node's silence still ends what it keeps.
TEST_F(FullLivenessTest, KnownNodesKeepTheirStanding) {
  from(kOcuA, pose_connection());
  EXPECT_EQ(link.to<msg::ConfirmServiceConnection>(kOcuA).at(0).response_code, msg::sc_response::kCreated);
  const Address sibling{kOcuB.subsystem, kOcuB.node, 41, 1};
  from(sibling, msg::RequestComponentControl{{10}});
  EXPECT_EQ(link.to<msg::ConfirmComponentControl>(sibling).at(0).response_code, msg::control_response::kAccepted);
  EXPECT_EQ(n->counters().unrecorded_senders, 0u);
  EXPECT_TRUE(n->holds_state_for(kOcuA.subsystem, kOcuA.node));
  EXPECT_TRUE(n->holds_state_for(kOcuB.subsystem, kOcuB.node));
}

TEST_F(StandingNodeTest, TheTransportsStandingReachesTheComponent) {
  from(kOcuA, msg::RequestComponentControl{{10}}, Standing::observer);
  EXPECT_EQ(link.to<msg::ConfirmComponentControl>(kOcuA).at(0).response_code, msg::control_response::kNotAccepted);
  from(kOcuA, pose_connection(), Standing::unrecorded);
  EXPECT_EQ(link.to<msg::ConfirmServiceConnection>(kOcuA).at(0).response_code, msg::sc_response::kRefused);
  EXPECT_EQ(driver->counters().refused_observer, 1u);
  EXPECT_EQ(driver->counters().refused_unrecorded, 1u);
}

TEST_F(StandingNodeTest, HoldsStateForTheNodesOfItsControllerHoldersAndRequesters) {
  EXPECT_FALSE(n->holds_state_for(2, 1));
  from(kOcuA, msg::RequestComponentControl{{10}});
  from(kOcuB, msg::SetEmergency{});
  from(kOcuC, pose_connection());
  EXPECT_TRUE(n->holds_state_for(kOcuA.subsystem, kOcuA.node));
  EXPECT_TRUE(n->holds_state_for(kOcuB.subsystem, kOcuB.node));
  EXPECT_TRUE(n->holds_state_for(kOcuC.subsystem, kOcuC.node));
  EXPECT_FALSE(n->holds_state_for(kOcuA.subsystem, 2));
  EXPECT_FALSE(n->holds_state_for(9, 1));
}

// A large data set is as trusted as its least trusted packet.
TEST_F(StandingNodeTest, ALargeDataSetTakesTheLeastStandingOfItsPackets) {
  msg::CreateServiceConnection m = pose_connection();
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(m, payload);
  ASSERT_TRUE(size);
  ASSERT_GE(*size, 2u);
  // Cut into two packets: first (flag 1) from an unrecorded sender, last (flag 8) trusted.
  const auto send_part = [&](std::uint8_t flag, std::uint16_t sequence, std::span<const std::uint8_t> part,
                             Standing standing) {
    std::vector<std::uint8_t> bytes(kHeaderSize + part.size());
    Header h;
    h.command_code = m.code;
    h.source = kOcuA;
    h.destination = kDriver;
    h.data_flag = static_cast<DataFlag>(flag);
    h.sequence = sequence;
    h.data_size = static_cast<std::uint16_t>(part.size());
    encode_header_unchecked(h, std::span(bytes).first<kHeaderSize>());
    std::copy(part.begin(), part.end(), bytes.begin() + kHeaderSize);
    const auto packet = decode_packet(bytes);
    ASSERT_TRUE(packet);
    n->receive(*packet, standing);
    time.run_ready();
  };
  const std::span<const std::uint8_t> whole = std::span(payload).first(*size);
  send_part(1, 7, whole.first(1), Standing::unrecorded);
  send_part(8, 8, whole.subspan(1), Standing::trusted);
  const auto confirms = link.to<msg::ConfirmServiceConnection>(kOcuA);
  ASSERT_EQ(confirms.size(), 1u);
  EXPECT_EQ(confirms[0].response_code, msg::sc_response::kRefused);
  EXPECT_EQ(driver->service_connections().active(), 0u);
}

}  // namespace
}  // namespace jaus::test
