// The page's frames (docs/console.md, "Protocol"): every type parsed, every
// malformed frame a clear error, every server frame formatted as documented.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "jaus/console/console_protocol.hpp"

namespace jaus::console {
namespace {

using nlohmann::json;

template <class F>
F parsed_as(const std::string& text) {
  auto frame = parse_page_frame(text);
  EXPECT_TRUE(frame) << text << ": " << (frame ? "" : frame.error().message());
  if (!frame) return F{};
  EXPECT_TRUE(std::holds_alternative<F>(*frame)) << text;
  return std::holds_alternative<F>(*frame) ? std::get<F>(*frame) : F{};
}

std::string error_of(const std::string& text) {
  auto frame = parse_page_frame(text);
  EXPECT_FALSE(frame) << text << " was accepted";
  return frame ? std::string() : frame.error().message();
}

const Address kDriver{1, 1, 33, 1};

TEST(ConsoleProtocol, ParsesControl) {
  EXPECT_EQ(parsed_as<ControlFrame>(R"({"type":"control","target":"1.1.33.1","action":"request","authority":5})"),
            (ControlFrame{kDriver, true, 5}));
  EXPECT_EQ(parsed_as<ControlFrame>(R"({"type":"control","target":"1.1.33.1","action":"release"})"),
            (ControlFrame{kDriver, false, 0}));
}

TEST(ConsoleProtocol, ParsesDrive) {
  EXPECT_EQ(parsed_as<DriveFrame>(R"({"type":"drive","target":"1.1.33.1","linear":50,"angular":-20.5,"held":true})"),
            (DriveFrame{kDriver, 50, -20.5, true}));
}

TEST(ConsoleProtocol, ParsesEmergencyWithAll) {
  EXPECT_EQ(parsed_as<EmergencyFrame>(R"({"type":"emergency","target":"all","action":"set"})"),
            (EmergencyFrame{Address{255, 255, 255, 255}, true}));
  EXPECT_EQ(parsed_as<EmergencyFrame>(R"({"type":"emergency","target":"1.1.33.1","action":"clear"})"),
            (EmergencyFrame{kDriver, false}));
}

TEST(ConsoleProtocol, ParsesStateCameraArmWaypoints) {
  EXPECT_EQ(parsed_as<StateFrame>(R"({"type":"state","target":"1.1.33.1","action":"resume"})"),
            (StateFrame{kDriver, true}));
  EXPECT_EQ(parsed_as<StateFrame>(R"({"type":"state","target":"1.1.33.1","action":"standby"})"),
            (StateFrame{kDriver, false}));
  EXPECT_EQ(parsed_as<CameraFrame>(R"({"type":"camera","target":"1.1.37.1","watch":true})"),
            (CameraFrame{Address{1, 1, 37, 1}, true, std::nullopt, std::nullopt}));
  EXPECT_EQ(parsed_as<CameraFrame>(R"({"type":"camera","target":"1.1.37.1","watch":false,"pan_deg":30,"tilt_deg":-10})"),
            (CameraFrame{Address{1, 1, 37, 1}, false, 30.0, -10.0}));
  EXPECT_EQ(parsed_as<ArmFrame>(R"({"type":"arm","target":"1.1.49.1","joints":[10,-20,0.5]})"),
            (ArmFrame{Address{1, 1, 49, 1}, {10, -20, 0.5}}));
  EXPECT_EQ(parsed_as<WaypointsFrame>(
                R"({"type":"waypoints","target":"1.1.46.1","points":[{"x":1,"y":2},{"x":-3,"y":4.5}],"speed_mps":0.5})"),
            (WaypointsFrame{Address{1, 1, 46, 1}, {{1, 2}, {-3, 4.5}}, 0.5}));
}

TEST(ConsoleProtocol, RefusesMalformedFramesWithTheReason) {
  EXPECT_EQ(error_of("not json"), "not JSON");
  EXPECT_EQ(error_of("[1,2]"), "a frame must be a JSON object");
  EXPECT_EQ(error_of(R"({"target":"1.1.33.1"})"), "a frame must have a \"type\" (text)");
  EXPECT_EQ(error_of(R"({"type":"fly"})"), "unknown frame type \"fly\"");
  EXPECT_EQ(error_of(R"({"type":"drive","target":"1.1.33","linear":0,"angular":0,"held":true})"),
            "drive: 'target' is not a JAUS ID: \"1.1.33\"");
  EXPECT_EQ(error_of(R"({"type":"drive","target":1,"linear":0,"angular":0,"held":true})"),
            "drive: 'target' must be a JAUS ID as text (\"1.1.33.1\")");
  EXPECT_EQ(error_of(R"({"type":"drive","target":"1.1.33.1","linear":101,"angular":0,"held":true})"),
            "drive: 'linear' must be a number in -100..100");
  EXPECT_EQ(error_of(R"({"type":"drive","target":"1.1.33.1","linear":0,"angular":"x","held":true})"),
            "drive: 'angular' must be a number in -100..100");
  EXPECT_EQ(error_of(R"({"type":"drive","target":"1.1.33.1","linear":0,"angular":0,"held":1})"),
            "drive: 'held' must be true or false");
  EXPECT_EQ(error_of(R"({"type":"control","target":"1.1.33.1","action":"take"})"),
            "control: 'action' must be \"request\" or \"release\"");
  EXPECT_EQ(error_of(R"({"type":"control","target":"1.1.33.1","action":"request"})"),
            "control: 'authority' must be a number in 0..255");
  EXPECT_EQ(error_of(R"({"type":"control","target":"1.1.33.1","action":"request","authority":2.5})"),
            "control: 'authority' must be a whole number");
  EXPECT_EQ(error_of(R"({"type":"emergency","target":"1.1.33.1","action":"on"})"),
            "emergency: 'action' must be \"set\" or \"clear\"");
  EXPECT_EQ(error_of(R"({"type":"state","target":"1.1.33.1","action":"go"})"),
            "state: 'action' must be \"resume\" or \"standby\"");
  EXPECT_EQ(error_of(R"({"type":"camera","target":"1.1.37.1"})"), "camera: 'watch' must be true or false");
  EXPECT_EQ(error_of(R"({"type":"camera","target":"1.1.37.1","watch":true,"pan_deg":400})"),
            "camera: 'pan_deg' must be a number in -360..360");
  EXPECT_EQ(error_of(R"({"type":"arm","target":"1.1.49.1","joints":[]})"), "arm: 'joints' must not be empty");
  EXPECT_EQ(error_of(R"({"type":"arm","target":"1.1.49.1","joints":["a"]})"),
            "arm: 'joints' must hold numbers (degrees or metres)");
  EXPECT_EQ(error_of(R"({"type":"arm","target":"1.1.49.1","joints":5})"),
            "arm: 'joints' must be an array of at most 32");
  EXPECT_EQ(error_of(R"({"type":"waypoints","target":"1.1.46.1","points":[{"x":1}],"speed_mps":1})"),
            "waypoints: each of 'points' must be {\"x\": m, \"y\": m} within +-100000 m");
  EXPECT_EQ(error_of(R"({"type":"waypoints","target":"1.1.46.1","points":[{"x":1,"y":1}],"speed_mps":-1})"),
            "waypoints: 'speed_mps' must be a number in 0..327.670000");
}

TEST(ConsoleProtocol, FormatsEveryServerFrame) {
  const Address self{254, 7, 40, 1};
  auto welcome =
      json::parse(format_frame(WelcomeFrame{self, 3, "0.1.0", 250, {{33, {"drive", "emergency"}}, {200, {"camera"}}}}));
  // The views by component ID (keys are text in JSON), the page's only way to pick its targets.
  EXPECT_EQ(welcome["views"], json({{"33", {"drive", "emergency"}}, {"200", {"camera"}}}));
  welcome.erase("views");
  EXPECT_EQ(welcome,
            json({{"type", "welcome"}, {"self", "254.7.40.1"}, {"page", 3}, {"version", "0.1.0"}, {"deadman_ms", 250}}));
  TreeFrame tree{{TreeSubsystem{1, "robot", {TreeNode{1, "vehicle", {TreeComponent{kDriver, "pd", "ready", self, 5}}}}}}};
  const auto t = json::parse(format_frame(tree));
  EXPECT_EQ(t["type"], "tree");
  EXPECT_EQ(t["subsystems"][0]["nodes"][0]["components"][0],
            json({{"address", "1.1.33.1"}, {"name", "pd"}, {"state", "ready"}, {"controller", "254.7.40.1"},
                  {"authority", 5}}));
  EXPECT_EQ(json::parse(format_frame(ControlStateFrame{kDriver, ControlState::lost, "taken over"})),
            json({{"type", "control"}, {"target", "1.1.33.1"}, {"state", "lost"}, {"why", "taken over"}}));
  EXPECT_EQ(json::parse(format_frame(DrivingFrame{kDriver, false, std::nullopt})),
            json({{"type", "driving"}, {"target", "1.1.33.1"}, {"sending", false}, {"by", nullptr}}));
  EXPECT_EQ(json::parse(format_frame(PoseFrame{Address{1, 1, 41, 1}, 1, 2, 0.5, 45.0, -75.0})),
            json({{"type", "pose"}, {"source", "1.1.41.1"}, {"x", 1.0}, {"y", 2.0}, {"yaw_rad", 0.5},
                  {"latitude", 45.0}, {"longitude", -75.0}}));
  EXPECT_EQ(json::parse(format_frame(VelocityFrame{Address{1, 1, 42, 1}, 1, 0, 0.1})),
            json({{"type", "velocity"}, {"source", "1.1.42.1"}, {"vx_mps", 1.0}, {"vy_mps", 0.0},
                  {"yaw_rate_rps", 0.1}}));
  EXPECT_EQ(json::parse(format_frame(ImageFrame{Address{1, 1, 37, 1}, "png", "AAEC", 7})),
            json({{"type", "image"}, {"source", "1.1.37.1"}, {"format", "png"}, {"data", "AAEC"}, {"frame", 7}}));
  EXPECT_EQ(json::parse(format_frame(ArmStateFrame{Address{1, 1, 49, 1}, {ArmJoint{-90, 90, 10, "deg"}}})),
            json({{"type", "arm"}, {"source", "1.1.49.1"},
                  {"joints", json::array({json({{"min", -90.0}, {"max", 90.0}, {"position", 10.0}, {"unit", "deg"}})})}}));
  EXPECT_EQ(json::parse(format_frame(EmergencyStateFrame{Address{255, 255, 255, 255}, true, {self}})),
            json({{"type", "emergency"}, {"target", "all"}, {"active", true}, {"holders", {"254.7.40.1"}}}));
  EXPECT_EQ(json::parse(format_frame(EventFrame{"2026-01-01T00:00:00.000Z", EventLevel::warn, "x"})),
            json({{"type", "event"}, {"time", "2026-01-01T00:00:00.000Z"}, {"level", "warn"}, {"text", "x"}}));
  EXPECT_EQ(json::parse(format_frame(LinkFrame{2, 150})),
            json({{"type", "link"}, {"peers", 2}, {"last_heard_ms", 150}}));
  EXPECT_EQ(json::parse(format_frame(LinkFrame{0, std::nullopt}))["last_heard_ms"], nullptr);
  EXPECT_EQ(json::parse(format_frame(ErrorFrame{"no"})), json({{"type", "error"}, {"text", "no"}}));
}

TEST(ConsoleProtocol, Base64) {
  const std::uint8_t bytes[] = {'M', 'a', 'n', 'y'};
  EXPECT_EQ(base64(std::span(bytes, 0)), "");
  EXPECT_EQ(base64(std::span(bytes, 1)), "TQ==");
  EXPECT_EQ(base64(std::span(bytes, 2)), "TWE=");
  EXPECT_EQ(base64(std::span(bytes, 3)), "TWFu");
  EXPECT_EQ(base64(std::span(bytes, 4)), "TWFueQ==");
}

}  // namespace
}  // namespace jaus::console
