// jaus-conform --profile jss against a real jausd with its JSS face on (the
// default components on the in-process simulated Clearpath platform), as a
// JSS team would run it: discovered the JSS way, every applicable JSS core
// and mobility case passes, and the reports are written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "default_jausd.hpp"
#include "jss_system.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

constexpr const char* kNode = "127.0.0.168";

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(JssConform, EveryApplicableJssCasePassesAgainstJausd) {
  DefaultJausd node("jss-conform", 14, kNode, jss_on_config());
  ASSERT_TRUE(node.started());
  const auto junit = node.dir() / "junit.xml";
  const auto report = node.dir() / "report.md";
  // jss.control.timeout waits out the controller timeout (some 6 s a component): every component of jausd shares
  // the runtime's controller liveness, so it runs once, on the driver, below.
  ChildProcess conform({JAUS_CONFORM_PATH, "--profile", "jss", "--to", kNode, "--junit", junit.string(), "--report",
                        report.string(), "--wait", "5", "--skip", "jss.control.timeout"},
                       (node.dir() / "jaus-conform.log").string());
  ASSERT_TRUE(conform.started());
  EXPECT_EQ(conform.wait(200s), std::optional<int>(0)) << conform.output() << "\n" << read(report) << node.output();
  const std::string output = conform.output();
  // The JSS components of the vehicle were tested: the node manager (discovery), the driver, the sensors and the
  // list driver.
  for (const char* component : {"14.1.1", "14.1.33", "14.1.38", "14.1.41", "14.1.42", "14.1.46"})
    EXPECT_NE(output.find(std::string("== ") + component), std::string::npos) << component << "\n" << output;
  for (const char* ran : {"pass  14.1.1 jss.discovery.services", "pass  14.1.33 jss.control.preemption",
                          "pass  14.1.33 jss.primitive_driver.effort", "pass  14.1.42 jss.velocity_state.presence",
                          "pass  14.1.46 jss.list_manager.validity", "pass  14.1.46 jss.list_driver.execute",
                          "pass  14.1.33 jss.management.emergency_other_client", "pass  14.1.33 jss.events.periodic"})
    EXPECT_NE(output.find(ran), std::string::npos) << ran << "\n" << output;
  EXPECT_NE(output.find(" 0 failed"), std::string::npos) << output;
  const std::string xml = read(junit);
  EXPECT_NE(xml.find("failures=\"0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"14.1.33\" name=\"jss.control.round_trip\""), std::string::npos) << xml;
  const std::string markdown = read(report);
  EXPECT_NE(markdown.find("Profile `jss`"), std::string::npos) << markdown;
  EXPECT_EQ(markdown.find("## Failures"), std::string::npos) << markdown;

  ChildProcess timeout({JAUS_CONFORM_PATH, "--profile", "jss", "--to", kNode, "--component", "14.1.33", "--only",
                        "jss.control.timeout", "--wait", "2"},
                       (node.dir() / "jaus-conform-timeout.log").string());
  ASSERT_TRUE(timeout.started());
  EXPECT_EQ(timeout.wait(60s), std::optional<int>(0)) << timeout.output();
  EXPECT_TRUE(timeout.output_shows("pass  14.1.33 jss.control.timeout: Report Timeout 3 s")) << timeout.output();
}

}  // namespace
}  // namespace jaus::test
