// jaus-console's core on a whole vehicle node under virtual time: the tree,
// control and emergencies seen by every page, the drive deadman (20 Hz while
// fresh, one zero at once on release, silence, a closed page; nothing once
// control is lost or the driver is not Ready), camera service connections
// following the pages that watch, the arm clamped to its limits, waypoints.
#include "console_node.hpp"

namespace jaus::test {
namespace {

using nlohmann::json;

class OperatorConsoleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(node.wait_ready());
    node.console().page_opened(1);
    node.console().page_opened(2);
    node.run_for(3s);  // discovery, the first status and control polls
  }

  std::size_t efforts_after(rt::TimePoint t) const {
    std::size_t n = 0;
    for (const auto& e : node.efforts())
      if (e.at > t) ++n;
    return n;
  }

  ConsoleNode node;
};

TEST_F(OperatorConsoleTest, WelcomesEachPageAndListsTheComponentsWithTheirStates) {
  const auto welcome = node.frames(1, "welcome");
  ASSERT_FALSE(welcome.empty());
  EXPECT_EQ(welcome.front()["self"], "254.1.40.1");
  EXPECT_EQ(welcome.front()["page"], 1);
  EXPECT_EQ(welcome.front()["deadman_ms"], 250);
  const auto trees = node.frames(2, "tree");
  ASSERT_FALSE(trees.empty());
  std::map<std::string, std::string> states;
  for (const auto& s : trees.back()["subsystems"])
    for (const auto& n : s["nodes"])
      for (const auto& c : n["components"]) states[c["address"]] = c["state"];
  EXPECT_EQ(states["1.1.33.1"], "ready");
  EXPECT_EQ(states["1.1.37.1"], "ready");
  EXPECT_EQ(states.count("254.1.40.1"), 0u) << "the console's own node is left out";
  EXPECT_FALSE(node.frames(1, "link").empty());
}

TEST_F(OperatorConsoleTest, ControlRequestAndReleaseAreSeenByBothPages) {
  ASSERT_TRUE(node.take_control(1));
  for (console::PageId page : {1, 2}) {
    const auto control = node.frames(page, "control");
    ASSERT_GE(control.size(), 2u);
    EXPECT_EQ(control[0]["state"], "requesting");
    EXPECT_EQ(control.back()["state"], "held");
  }
  node.run_for(2s);
  auto controller_of_driver = [&] {
    const auto trees = node.frames(1, "tree");
    for (const auto& s : trees.back()["subsystems"])
      for (const auto& n : s["nodes"])
        for (const auto& c : n["components"])
          if (c["address"] == "1.1.33.1") return c["controller"];
    return json();
  };
  EXPECT_EQ(controller_of_driver(), "254.1.40.1");

  node.page_sends(2, {{"type", "control"}, {"target", "1.1.33.1"}, {"action", "release"}});
  node.run_for(2s);
  for (console::PageId page : {1, 2}) EXPECT_EQ(node.frames(page, "control").back()["state"], "released");
  EXPECT_FALSE(node.console().holds_control(kPrimitiveDriver));
  EXPECT_EQ(controller_of_driver(), nullptr);
}

TEST_F(OperatorConsoleTest, DrivesAtTwentyHertzWhileHeldAndFresh) {
  ASSERT_TRUE(node.take_control(1));
  const auto start = node.time().now();
  node.hold(1, 60, 0, 2s);
  const auto sent = efforts_after(start - 1ms);
  EXPECT_GE(sent, 39u);
  EXPECT_LE(sent, 41u);
  EXPECT_GT(node.speed_mps(), 0.1) << "the vehicle moves";
  const auto driving = node.frames(2, "driving");
  ASSERT_FALSE(driving.empty());
  EXPECT_EQ(driving.front()["sending"], true);
  EXPECT_EQ(driving.front()["by"], 1);
}

TEST_F(OperatorConsoleTest, ReleasingTheKeySendsOneZeroAtOnceThenNothing) {
  ASSERT_TRUE(node.take_control(1));
  node.hold(1, 60, 10, 1s);
  const auto released = node.time().now();
  node.page_sends(1, {{"type", "drive"}, {"target", "1.1.33.1"}, {"linear", 0}, {"angular", 0}, {"held", false}});
  ASSERT_FALSE(node.efforts().empty());
  EXPECT_EQ(node.efforts().back().at, released) << "the zero goes in the same instant";
  EXPECT_EQ(node.efforts().back().linear, 0);
  EXPECT_EQ(node.efforts().back().angular, 0);
  node.run_for(1s);
  EXPECT_EQ(efforts_after(released), 0u);
  EXPECT_EQ(node.frames(1, "driving").back()["sending"], false);
  EXPECT_TRUE(node.run_until([&] { return node.speed_mps() < 0.01; }, 5s)) << "the vehicle stops";
}

TEST_F(OperatorConsoleTest, SilenceLongerThanTheDeadmanStopsWithinOnePeriod) {
  ASSERT_TRUE(node.take_control(1));
  node.hold(1, 60, 0, 1s);
  const auto last_frame = node.time().now() - 50ms;
  node.run_for(1s);
  ASSERT_FALSE(node.efforts().empty());
  const auto& zero = node.efforts().back();
  EXPECT_EQ(zero.linear, 0);
  EXPECT_GT(zero.at, last_frame + 250ms);
  EXPECT_LE(zero.at, last_frame + 250ms + 50ms);
  EXPECT_EQ(efforts_after(zero.at), 0u);
  EXPECT_EQ(node.console().counters().zero_efforts_sent, 1u);
}

TEST_F(OperatorConsoleTest, AClosedPageStopsItsDrive) {
  ASSERT_TRUE(node.take_control(1));
  node.hold(1, 60, 0, 500ms);
  const auto closed = node.time().now();
  node.console().page_closed(1);
  ASSERT_FALSE(node.efforts().empty());
  EXPECT_EQ(node.efforts().back().at, closed);
  EXPECT_EQ(node.efforts().back().linear, 0);
  node.run_for(1s);
  EXPECT_EQ(efforts_after(closed), 0u);
  EXPECT_EQ(node.frames(2, "driving").back()["sending"], false);
}

TEST_F(OperatorConsoleTest, ControlTakenOverStopsTheDriveAndEveryPageSeesItLost) {
  ASSERT_TRUE(node.take_control(1));
  node.hold(1, 60, 0, 500ms);
  node.rival().send(kPrimitiveDriver, msg::RequestComponentControl{{10}});  // higher authority: takes over
  const auto taken = node.time().now();
  // The page keeps holding the key: nothing more goes to a driver it lost.
  node.hold(1, 60, 0, 1s);
  EXPECT_FALSE(node.console().holds_control(kPrimitiveDriver));
  EXPECT_LE(efforts_after(taken + 20ms), 0u);
  for (console::PageId page : {1, 2}) EXPECT_EQ(node.frames(page, "control").back()["state"], "lost");
  EXPECT_FALSE(node.frames(1, "error").empty()) << "drive frames after the loss are refused";
}

TEST_F(OperatorConsoleTest, NothingIsSentToADriverThatIsNotReady) {
  node.rival().send(kPrimitiveDriver, msg::SetEmergency{{1}});
  node.run_for(200ms);
  ASSERT_EQ(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::emergency);
  node.page_sends(1, {{"type", "control"}, {"target", "1.1.33.1"}, {"action", "request"}, {"authority", 5}});
  node.hold(1, 60, 0, 2s);
  EXPECT_FALSE(node.console().holds_control(kPrimitiveDriver));
  EXPECT_TRUE(node.efforts().empty());
  const auto errors = node.frames(1, "error");
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors.back()["text"].get<std::string>().find("does not hold control"), std::string::npos);
  EXPECT_TRUE(node.frames(2, "error").empty()) << "an error answers the page that sent the frame";
}

TEST_F(OperatorConsoleTest, EmergencySetAndClearAreSeenByBothPages) {
  node.page_sends(1, {{"type", "emergency"}, {"target", "1.1.33.1"}, {"action", "set"}});
  node.run_for(300ms);
  EXPECT_EQ(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::emergency);
  for (console::PageId page : {1, 2}) {
    const auto e = node.frames(page, "emergency");
    ASSERT_FALSE(e.empty());
    EXPECT_EQ(e.back()["active"], true);
    EXPECT_EQ(e.back()["holders"], json::array({"254.1.40.1"}));
  }
  node.page_sends(2, {{"type", "emergency"}, {"target", "1.1.33.1"}, {"action", "clear"}});
  node.run_for(300ms);
  EXPECT_NE(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::emergency);
  for (console::PageId page : {1, 2}) EXPECT_EQ(node.frames(page, "emergency").back()["active"], false);
  bool acknowledged = false;
  for (const auto& e : node.frames(1, "event"))
    if (e["text"].get<std::string>().find("Set Emergency to 1.1.33.1: acknowledged") != std::string::npos)
      acknowledged = true;
  EXPECT_TRUE(acknowledged) << "Set Emergency goes ACK-requested";
}

// `all` (issue 49): every component stops, found yet or not, and the event
// says which confirmed it; a clear to `all` confirmed the same way.
TEST_F(OperatorConsoleTest, EmergencyToAllStopsEveryComponentAndSaysWhichConfirmedIt) {
  node.page_sends(1, {{"type", "emergency"}, {"target", "all"}, {"action", "set"}});
  node.run_for(3s);
  EXPECT_EQ(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::emergency);
  EXPECT_EQ(node.state_of(kCamera), rt::PrimaryStatus::emergency);
  EXPECT_EQ(node.state_of(kArm), rt::PrimaryStatus::emergency);
  const auto said = [&](const std::string& text) {
    for (const auto& e : node.frames(1, "event"))
      if (e["text"].get<std::string>().find(text) != std::string::npos) return e["level"].get<std::string>();
    return std::string();
  };
  EXPECT_EQ(said("Set Emergency to all: confirmed by "), "info");
  EXPECT_NE(said("1.1.33.1"), "");
  node.page_sends(1, {{"type", "emergency"}, {"target", "all"}, {"action", "clear"}});
  node.run_for(3s);
  EXPECT_NE(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::emergency);
  EXPECT_EQ(said("Clear Emergency to all: confirmed by "), "info");
}

TEST_F(OperatorConsoleTest, CameraImagesFlowWhileAPageWatchesAndTheConnectionCloses) {
  auto& camera = *node.find(kCamera);
  node.page_sends(1, {{"type", "camera"}, {"target", "1.1.37.1"}, {"watch", true}});
  node.page_sends(2, {{"type", "camera"}, {"target", "1.1.37.1"}, {"watch", true}});
  node.run_for(3s);
  EXPECT_EQ(camera.service_connections().active(), 1u) << "one connection for both pages";
  const auto images = node.frames(1, "image");
  ASSERT_GE(images.size(), 2u);
  EXPECT_NE(images[0]["frame"], images[1]["frame"]);
  EXPECT_FALSE(images[0]["data"].get<std::string>().empty());

  node.page_sends(1, {{"type", "camera"}, {"target", "1.1.37.1"}, {"watch", false}});
  node.run_for(1s);
  EXPECT_EQ(camera.service_connections().active(), 1u) << "page 2 still watches";
  node.console().page_closed(2);
  node.run_for(1s);
  EXPECT_EQ(camera.service_connections().active(), 0u);
}

TEST_F(OperatorConsoleTest, PanTiltTakesControlOfTheCameraAndCommandsIt) {
  node.page_sends(1, {{"type", "camera"}, {"target", "1.1.37.1"}, {"watch", false}, {"pan_deg", 30}, {"tilt_deg", 10}});
  EXPECT_TRUE(node.run_until([&] { return node.console().holds_control(kCamera); }, 2s));
  node.run_for(500ms);
  EXPECT_EQ(node.find(kCamera)->counters().refused_not_controller, 0u) << "Set Camera Pose came from the controller";
}

TEST_F(OperatorConsoleTest, ArmJointsAreClampedToTheirLimits) {
  // No control asked first: the joints ask for it (the OCU's authority) and go once it is held.
  ASSERT_TRUE(node.run_until([&] { return !node.frames(1, "arm").empty(); }, 3s));
  const auto joints = node.frames(1, "arm").back()["joints"];
  ASSERT_FALSE(joints.empty());
  json wanted = json::array();
  for (std::size_t i = 0; i < joints.size(); ++i) wanted.push_back(i == 0 ? 100000.0 : 0.0);
  node.page_sends(1, {{"type", "arm"}, {"target", "1.1.49.1"}, {"joints", wanted}});
  node.run_for(30s);
  const auto after = node.frames(1, "arm").back()["joints"];
  EXPECT_TRUE(node.console().holds_control(kArm));
  const double max = after[0]["max"];
  EXPECT_NEAR(after[0]["position"].get<double>(), max, 0.5) << "joint 1 goes to its maximum, no further";
  EXPECT_TRUE(node.frames(1, "error").empty());

  node.page_sends(1, {{"type", "arm"}, {"target", "1.1.49.1"}, {"joints", {1.0}}});
  if (joints.size() != 1) {
    EXPECT_FALSE(node.frames(1, "error").empty()) << "a wrong joint count is refused";
  }
}

TEST_F(OperatorConsoleTest, WaypointsAreLoadedAndResumeDrivesThem) {
  ASSERT_TRUE(node.take_control(1, kWaypointDriver));
  node.page_sends(1, {{"type", "waypoints"},
                      {"target", "1.1.46.1"},
                      {"points", {{{"x", 1}, {"y", 0}}, {{"x", 2}, {"y", 1}}, {{"x", 3}, {"y", 3}}}},
                      {"speed_mps", 0.5}});
  node.run_for(200ms);
  auto count = node.rival().request(kWaypointDriver, msg::QueryWaypointCount{}, {msg::ReportWaypointCount::code}, 1s);
  ASSERT_TRUE(count);
  msg::ReportWaypointCount report{};
  ASSERT_TRUE(wire::decode_payload_into(count->payload, report, wire::Dialect::ra, kHeaderSize));
  EXPECT_EQ(report.waypoint_count, 3);

  node.page_sends(1, {{"type", "state"}, {"target", "1.1.46.1"}, {"action", "resume"}});
  EXPECT_TRUE(node.run_until([&] { return node.speed_mps() > 0.1; }, 5s)) << "resume drives the route";
}

TEST_F(OperatorConsoleTest, PoseVelocityAndJointsFlowToEveryPage) {
  node.run_for(1s);
  for (const auto* type : {"pose", "velocity", "arm"}) EXPECT_GE(node.frames(2, type).size(), 4u) << type;
  const auto pose = node.frames(1, "pose").back();
  EXPECT_EQ(pose["source"], "1.1.41.1");
  EXPECT_TRUE(pose.contains("latitude")) << "the node's global pose sensor gives latitude and longitude";
  EXPECT_EQ(node.frames(1, "velocity").back()["source"], "1.1.42.1");
}

TEST_F(OperatorConsoleTest, StandbyLosesControlAndResumeTakesItAgain) {
  ASSERT_TRUE(node.take_control(1));
  node.page_sends(2, {{"type", "state"}, {"target", "1.1.33.1"}, {"action", "standby"}});
  node.run_for(300ms);
  EXPECT_EQ(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::standby);
  // Leaving Ready loses control (rt::ControlClient): nothing resumes by itself.
  EXPECT_EQ(node.frames(1, "control").back()["state"], "lost");
  // Resume asks for control again (with the authority asked before), then resumes as controller.
  node.page_sends(2, {{"type", "state"}, {"target", "1.1.33.1"}, {"action", "resume"}});
  ASSERT_TRUE(node.run_until([&] { return node.console().holds_control(kPrimitiveDriver); }, 2s));
  EXPECT_EQ(node.state_of(kPrimitiveDriver), rt::PrimaryStatus::ready);
}

TEST_F(OperatorConsoleTest, MalformedFramesAreAnsweredToTheirPageAndCounted) {
  node.page_sends(2, {{"type", "drive"}, {"target", "1.1.33.1"}});
  EXPECT_EQ(node.console().counters().frames_refused, 1u);
  ASSERT_EQ(node.frames(2, "error").size(), 1u);
  EXPECT_TRUE(node.frames(1, "error").empty());
}

TEST_F(OperatorConsoleTest, ShutdownZeroesTheDriveAndReleasesControl) {
  ASSERT_TRUE(node.take_control(1));
  node.hold(1, 60, 0, 500ms);
  const auto at = node.time().now();
  node.console().shutdown();
  ASSERT_FALSE(node.efforts().empty());
  EXPECT_EQ(node.efforts().back().at, at);
  EXPECT_EQ(node.efforts().back().linear, 0);
  node.run_for(1s);
  EXPECT_EQ(efforts_after(at), 0u);
  EXPECT_EQ(node.frames(1, "control").back()["state"], "released");
}

}  // namespace
}  // namespace jaus::test
