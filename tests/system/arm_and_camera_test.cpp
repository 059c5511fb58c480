// The visual sensor and the primitive manipulator end to end, with real
// processes and only jausctl as the OCU: on a jausd running its default
// components, jausctl takes control of the manipulator, moves a joint and
// reads the new position back; it points the front camera and reads its pose;
// and it subscribes to images and saves one that libpng opens as a picture of
// the configured size. Generous deadlines: a loaded machine, sanitizers.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "default_jausd.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kNode = "127.0.0.28";
constexpr const char* kManipulator = "6.1.49.1";
constexpr const char* kVisualSensor = "6.1.37.1";

class ArmAndCamera : public ::testing::Test {
 protected:
  void SetUp() override {
    jausd = std::make_unique<DefaultJausd>("arm-camera", 6, kNode);
    ASSERT_TRUE(jausd->started());
    // The daemon takes a moment to start (longer under sanitizers).
    const auto until = std::chrono::steady_clock::now() + 20s;
    while (!query(kManipulator, "0x2600")) {
      ASSERT_LT(std::chrono::steady_clock::now(), until) << jausd->output();
      std::this_thread::sleep_for(100ms);
    }
  }
  void TearDown() override { jausd.reset(); }

  std::unique_ptr<ChildProcess> jausctl(const std::string& name, std::vector<std::string> args,
                                        const std::string& bind) {
    auto child = jausd->jausctl_own_id(name, std::move(args), bind);
    EXPECT_TRUE(child->started());
    return child;
  }

  // `jausctl query ADDR CODE [--fields F]`: the report's fields, or nothing.
  std::optional<Json> query(const std::string& address, const std::string& code, const std::string& fields = "{}") {
    auto child = jausctl("query", {"query", address, code, "--fields", fields, "--timeout", "2"}, "127.0.0.29:0");
    if (child->wait(20s) != 0) return std::nullopt;
    std::istringstream lines(child->output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json report = Json::parse(line, nullptr, false);
        if (!report.is_discarded() && report.contains("fields")) return report["fields"];
      }
    return std::nullopt;
  }

  // Queries until `good` holds for the report's fields, or the deadline.
  std::optional<Json> poll(const std::string& address, const std::string& code, const std::string& fields,
                           const std::function<bool(const Json&)>& good, std::chrono::seconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    std::optional<Json> last;
    while (std::chrono::steady_clock::now() < until) {
      last = query(address, code, fields);
      if (last && good(*last)) return last;
      std::this_thread::sleep_for(200ms);
    }
    return last;
  }

  std::unique_ptr<DefaultJausd> jausd;
};

TEST_F(ArmAndCamera, JausctlMovesAJointAndReadsItBack) {
  const auto before = query(kManipulator, "Query Joint Positions");
  ASSERT_TRUE(before) << jausd->output();
  ASSERT_EQ((*before)["positions_rad"].size(), 6u) << before->dump();
  EXPECT_NEAR((*before)["positions_rad"][0].get<double>(), 0.0, 1e-3);

  // Joint 1 (base yaw) to 0.5 rad; the controller holds control meanwhile.
  auto controller = jausctl(
      "control",
      {"control", kManipulator, "--authority", "10", "--for", "30", "--rate", "2", "--send",
       R"({"name":"Set Joint Positions","fields":{"positions_rad":[0.5,0,0,0,0,0]}})"},
      "127.0.0.30:3794");
  const auto moved = poll(kManipulator, "Query Joint Positions", "{}",
                          [](const Json& f) { return std::abs(f["positions_rad"][0].get<double>() - 0.5) < 1e-3; },
                          30s);
  ASSERT_TRUE(moved) << jausd->output();
  EXPECT_NEAR((*moved)["positions_rad"][0].get<double>(), 0.5, 1e-3) << controller->output() << jausd->output();
  for (int j = 1; j < 6; ++j) EXPECT_NEAR((*moved)["positions_rad"][j].get<double>(), 0.0, 1e-3);

  // Out of the joint's limits (base yaw: +-170 degrees): refused whole, nothing moves.
  controller->signal(SIGINT);
  EXPECT_TRUE(controller->wait(10s)) << controller->output();
  auto refused = jausctl("refused",
                         {"control", kManipulator, "--authority", "10", "--for", "2", "--rate", "2", "--send",
                          R"({"name":"Set Joint Positions","fields":{"positions_rad":[3.1,0.2,0,0,0,0]}})"},
                         "127.0.0.30:3794");
  EXPECT_TRUE(refused->wait(20s)) << refused->output();
  const auto after = query(kManipulator, "Query Joint Positions");
  ASSERT_TRUE(after);
  EXPECT_NEAR((*after)["positions_rad"][0].get<double>(), 0.5, 1e-3);
  EXPECT_NEAR((*after)["positions_rad"][1].get<double>(), 0.0, 1e-3);
}

TEST_F(ArmAndCamera, JausctlPointsTheCameraAndSavesAnImageThatOpens) {
  // Pan the front camera to 50 % of its range (position mode) and read the pose back.
  const auto home = query(kVisualSensor, "Query Camera Pose", R"({"presence_vector":1023,"camera_id":1})");
  ASSERT_TRUE(home) << jausd->output();
  auto pointer = jausctl("control",
                         {"control", kVisualSensor, "--authority", "10", "--for", "30", "--rate", "2", "--send",
                          R"({"name":"Set Camera Pose","fields":{"camera_id":1,"mode_indicator":0,"y_angular_percent":50}})"},
                         "127.0.0.30:3794");
  // Polled until the pan has ended (within the tolerance below), not merely
  // begun: under load a poll can land mid-pan (0.990 is 82 degrees, moving).
  const double panned_y = std::sin(85.0 * std::numbers::pi / 180.0);
  const auto pointed = poll(
      kVisualSensor, "Query Camera Pose", R"({"presence_vector":1023,"camera_id":1})",
      [&](const Json& f) {
        return f != *home && f.contains("z_axis_direction_cosine_y") &&
               f["z_axis_direction_cosine_y"].get<double>() > panned_y - 0.002;
      },
      30s);
  ASSERT_TRUE(pointed) << pointer->output() << jausd->output();
  // Panned right by 85 degrees (half of 170) at 60 deg/s: the optical axis ends at sin(85 deg) on the
  // platform's right (+y), no further.
  EXPECT_NEAR((*pointed)["z_axis_direction_cosine_y"].get<double>(), panned_y, 0.002) << pointed->dump();
  const auto settled = query(kVisualSensor, "Query Camera Pose", R"({"presence_vector":1023,"camera_id":1})");
  ASSERT_TRUE(settled);
  EXPECT_NEAR((*settled)["z_axis_direction_cosine_y"].get<double>(), panned_y, 0.002);
  pointer->signal(SIGINT);
  EXPECT_TRUE(pointer->wait(10s));

  // Two images on a service connection; the last one stays in the file.
  const fs::path image = jausd->dir() / "frame.png";
  auto subscriber = jausctl("subscribe",
                            {"subscribe", kVisualSensor, "Report Image", "--rate", "2", "--count", "2",
                             "--save-image", image.string(), "--timeout", "5"},
                            "127.0.0.31:3794");
  ASSERT_EQ(subscriber->wait(60s), 0) << subscriber->output() << jausd->output();
  ASSERT_TRUE(fs::exists(image)) << subscriber->output();
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&png, image.c_str())) << png.message;
  EXPECT_EQ(png.width, 320u);
  EXPECT_EQ(png.height, 240u);
  png.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(png));
  ASSERT_TRUE(png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr)) << png.message;
  // A picture, not a blank: more than a handful of distinct colours.
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 2 < pixels.size(); i += 3)
    colours.insert(pixels[i] << 16 | pixels[i + 1] << 8 | pixels[i + 2]);
  EXPECT_GT(colours.size(), 4u);
}

}  // namespace
}  // namespace jaus::test
