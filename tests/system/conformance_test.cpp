// jaus-conform against a real jausd, as a team would run it before an event:
// with the default configuration (every component, on the simulated
// Clearpath platform) and with the components' own simulated vehicle. Every
// applicable case passes, and the JUnit and readable reports are written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "default_jausd.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Platform {
  const char* name;
  const char* address;
  const char* config;
};

void PrintTo(const Platform& platform, std::ostream* out) { *out << platform.name; }

class JausConform : public ::testing::TestWithParam<Platform> {};

TEST_P(JausConform, EveryApplicableCasePassesAgainstJausd) {
  const Platform& platform = GetParam();
  DefaultJausd node(std::string("conform-") + platform.name, 1, platform.address, platform.config);
  ASSERT_TRUE(node.started());
  const auto junit = node.dir() / "junit.xml";
  const auto report = node.dir() / "report.md";
  // The silent-requester case takes some 6 s per component (a node notices
  // silence after seconds): every component shares the runtime's liveness
  // code, so it runs once, on the driver, below.
  ChildProcess conform({JAUS_CONFORM_PATH, "--to", platform.address, "--junit", junit.string(), "--report",
                        report.string(), "--wait", "3", "--skip", "control.silent_requester"},
                       (node.dir() / "jaus-conform.log").string());
  ASSERT_TRUE(conform.started());
  // Thirteen components, some 7 s each (about 90 s in a Release build).
  EXPECT_EQ(conform.wait(200s), std::optional<int>(0)) << conform.output() << "\n" << read(report);
  const std::string output = conform.output();
  // Every component of the node was tested, and the summary says so.
  for (const char* component : {"1.1.1.1", "1.1.35.1", "1.1.33.1", "1.1.38.1", "1.1.41.1", "1.1.42.1", "1.1.37.1",
                                "1.1.49.1", "1.1.34.1", "1.1.44.1", "1.1.45.1", "1.1.46.1", "1.1.47.1", "1.1.48.1"})
    EXPECT_NE(output.find(std::string("== ") + component), std::string::npos) << component << "\n" << output;
  EXPECT_NE(output.find(" 0 failed"), std::string::npos) << output;
  const std::string xml = read(junit);
  EXPECT_NE(xml.find("<testsuites name=\"jaus-conform"), std::string::npos) << xml;
  EXPECT_NE(xml.find("failures=\"0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"1.1.33.1\" name=\"control.round_trip\""), std::string::npos) << xml;
  const std::string markdown = read(report);
  EXPECT_NE(markdown.find("# JAUS conformance: " + std::string(platform.address) + ":3794"), std::string::npos)
      << markdown;
  EXPECT_EQ(markdown.find("## Failures"), std::string::npos) << markdown;

  // A requester that falls silent loses the driver's control and its service connection.
  ChildProcess silent({JAUS_CONFORM_PATH, "--to", platform.address, "--component", "1.1.33.1", "--only",
                       "control.silent_requester", "--wait", "1"},
                      (node.dir() / "jaus-conform-silent.log").string());
  ASSERT_TRUE(silent.started());
  EXPECT_EQ(silent.wait(30s), std::optional<int>(0)) << silent.output();
  EXPECT_TRUE(silent.output_shows("pass  1.1.33.1 control.silent_requester: control dropped after"))
      << silent.output();
  EXPECT_TRUE(silent.output_shows("reports stopped after")) << silent.output();
}

INSTANTIATE_TEST_SUITE_P(Platforms, JausConform,
                         ::testing::Values(Platform{"clearpath_sim", "127.0.0.40", ""},
                                           Platform{"model", "127.0.0.41", "platform: model\n"}),
                         [](const ::testing::TestParamInfo<Platform>& p) { return std::string(p.param.name); });

// A component that does not answer fails, and the others are still tested.
TEST(JausConformUsage, AComponentThatDoesNotAnswerFailsAndTheOthersAreStillTested) {
  DefaultJausd node("conform-missing", 1, "127.0.0.42", "platform: model\n");
  ASSERT_TRUE(node.started());
  ChildProcess conform({JAUS_CONFORM_PATH, "--to", "127.0.0.42", "--component", "1.1.99.1", "--component", "1.1.35.1",
                        "--only", "core.status", "--wait", "1"},
                       (node.dir() / "jaus-conform.log").string());
  EXPECT_EQ(conform.wait(60s), std::optional<int>(1)) << conform.output();
  EXPECT_TRUE(conform.output_shows("fail  1.1.99.1 runner.answers: no reply from 1.1.99.1 within 1 s"))
      << conform.output();
  EXPECT_TRUE(conform.output_shows("pass  1.1.35.1 core.status: primary status")) << conform.output();
  EXPECT_TRUE(conform.output_shows("2 cases: 1 passed, 1 failed, 0 skipped")) << conform.output();
}

// A node that is not there: exit 2 and one line saying so.
TEST(JausConformUsage, NoNodeIsExit2AndOneLine) {
  const auto log =
      std::filesystem::temp_directory_path() / ("jaus-conform-none-" + std::to_string(::getpid()) + ".log");
  ChildProcess conform({JAUS_CONFORM_PATH, "--to", "127.0.0.42", "--wait", "0.5"}, log.string());
  EXPECT_EQ(conform.wait(20s), std::optional<int>(2));
  EXPECT_TRUE(conform.output_shows("jaus-conform: no JAUS node heard at 127.0.0.42:3794 within 0.5 s"))
      << conform.output();
  if (!HasFailure()) std::filesystem::remove(log);  // kept when it failed, to look at
}

TEST(JausConformUsage, BadArgumentsAreExit2AndOneLine) {
  const auto log = std::filesystem::temp_directory_path() / ("jaus-conform-bad-" + std::to_string(::getpid()) + ".log");
  ChildProcess conform({JAUS_CONFORM_PATH, "--to", "127.0.0.42", "--profile", "nasa"}, log.string());
  EXPECT_EQ(conform.wait(20s), std::optional<int>(2));
  EXPECT_TRUE(conform.output_shows("jaus-conform: --profile nasa: expected ra, openjaus or jss")) << conform.output();
  if (!HasFailure()) std::filesystem::remove(log);  // kept when it failed, to look at
}

}  // namespace
}  // namespace jaus::test
