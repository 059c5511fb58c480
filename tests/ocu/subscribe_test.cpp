// `jausctl subscribe`: reports at about the rate as JSON lines, the rate on
// stderr, and the service connection terminated on the way out.
#include <nlohmann/json.hpp>

#include "ocu_fixture.hpp"

namespace jausctl::test {
namespace {

ocu::SubscribeOptions pose_at(double hz) {
  ocu::SubscribeOptions o;
  o.target = kPoseSensor;
  o.report_code = jaus::msg::ReportGlobalPose::code;
  o.rate_hz = hz;
  return o;
}

TEST_F(OcuTest, SubscribeReceivesReportsAtAboutTheRateAndTerminates) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(5);
  options.presence_vector = 0x3;
  options.run_for = 2s;
  options.rate_every = 1s;
  ASSERT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitOk) << err.str();
  const auto lines = out_lines();
  EXPECT_GE(lines.size(), 5u);
  EXPECT_LE(lines.size(), 15u);
  for (const auto& line : lines) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j["code"], "0x4402");
    EXPECT_EQ(j["header"]["service_connection"], true);
    EXPECT_TRUE(j["fields"].contains("latitude_deg"));
    EXPECT_FALSE(j["fields"].contains("elevation_m"));  // outside the requested presence vector
  }
  const std::string e = err.str();
  EXPECT_NE(e.find("Report Global Pose (0x4402) from 1.1.38.1 at 5 Hz"), std::string::npos) << e;
  EXPECT_NE(e.find(" Hz)\n"), std::string::npos) << e;  // the measured rate, every second
  EXPECT_NE(e.find("; service connection terminated\n"), std::string::npos) << e;

  EXPECT_EQ(target->pose_sensor().service_connections().active(), 1u);  // the Terminate is on its way
  ASSERT_TRUE(run_until([&] { return target->pose_sensor().service_connections().active() == 0; }));
  EXPECT_EQ(target->pose_sensor().service_connections().counters().terminated, 1u);
}

TEST_F(OcuTest, SubscribeStopsAfterCount) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(20);
  options.count = 3;
  ASSERT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_EQ(out_lines().size(), 3u);
  ASSERT_TRUE(run_until([&] { return target->pose_sensor().service_connections().active() == 0; }));
}

TEST_F(OcuTest, SubscribeToAReportTheComponentDoesNotProvideIsRefused) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(5);
  options.target = kCommunicator;
  options.run_for = 1s;
  EXPECT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitFailure);
  EXPECT_EQ(err.str(),
            "jausctl subscribe: service connection for Report Global Pose (0x4402) from 1.1.35.1 refused: "
            "command not supported (response 6)\n");
}

TEST_F(OcuTest, SubscribeWithoutAnswerTimesOut) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(5);
  options.target = kNobody;
  options.timeout = 300ms;
  EXPECT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl subscribe: no reply from 1.1.42.1 within 0.3 s\n");
}

}  // namespace
}  // namespace jausctl::test
