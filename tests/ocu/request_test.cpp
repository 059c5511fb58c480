// status, query, send and emergency against a node in process under virtual
// time (virtual_fixture.hpp), and the one line a
// command prints when nobody answers.
#include <nlohmann/json.hpp>

#include "jaus/ocu/message_json.hpp"
#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

using jaus::msg::PrimaryStatus;

ocu::PreparedMessage prepared(const std::string& json) {
  auto p = ocu::prepare_message(ocu::Json::parse(json), jaus::wire::Dialect::ra);
  EXPECT_TRUE(p) << p.error().message();
  return p ? *p : ocu::PreparedMessage{};
}

TEST_F(VirtualOcuTest, StatusPrintsTheComponentStatusAsJson) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_status(*ocu, kCommunicator, 1s, io()), kExitOk) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["component"], "1.1.35.1");
  EXPECT_EQ(j["primary_status"], "ready");
  EXPECT_EQ(j["primary_status_code"], 1);
  EXPECT_EQ(j["stops"], 0);
  EXPECT_EQ(j["emergency"], false);
}

// The stop counter moves on every stop, and stays moved once it is over.
TEST_F(VirtualOcuTest, StatusCountsTheStopsOfTheComponent) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  for (int stop = 1; stop <= 2; ++stop) {
    ocu->send(kCommunicator, jaus::msg::SetEmergency{{1}});
    ocu->send(kCommunicator, jaus::msg::ClearEmergency{{1}});
    out.str("");
    ASSERT_EQ(ocu::run_status(*ocu, kCommunicator, 1s, io()), kExitOk) << err.str();
    const auto j = nlohmann::json::parse(out.str());
    EXPECT_EQ(j["primary_status"], "ready");
    EXPECT_EQ(j["stops"], stop);
    EXPECT_EQ(j["secondary_status"].get<std::uint32_t>() >> 20, static_cast<std::uint32_t>(stop));
  }
}

TEST_F(VirtualOcuTest, NoReplyIsOneLineNamingTheComponentAndTheTimeout) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  EXPECT_EQ(ocu::run_status(*ocu, kNobody, 300ms, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl status: no reply from 1.1.42.1 within 0.3 s\n");
  EXPECT_EQ(out.str(), "");
}

TEST_F(VirtualOcuTest, QueryWithAPresenceVectorGetsTheReportWithThoseFields) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto query = ocu::prepare_query(jaus::msg::QueryGlobalPose::code, 0x3, ocu::Json::object());
  ASSERT_TRUE(query) << query.error().message();
  ASSERT_EQ(ocu::run_query(*ocu, kPoseSensor, *query, jaus::msg::ReportGlobalPose::code, 1s, io()), kExitOk)
      << err.str();
  const auto lines = out_lines();
  ASSERT_EQ(lines.size(), 1u);
  const auto j = nlohmann::json::parse(lines[0]);
  EXPECT_EQ(j["code"], "0x4402");
  EXPECT_EQ(j["name"], "Report Global Pose");
  EXPECT_EQ(j["header"]["source"], "1.1.38.1");
  EXPECT_EQ(j["header"]["destination"], "254.1.40.1");
  EXPECT_NEAR(j["fields"]["latitude_deg"].get<double>(), 45.5, 1e-6);
  EXPECT_NEAR(j["fields"]["longitude_deg"].get<double>(), -73.6, 1e-6);
  EXPECT_FALSE(j["fields"].contains("elevation_m"));
}

TEST_F(VirtualOcuTest, QueryFieldsOtherThanThePresenceVectorAreGiven) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto query = ocu::prepare_query(jaus::msg::QueryIdentification::code, std::nullopt, ocu::Json{{"query_type", 3}});
  ASSERT_TRUE(query) << query.error().message();
  ASSERT_EQ(ocu::run_query(*ocu, kTargetManager, *query, jaus::msg::ReportIdentification::code, 1s, io()), kExitOk)
      << err.str();
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["fields"]["identification"], "test-node");
  EXPECT_EQ(j["fields"]["type"], 40001);
}

TEST_F(VirtualOcuTest, QueryWithoutAnswerTimesOut) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto query = ocu::prepare_query(jaus::msg::QueryGlobalPose::code, std::nullopt, ocu::Json::object());
  ASSERT_TRUE(query);
  // The communicator does not answer Query Global Pose.
  EXPECT_EQ(ocu::run_query(*ocu, kCommunicator, *query, jaus::msg::ReportGlobalPose::code, 300ms, io()),
            kExitFailure);
  EXPECT_EQ(err.str(), "jausctl query: no reply from 1.1.35.1 within 0.3 s\n");
}

TEST_F(VirtualOcuTest, SendOfAJsonCommandActsAndItsClearUndoesIt) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  // As `jausctl msg decode` prints it, with someone else's addresses: they are replaced.
  const auto set = prepared(
      R"({"code":"0x0006","name":"Set Emergency","header":{"priority":6,"destination":"9.9.9.9","source":"8.8.8.8"},)"
      R"("fields":{"emergency_code":1}})");
  EXPECT_EQ(ocu::run_send(*ocu, kCommunicator, set, 300ms, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "");  // a command has no reply
  ASSERT_TRUE(run_until([&] { return target->communicator().state() == PrimaryStatus::emergency; }));
  EXPECT_TRUE(target->communicator().emergency().active());

  const auto clear = prepared(R"({"code":"0x0007","fields":{"emergency_code":1}})");
  EXPECT_EQ(ocu::run_send(*ocu, kCommunicator, clear, 300ms, io()), kExitOk);
  ASSERT_TRUE(run_until([&] { return target->communicator().state() == PrimaryStatus::ready; }));
}

TEST_F(VirtualOcuTest, SendPrintsTheReplyWhenOneComes) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_send(*ocu, kCommunicator, prepared(R"({"name":"Query Component Authority"})"), 1s, io()),
            kExitOk);
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["name"], "Report Component Authority");
  EXPECT_EQ(j["header"]["source"], "1.1.35.1");

  // A reply the runtime consumes itself (Confirm Service Connection) is shown too.
  out.str("");
  const auto create = prepared(
      R"({"name":"Create Service Connection","fields":{"command_code":17410,"periodic_rate_hz":1,"presence_vector":1}})");
  ASSERT_EQ(ocu::run_send(*ocu, kPoseSensor, create, 1s, io()), kExitOk);
  const auto confirm = nlohmann::json::parse(out_lines().at(0));
  EXPECT_EQ(confirm["name"], "Confirm Service Connection");
  EXPECT_EQ(confirm["fields"]["response_code"], "created");
}

TEST_F(VirtualOcuTest, EmergencySetAndClearShowTheResultingState) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, true, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "1.1.35.1: emergency set by 254.1.40.1 (state Emergency)\n");
  EXPECT_EQ(target->communicator().state(), PrimaryStatus::emergency);

  out.str("");
  ASSERT_EQ(ocu::run_emergency(*ocu, kCommunicator, false, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str(), "1.1.35.1: emergency cleared by 254.1.40.1 (state Ready)\n");
  EXPECT_EQ(target->communicator().state(), PrimaryStatus::ready);
}

TEST_F(VirtualOcuTest, ClearingSomeoneElsesEmergencyFailsAndSaysWhy) {
  auto other = open_ocu(jaus::Address{254, 2, 40, 1});
  auto ocu = open_ocu();
  ASSERT_TRUE(other && ocu);
  ASSERT_EQ(ocu::run_emergency(*other, kCommunicator, true, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(ocu::run_emergency(*ocu, kCommunicator, false, 1s, io()), kExitFailure);
  EXPECT_EQ(err.str(),
            "jausctl emergency: 1.1.35.1 is still in Emergency: another sender holds it, the platform's own stop does, or "
            "254.1.40.1 never set it\n");
  EXPECT_EQ(target->communicator().state(), PrimaryStatus::emergency);
}

}  // namespace
}  // namespace jausctl::test
