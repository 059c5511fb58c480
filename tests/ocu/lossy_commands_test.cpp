// jausctl's one-shot commands over a lossy link, under virtual time: an
// emergency is retransmitted until acknowledged (acted on even when its
// first datagrams are lost; a clear failure when nothing gets through), and
// status, query and the status after an emergency send their query again
// every 250 ms, so one lost datagram does not fail them.
#include <nlohmann/json.hpp>

#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/repeated_query.hpp"
#include "lossy_fixture.hpp"

namespace jausctl::test {
namespace {

using jaus::msg::PrimaryStatus;

class LossyCommandsTest : public LossyOcuTest {
 protected:
  PrimaryStatus state() const { return target->communicator().state(); }
};

TEST_F(LossyCommandsTest, EmergencySetActsWhenItsFirstDatagramsAreLost) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  cut_for(120ms);  // three transmissions lost (a stop to a node not measured yet goes every 50 ms)
  const auto start = time.now();
  ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, true, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "1.1.35.1: emergency set by 254.1.40.1 (state Emergency)\n");
  EXPECT_EQ(state(), PrimaryStatus::emergency);
  EXPECT_LE(time.now() - start, 150ms + 4 * kOneWay);  // acknowledged at 160 ms, the status a round trip later

  out.str("");
  cut_for(120ms);
  ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, false, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "1.1.35.1: emergency cleared by 254.1.40.1 (state Ready)\n");
  EXPECT_EQ(state(), PrimaryStatus::ready);
}

TEST_F(LossyCommandsTest, EmergencySetReportsFailureWhenEverythingIsLost) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(1, 1, 7);
  EXPECT_EQ(ocu::run_emergency(*ocu, kCommunicator, true, 1s, io()), kExitFailure);
  EXPECT_EQ(err.str(),
            "jausctl emergency: Set Emergency to 1.1.35.1 not acknowledged (200 transmissions in 10 s): it may NOT "
            "have stopped; stop it another way (its own stop button, the radio's)\n");
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(state(), PrimaryStatus::ready);
}

// The common RA 3.3 peer may ignore ACK requests: with --dialect openjaus an
// emergency not acknowledged is judged by the status that follows (with the
// RA dialect it is a failure, as above).
TEST_F(LossyCommandsTest, WithTheOpenJausDialectTheStatusTellsWhenNoAckComes) {
  ocu::SessionOptions options;
  options.dialect = jaus::wire::Dialect::openjaus;
  auto& link = network.attach(options.self.subsystem, options.self.node);
  // What reaches the OCU, but the ACKs: a peer that never sends them.
  const auto no_acks = [&link](std::function<void(std::span<const std::uint8_t>)> receiver) {
    if (!receiver) return link.on_receive({});
    link.on_receive([receiver = std::move(receiver)](std::span<const std::uint8_t> packet) {
      const auto decoded = jaus::decode_packet(packet);
      if (decoded && decoded->header.ack_nak == jaus::AckNak::ack) return;
      receiver(packet);
    });
  };
  auto session = ocu::OcuSession::attach(
      options, ocu::SessionEnvironment{&time, &time, &link, no_acks, jaus::testing::stepper(time)});
  ASSERT_TRUE(session) << session.error().message();
  ASSERT_EQ(ocu::run_emergency(**session, kCommunicator, true, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(err.str(), "jausctl emergency: Set Emergency to 1.1.35.1 not acknowledged (20 transmissions in 1 s) (the "
                       "peer may ignore ACK requests): its status tells\n");
  EXPECT_EQ(out.str(), "1.1.35.1: emergency set by 254.1.40.1 (state Emergency)\n");
  EXPECT_EQ(state(), PrimaryStatus::emergency);
}

TEST_F(LossyCommandsTest, EmergencyToNoSuchComponentIsRefusedByItsNode) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  EXPECT_EQ(ocu::run_emergency(*ocu, kNobody, true, 1s, io()), kExitFailure);
  EXPECT_EQ(err.str(),
            "jausctl emergency: Set Emergency to 1.1.42.1 refused by its node (NAK): no component there took it: it "
            "may NOT have stopped; stop it another way (its own stop button, the radio's)\n");
}

// To a wildcard: each component confirms it (wildcard_command_test.cpp has the rest).
TEST_F(LossyCommandsTest, EmergencyToABroadcastIsConfirmedByEachComponent) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(0.10, 0.10, 32);
  ASSERT_EQ(ocu::run_emergency(*ocu, jaus::Address{1, 255, 255, 255}, true, 1s, io()), kExitOk) << err.str();
  EXPECT_NE(out.str().find("confirmed by 3 components (1.1.1.1, 1.1.35.1, 1.1.38.1)"), std::string::npos) << out.str();
  EXPECT_EQ(state(), PrimaryStatus::emergency);
}

TEST_F(LossyCommandsTest, AtTenPercentLossEveryEmergencyOfTwentyTakesEffect) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(0.10, 0.10, 20);
  for (int i = 0; i < 20; ++i) {
    ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, true, 1s, io()), kExitOk) << i << ": " << err.str();
    EXPECT_EQ(state(), PrimaryStatus::emergency);
    ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, false, 1s, io()), kExitOk) << i << ": " << err.str();
    EXPECT_EQ(state(), PrimaryStatus::ready);
  }
}

TEST_F(LossyCommandsTest, StatusSendsItsQueryAgainWhenTheFirstIsLost) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  cut_for(100ms);
  const auto start = time.now();
  ASSERT_EQ(ocu::run_status(*ocu, kCommunicator, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(nlohmann::json::parse(out.str())["primary_status"], "ready");
  EXPECT_EQ(time.now() - start, ocu::kQueryResendPeriod + 2 * kOneWay);
}

TEST_F(LossyCommandsTest, QuerySendsItsQueryAgainWhenTheReportIsLost) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  auto query = ocu::prepare_query(jaus::msg::QueryGlobalPose::code, 0x3, ocu::Json::object());
  ASSERT_TRUE(query) << query.error().message();
  time.call_at(time.now() + 2ms, [&] { cut_for(100ms); });  // the query went, its report is lost
  const auto start = time.now();
  ASSERT_EQ(ocu::run_query(*ocu, kPoseSensor, *query, jaus::msg::ReportGlobalPose::code, 1s, io()), kExitOk)
      << err.str();
  EXPECT_EQ(nlohmann::json::parse(out.str())["name"], "Report Global Pose");
  EXPECT_EQ(time.now() - start, ocu::kQueryResendPeriod + 2 * kOneWay);
}

TEST_F(LossyCommandsTest, StatusAtTenPercentLossAnswersTwentyTimesOfTwenty) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(0.10, 0.10, 21);
  for (int i = 0; i < 20; ++i) {
    out.str("");
    ASSERT_EQ(ocu::run_status(*ocu, kCommunicator, 1s, io()), kExitOk) << i << ": " << err.str();
  }
}

// At 30 % each way a round trip fails half the time: 4 tries in the default
// 1 s all fail once in 15; --timeout 3 (12 tries) once in 3000.
TEST_F(LossyCommandsTest, StatusAtThirtyPercentLossAnswersTwentyTimesOfTwentyWithinThreeSeconds) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(0.30, 0.30, 21);
  for (int i = 0; i < 20; ++i) {
    out.str("");
    ASSERT_EQ(ocu::run_status(*ocu, kCommunicator, 3s, io()), kExitOk) << i << ": " << err.str();
  }
}

TEST_F(LossyCommandsTest, SendRetransmitsACommandUntilAcknowledged) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  auto standby = ocu::prepare_message(ocu::Json::parse(R"({"name":"Standby"})"), jaus::wire::Dialect::ra);
  ASSERT_TRUE(standby) << standby.error().message();
  cut_for(120ms);
  ASSERT_EQ(ocu::run_send(*ocu, kCommunicator, *standby, 300ms, io()), kExitOk) << err.str();
  EXPECT_EQ(state(), PrimaryStatus::standby);
}

TEST_F(LossyCommandsTest, SendSaysWhenACommandIsNotAcknowledged) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  auto resume = ocu::prepare_message(ocu::Json::parse(R"({"name":"Resume"})"), jaus::wire::Dialect::ra);
  ASSERT_TRUE(resume) << resume.error().message();
  lose(1, 1, 3);
  EXPECT_EQ(ocu::run_send(*ocu, kCommunicator, *resume, 300ms, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl send: Resume to 1.1.35.1 not acknowledged (6 transmissions in 3 s)\n");
}

TEST_F(LossyCommandsTest, SendOfAStopTriesAsAStop) {
  // Standby is a stop: as `emergency set` sends Set Emergency (the session's
  // stop settings), at least every 100 ms, never doubled, for 10 s.
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  auto standby = ocu::prepare_message(ocu::Json::parse(R"({"name":"Standby"})"), jaus::wire::Dialect::ra);
  ASSERT_TRUE(standby) << standby.error().message();
  lose(1, 1, 3);
  EXPECT_EQ(ocu::run_send(*ocu, kCommunicator, *standby, 300ms, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl send: Standby to 1.1.35.1 not acknowledged (200 transmissions in 10 s)\n");
}

}  // namespace
}  // namespace jausctl::test
