// `jausctl subscribe`: reports as JSON lines, the measured rate on stderr, and
// the service connection terminated on the way out, against a node in process
// under virtual time (virtual_fixture.hpp): the reports come, never faster
// than the rate. The rate itself is tested in
// tests/runtime/service_connection_test.cpp, and the measured rate's
// arithmetic is RateMeter's (values_test.cpp).
#include <nlohmann/json.hpp>

#include "virtual_fixture.hpp"

namespace jausctl::test {
namespace {

ocu::SubscribeOptions pose_at(double hz) {
  ocu::SubscribeOptions o;
  o.target = kPoseSensor;
  o.report_code = jaus::msg::ReportGlobalPose::code;
  o.rate_hz = hz;
  return o;
}

TEST_F(VirtualOcuTest, SubscribePrintsReportsAndTheMeasuredRateNeverFasterThanAskedAndTerminates) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(5);
  options.presence_vector = 0x3;
  options.run_for = 30s;  // only if the reports or the rate line never come
  options.rate_every = 1s;
  // Ends (as SIGINT does) once five reports and a measured rate are out.
  once([&] { return out_lines().size() >= 5 && err.str().find(" Hz)\n") != std::string::npos; },
       [&] { ocu->interrupt(); });
  const auto start = time.now();
  ASSERT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitOk) << err.str();
  const auto elapsed = std::chrono::duration<double>(time.now() - start).count();
  const auto lines = out_lines();
  EXPECT_GE(lines.size(), 5u);
  // 5 Hz, the first report at once: no more than that (one spare, for a
  // report on its way when the time was read).
  EXPECT_LE(static_cast<double>(lines.size()), 2 + 5 * elapsed) << elapsed << " s";
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

TEST_F(VirtualOcuTest, SubscribeForAWhileEndsWhenTheTimeIsUpAndTerminates) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(5);
  options.run_for = 300ms;
  const auto start = time.now();
  ASSERT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_GE(time.now() - start, 300ms);
  EXPECT_NE(err.str().find("; service connection terminated\n"), std::string::npos) << err.str();
  ASSERT_TRUE(run_until([&] { return target->pose_sensor().service_connections().active() == 0; }));
}

TEST_F(VirtualOcuTest, SubscribeStopsAfterCount) {
  auto ocu = open_ocu();
  ASSERT_TRUE(ocu);
  auto options = pose_at(20);
  options.count = 3;
  ASSERT_EQ(ocu::run_subscribe(*ocu, options, io()), kExitOk) << err.str();
  EXPECT_EQ(out_lines().size(), 3u);
  ASSERT_TRUE(run_until([&] { return target->pose_sensor().service_connections().active() == 0; }));
}

TEST_F(VirtualOcuTest, SubscribeToAReportTheComponentDoesNotProvideIsRefused) {
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

TEST_F(VirtualOcuTest, SubscribeWithoutAnswerTimesOut) {
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
