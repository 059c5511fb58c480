// The simulated cameras under virtual time: mounts that move at their rate
// limits and hold, frames that follow the clock, and a directory source.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include "decoded_image.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/components/image_codec.hpp"
#include "jaus/components/simulated_cameras.hpp"
#include "jaus/components/test_pattern.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using namespace components;

VisualSensorConfig two_cameras() {
  VisualSensorConfig config;
  CameraConfig ptz;
  ptz.id = 1;
  ptz.pan = {-1.0, 1.0, 0.5};  // rad, rad/s
  ptz.tilt = {-0.5, 0.5, 0.25};
  ptz.zoom = {0, 100, 20};
  CameraConfig fixed;
  fixed.id = 2;
  config.cameras = {ptz, fixed};
  return config;
}

AxisCommand position(double v) { return {AxisMode::position, v}; }
AxisCommand rate(double v) { return {AxisMode::rate, v}; }

TEST(SimulatedCameras, PositionCommandsMoveAtTheAxisRateAndStopAtTheTarget) {
  rt::VirtualTime time;
  SimulatedCameras cameras(two_cameras(), time);
  cameras.command_mount(1, MountCommand{position(0.8), position(-2.0), position(50)});
  time.advance(1s);
  auto m = cameras.mount_state(1);
  EXPECT_NEAR(m.pan_rad, 0.5, 1e-9);  // 0.5 rad/s
  EXPECT_NEAR(m.tilt_rad, -0.25, 1e-9);
  EXPECT_NEAR(m.zoom_percent, 20, 1e-9);
  EXPECT_TRUE(m.moving);
  time.advance(2s);
  m = cameras.mount_state(1);
  EXPECT_NEAR(m.pan_rad, 0.8, 1e-9);
  EXPECT_NEAR(m.tilt_rad, -0.5, 1e-9);  // target -2 clipped to the limit
  EXPECT_NEAR(m.zoom_percent, 50, 1e-9);
  EXPECT_FALSE(m.moving);
}

TEST(SimulatedCameras, RateCommandsMoveUntilTheLimitAndHoldStopsWhereItIs) {
  rt::VirtualTime time;
  SimulatedCameras cameras(two_cameras(), time);
  cameras.command_mount(1, MountCommand{rate(0.4), std::nullopt, std::nullopt});
  time.advance(1s);
  EXPECT_NEAR(cameras.mount_state(1).pan_rad, 0.4, 1e-9);
  time.advance(10s);
  EXPECT_NEAR(cameras.mount_state(1).pan_rad, 1.0, 1e-9);  // at the limit, stays
  EXPECT_FALSE(cameras.mount_state(1).moving);
  cameras.command_mount(1, MountCommand{rate(-9), std::nullopt, std::nullopt});  // capped at max_rate
  time.advance(1s);
  EXPECT_NEAR(cameras.mount_state(1).pan_rad, 0.5, 1e-9);
  cameras.hold(1);
  time.advance(5s);
  EXPECT_NEAR(cameras.mount_state(1).pan_rad, 0.5, 1e-9);
  EXPECT_FALSE(cameras.mount_state(1).moving);
}

TEST(SimulatedCameras, AnAxisThatIsNotMovableNeverMovesAndUnknownCamerasAreIgnored) {
  rt::VirtualTime time;
  SimulatedCameras cameras(two_cameras(), time);
  cameras.command_mount(2, MountCommand{rate(1), position(1), position(50)});
  cameras.command_mount(9, MountCommand{rate(1), position(1), position(50)});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  cameras.command_mount(1, MountCommand{position(nan), std::nullopt, std::nullopt});
  time.advance(3s);
  const auto m = cameras.mount_state(2);
  EXPECT_EQ(m.pan_rad, 0);
  EXPECT_EQ(m.zoom_percent, 0);
  EXPECT_EQ(cameras.mount_state(1).pan_rad, 0);
  EXPECT_FALSE(cameras.capture(9, {}));
}

TEST(SimulatedCameras, FramesFollowTheClockInTheRequestedFormatAndSize) {
  rt::VirtualTime time;
  SimulatedCameras cameras(two_cameras(), time);
  const ImageRequest png{image_format::kPng, 160, 120, 10};
  const auto first = cameras.capture(1, png);
  ASSERT_TRUE(first) << first.error().message();
  EXPECT_EQ(first->data, cameras.capture(1, png)->data);  // same frame period, same frame
  time.advance(100ms);
  const auto second = cameras.capture(1, png);
  ASSERT_TRUE(second);
  EXPECT_NE(first->data, second->data);
  EXPECT_EQ(cameras.frame_number(10), 1u);
  const auto decoded = decode_png(second->data);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->width, 160u);
  EXPECT_EQ(decoded->rgb, test_pattern(160, 120, 1).rgb);

  const auto jpeg = cameras.capture(1, ImageRequest{image_format::kJpeg, 64, 32, 10});
  ASSERT_TRUE(jpeg);
  EXPECT_EQ(jpeg->format, image_format::kJpeg);
  EXPECT_EQ(decode_jpeg(jpeg->data)->height, 32u);
  EXPECT_FALSE(cameras.capture(1, ImageRequest{12, 64, 32, 10}));  // BMP
}

class ImageDirectoryTest : public ::testing::Test {
 protected:
  ImageDirectoryTest() {
    dir = std::filesystem::temp_directory_path() /
          ("jaus-visual-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
           std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ImageDirectoryTest() override { std::filesystem::remove_all(dir); }

  void write(const std::string& name, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(dir / name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  std::vector<std::uint8_t> png(std::uint16_t w, std::uint16_t h, std::uint64_t frame) {
    return *encode_png(test_pattern(w, h, frame));
  }

  std::filesystem::path dir;
};

TEST_F(ImageDirectoryTest, FilesPlayInNameOrderOnePerFrameInALoopAsTheyAre) {
  const auto a = png(40, 30, 1);
  const auto b = *encode_jpeg(test_pattern(20, 10, 2));
  write("b-second.jpg", b);
  write("a-first.png", a);
  write("notes.txt", {'h', 'i'});  // not an image: skipped
  rt::VirtualTime time;
  VisualSensorConfig config = two_cameras();
  config.cameras[0].image_directory = dir.string();
  SimulatedCameras cameras(config, time);
  const ImageRequest request{image_format::kPng, 320, 240, 5};
  auto image = cameras.capture(1, request);
  ASSERT_TRUE(image) << image.error().message();
  EXPECT_EQ(image->data, a);
  EXPECT_EQ(image->format, image_format::kPng);
  EXPECT_EQ(image->width, 40);
  time.advance(200ms);
  image = cameras.capture(1, request);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->data, b);
  EXPECT_EQ(image->format, image_format::kJpeg);  // the file's format, from its magic bytes
  EXPECT_EQ(image->width, 20);
  EXPECT_EQ(image->height, 10);
  time.advance(200ms);
  EXPECT_EQ(cameras.capture(1, request)->data, a);  // a loop
}

TEST_F(ImageDirectoryTest, AMissingOrEmptyDirectoryIsAnErrorOnCaptureAndAFilledOneWorksLater) {
  rt::VirtualTime time;
  VisualSensorConfig config = two_cameras();
  config.cameras[0].image_directory = (dir / "missing").string();
  config.cameras[1].image_directory = dir.string();
  SimulatedCameras cameras(config, time);
  const auto missing = cameras.capture(1, {});
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  EXPECT_FALSE(cameras.capture(2, {}));  // empty
  write("only.png", png(16, 16, 0));
  const auto later = cameras.capture(2, {});
  ASSERT_TRUE(later);
  EXPECT_EQ(later->width, 16);
}

}  // namespace
}  // namespace jaus::test
