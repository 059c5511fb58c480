// jaus-conform run from the `ocu` namespace against veh1 across the bridge
// (no loss) passes as on loopback: zero failures. The components: every one
// of veh1 (node manager, communicator, primitive driver, global pose and
// velocity state sensors, global vector driver: vehicles.hpp), about 7 s
// each, so the test stays under 90 s; the silent-requester case (some 6 s
// a component, the same runtime code in each) runs once, on the driver, as
// tests/system/conformance_test.cpp does.
#include "network_test.hpp"

namespace jaus::test::network {
namespace {

class ConformanceAcrossTheBridge : public NetworkTest {};

TEST_F(ConformanceAcrossTheBridge, EveryApplicableCasePassesAgainstVeh1FromTheOcu) {
  start_simulator();
  auto& veh1 = start_node(veh1_spec(Finding::alone));
  ASSERT_TRUE(wait_for_status("1.1.33.1", kVeh1, "ready", 30s)) << veh1.output();
  std::vector<std::string> argv = lab->exec_in(kOcu);
  argv.insert(argv.end(), {JAUS_CONFORM_PATH, "--to", kVeh1.address, "--bind", kOcu.address,
                           "--wait", "3", "--skip", "control.silent_requester"});
  for (const auto& c : veh1.spec().components)
    argv.insert(argv.end(), {"--component", veh1.address_of(c.id).to_string()});
  const auto started = Clock::now();
  ChildProcess conform(argv, (dir / "jaus-conform.log").string());
  ASSERT_TRUE(conform.started());
  EXPECT_EQ(conform.wait(120s), std::optional<int>(0)) << conform.output();
  const std::string output = conform.output();
  for (const auto& c : veh1.spec().components)
    EXPECT_NE(output.find("== " + veh1.address_of(c.id).to_string()), std::string::npos) << c.kind << "\n" << output;
  EXPECT_NE(output.find(" 0 failed"), std::string::npos) << output;

  ChildProcess silent({argv[0], argv[1], argv[2], argv[3], JAUS_CONFORM_PATH, "--to", kVeh1.address, "--bind", kOcu.address, "--component", "1.1.33.1", "--only",
                       "control.silent_requester", "--wait", "1"},
                      (dir / "jaus-conform-silent.log").string());
  ASSERT_TRUE(silent.started());
  EXPECT_EQ(silent.wait(30s), std::optional<int>(0)) << silent.output();
  EXPECT_TRUE(silent.output_shows("pass  1.1.33.1 control.silent_requester")) << silent.output();
  std::cout << "jaus-conform across the bridge: " << veh1.spec().components.size()
            << " components and the silent requester in " << seconds_since(started) << " s\n";
}

}  // namespace
}  // namespace jaus::test::network
