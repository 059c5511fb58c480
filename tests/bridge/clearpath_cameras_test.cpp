// The Clearpath camera mounts under virtual time, against the simulated
// platform (LoopbackClient): JAUS pan/tilt/zoom reach the simulated mount in
// its degrees and zoom factor, with the mapping's signs and offsets; rate mode
// is integrated and stops at the limit; hold stops; mount_state is 0x8400's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/bridge/clearpath_cameras.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"
#include "jaus/components/simulated_cameras.hpp"

namespace {

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
namespace rt = jaus::rt;
namespace bridge = jaus::bridge;
namespace components = jaus::components;
using namespace std::chrono_literals;
using components::AxisCommand;
using components::AxisMode;
using components::MountCommand;

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

components::VisualSensorConfig two_cameras() {
  components::CameraConfig c;
  c.id = 1;
  c.name = "mast";
  c.pan = {-std::numbers::pi / 2, std::numbers::pi / 2, 1.0};
  c.tilt = {-0.5, 0.5, 0.5};
  c.zoom = {0, 100, 50};
  components::CameraConfig d = c;
  d.id = 2;
  d.name = "rear";
  return components::VisualSensorConfig{{c, d}};
}

// Camera 1 on Clearpath mount 1: pan reversed and 10 deg off, zoom 1x..10x.
bridge::ClearpathCamerasConfig mast_on_mount_1() {
  bridge::ClearpathMountConfig m;
  m.camera_id = 1;
  m.mount = 1;
  m.pan_sign = -1;
  m.pan_offset_deg = 10;
  m.tilt_sign = 1;
  m.tilt_offset_deg = 0;
  m.zoom_min_factor = 1;
  m.zoom_max_factor = 10;
  bridge::ClearpathCamerasConfig config;
  config.mounts = {m};
  return config;
}

MountCommand pan(AxisMode mode, double value) { return MountCommand{AxisCommand{mode, value}, {}, {}}; }
MountCommand tilt(AxisMode mode, double value) { return MountCommand{{}, AxisCommand{mode, value}, {}}; }
MountCommand zoom(AxisMode mode, double value) { return MountCommand{{}, {}, AxisCommand{mode, value}}; }

class ClearpathCamerasTest : public ::testing::Test {
 protected:
  explicit ClearpathCamerasTest(bridge::ClearpathCamerasConfig mapping = mast_on_mount_1())
      : loopback(time, time),
        platform(loopback, time, [this](rt::LogLevel, const std::string& line) { logs.push_back(line); }),
        images(two_cameras(), time),
        made_cameras(bridge::ClearpathCameras::make(platform, time, images, std::move(mapping)).value()),
        cameras(*made_cameras) {
    loopback.on_written([this](std::span<const std::uint8_t> frame) {
      const auto f = cp::decode_frame(frame);
      if (!f || f->header.type != cp::SetPanTiltZoom::kType) return;
      if (auto e = cp::decode(*f, cp::Direction::to_platform))
        if (const auto* m = e->message.get_if<cp::SetPanTiltZoom>()) sent.push_back(*m);
    });
  }

  void run(rt::Duration d) { time.advance(d); }
  const sim::Mount& mount(std::size_t i) const { return loopback.platform().vehicle().mounts().at(i); }
  bool logged(const std::string& text) const {
    return std::any_of(logs.begin(), logs.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  }

  rt::VirtualTime time;
  sim::LoopbackClient loopback;
  std::vector<std::string> logs;
  bridge::PlatformConnection platform;
  components::SimulatedCameras images;
  std::unique_ptr<bridge::ClearpathCameras> made_cameras;
  bridge::ClearpathCameras& cameras;
  std::vector<cp::SetPanTiltZoom> sent;
};

TEST_F(ClearpathCamerasTest, ConfigsAndImagesComeFromTheInnerSource) {
  EXPECT_EQ(&cameras.configs(), &images.configs());
  run(100ms);
  const auto image = cameras.capture(1, components::ImageRequest{});
  ASSERT_TRUE(image) << image.error().message();
  EXPECT_FALSE(image->data.empty());
}

TEST_F(ClearpathCamerasTest, PanPositionReachesTheMountInItsDegreesAndSign) {
  run(200ms);  // the mount's first 0x8400
  cameras.command_mount(1, pan(AxisMode::position, 0.5));
  run(1s);
  // mount pan = 10 deg + (-1) * 0.5 rad
  const double expected = 10 - 0.5 * kDegPerRad;
  EXPECT_NEAR(mount(1).target_pan, expected, 0.01);
  EXPECT_NEAR(mount(1).pan, expected, 0.01);
  EXPECT_NEAR(mount(1).tilt, 0, 1e-9);  // left out: kept where it was
  EXPECT_NEAR(mount(1).zoom, 1, 1e-9);
  EXPECT_NEAR(mount(0).pan, 0, 1e-9);  // the other mount is not this camera's
  ASSERT_FALSE(sent.empty());
  EXPECT_EQ(sent.back().mount, 1);

  const auto state = cameras.mount_state(1);
  EXPECT_NEAR(state.pan_rad, 0.5, 1e-3);
  EXPECT_NEAR(state.tilt_rad, 0, 1e-3);
  EXPECT_NEAR(state.zoom_percent, 0, 1e-3);
  EXPECT_FALSE(state.moving);
}

TEST_F(ClearpathCamerasTest, PositionTargetsAreClippedToTheCameraLimits) {
  run(200ms);
  cameras.command_mount(1, MountCommand{AxisCommand{AxisMode::position, 3.0}, AxisCommand{AxisMode::position, -2.0}, {}});
  run(2s);
  EXPECT_NEAR(mount(1).pan, 10 - 90, 0.01);          // pi/2 reversed, from 10 deg
  EXPECT_NEAR(mount(1).tilt, -0.5 * kDegPerRad, 0.01);  // -0.5 rad
  EXPECT_NEAR(cameras.mount_state(1).pan_rad, std::numbers::pi / 2, 1e-3);
}

TEST_F(ClearpathCamerasTest, ZoomPercentIsTheMountsZoomFactor) {
  run(200ms);
  cameras.command_mount(1, zoom(AxisMode::position, 50));
  run(500ms);
  EXPECT_NEAR(mount(1).zoom, 5.5, 0.01);  // 1 + (10 - 1) * 50 %
  EXPECT_NEAR(cameras.mount_state(1).zoom_percent, 50, 0.2);
}

TEST_F(ClearpathCamerasTest, MountStateFollowsTheMountsDataAndSaysWhenItMoves) {
  run(200ms);
  cameras.command_mount(1, pan(AxisMode::position, -1.5));  // 10 + 86 deg at the mount's 90 deg/s
  run(300ms);
  auto state = cameras.mount_state(1);
  EXPECT_TRUE(state.moving);
  EXPECT_LT(state.pan_rad, -0.2);
  EXPECT_GT(state.pan_rad, -1.4);
  run(2s);
  state = cameras.mount_state(1);
  EXPECT_FALSE(state.moving);
  EXPECT_NEAR(state.pan_rad, -1.5, 1e-3);
  EXPECT_NEAR(mount(1).pan, 10 + 1.5 * kDegPerRad, 0.01);
}

TEST_F(ClearpathCamerasTest, RateModeIsIntegratedAndStopsAtTheLimit) {
  run(200ms);
  cameras.command_mount(1, tilt(AxisMode::rate, 0.4));
  run(500ms);
  auto state = cameras.mount_state(1);
  EXPECT_TRUE(state.moving);
  EXPECT_NEAR(state.tilt_rad, 0.2, 0.05);  // 0.4 rad/s for 0.5 s, the data 50 ms late at most
  EXPECT_GT(sent.size(), 5u);              // a target every 50 ms
  run(2s);                                 // the limit, 0.5 rad, after 1.25 s
  EXPECT_NEAR(mount(1).tilt, 0.5 * kDegPerRad, 0.01);
  EXPECT_NEAR(mount(1).target_tilt, 0.5 * kDegPerRad, 0.01);
  state = cameras.mount_state(1);
  EXPECT_FALSE(state.moving);
  EXPECT_NEAR(state.tilt_rad, 0.5, 1e-3);
  const std::size_t count = sent.size();
  run(1s);
  EXPECT_EQ(sent.size(), count);  // at the limit the stream ends
}

TEST_F(ClearpathCamerasTest, RateIsLimitedToTheAxisMaxRateAndFollowsTheSign) {
  run(200ms);
  // The mount at 0 deg is JAUS pan 10 deg (reversed, offset 10 deg).
  const double start = cameras.mount_state(1).pan_rad;
  EXPECT_NEAR(start, 10 / kDegPerRad, 1e-4);
  cameras.command_mount(1, pan(AxisMode::rate, 5.0));  // max_rate 1 rad/s
  run(1s);
  EXPECT_NEAR(cameras.mount_state(1).pan_rad - start, 1.0, 0.1);  // the data 50 ms late at most
  EXPECT_LT(mount(1).pan, -40);  // positive JAUS pan is negative mount pan here
}

TEST_F(ClearpathCamerasTest, HoldEndsRateMotionWhereTheMountIs) {
  run(200ms);
  cameras.command_mount(1, pan(AxisMode::rate, 1.0));
  run(500ms);
  cameras.hold(1);
  run(200ms);
  const double held = mount(1).pan;
  EXPECT_LT(held, 10 - 20);  // it did move
  run(1s);
  EXPECT_NEAR(mount(1).pan, held, 0.02);
  EXPECT_NEAR(mount(1).target_pan, held, 0.02);
  EXPECT_FALSE(cameras.mount_state(1).moving);
}

TEST_F(ClearpathCamerasTest, HoldStopsAPositionMove) {
  run(200ms);
  cameras.command_mount(1, pan(AxisMode::position, -1.5));
  run(300ms);
  cameras.hold(1);
  run(1s);
  EXPECT_LT(mount(1).pan, 10 + 60);  // it would have gone to 96 deg
  EXPECT_NEAR(mount(1).target_pan, mount(1).pan, 0.1);
  EXPECT_FALSE(cameras.mount_state(1).moving);
}

TEST_F(ClearpathCamerasTest, AnUnmappedCameraIsTheInnerSources) {
  run(200ms);
  cameras.command_mount(2, pan(AxisMode::position, 0.5));
  run(1s);
  EXPECT_NEAR(images.mount_state(2).pan_rad, 0.5, 1e-9);
  EXPECT_NEAR(cameras.mount_state(2).pan_rad, 0.5, 1e-9);
  EXPECT_TRUE(sent.empty());
  EXPECT_NEAR(mount(0).pan, 0, 1e-9);
  EXPECT_NEAR(mount(1).pan, 0, 1e-9);
}

TEST_F(ClearpathCamerasTest, CommandsBeforeTheMountsDataAreDropped) {
  cameras.command_mount(1, pan(AxisMode::position, 0.5));  // nothing heard from the platform yet
  EXPECT_EQ(cameras.counters().commands_dropped, 1u);
  EXPECT_TRUE(logged("mount command dropped"));
  run(1s);
  EXPECT_TRUE(sent.empty());
  EXPECT_NEAR(mount(1).pan, 0, 1e-9);
  EXPECT_GT(cameras.counters().mount_data, 0u);  // subscribed: data arrives now
}

TEST_F(ClearpathCamerasTest, LosingThePlatformEndsRateMotion) {
  run(200ms);
  cameras.command_mount(1, pan(AxisMode::rate, 0.5));
  run(300ms);
  loopback.set_plugged(false);
  run(2s);  // silence: the client marks the link down
  EXPECT_FALSE(platform.alive());
  EXPECT_TRUE(logged("rate motion ended"));
  EXPECT_GT(cameras.mount_state(1).pan_rad, 0.25);  // the last 0x8400 (0.17 rad at the start)
  EXPECT_FALSE(cameras.mount_state(1).moving);
  loopback.set_plugged(true);
  run(3s);
  ASSERT_TRUE(platform.alive());
  const double pan_now = mount(1).pan;
  const std::size_t count = sent.size();
  run(1s);
  EXPECT_EQ(sent.size(), count);  // nothing resumes by itself
  EXPECT_NEAR(mount(1).pan, pan_now, 1e-9);
  EXPECT_FALSE(cameras.mount_state(1).moving);
}

bridge::ClearpathCamerasConfig on_missing_mount() {
  auto config = mast_on_mount_1();
  config.mounts[0].mount = 7;  // the simulated platform has mounts 0 and 1
  return config;
}

class ClearpathCamerasMissingMountTest : public ClearpathCamerasTest {
 protected:
  ClearpathCamerasMissingMountTest() : ClearpathCamerasTest(on_missing_mount()) {}
};

TEST_F(ClearpathCamerasMissingMountTest, ARefusedSubscriptionIsLoggedAndNothingMoves) {
  run(500ms);
  EXPECT_TRUE(logged("subscription (0x4400) not applied (refused by the platform"));
  cameras.command_mount(1, pan(AxisMode::position, 0.5));
  run(500ms);
  EXPECT_TRUE(sent.empty());
  EXPECT_EQ(cameras.counters().commands_dropped, 1u);
}

TEST(ClearpathCamerasConfig, BadMappingsAreRefusedNamingTheCamera) {
  const auto cameras = two_cameras().cameras;
  EXPECT_TRUE(bridge::check_clearpath_cameras_config(cameras, mast_on_mount_1()));

  auto c = mast_on_mount_1();
  c.mounts[0].camera_id = 9;
  auto ok = bridge::check_clearpath_cameras_config(cameras, c);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("camera 9"), std::string::npos) << ok.error().message();

  c = mast_on_mount_1();
  c.mounts.push_back(c.mounts[0]);
  c.mounts[1].camera_id = 2;  // the same mount twice
  ok = bridge::check_clearpath_cameras_config(cameras, c);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message().find("mount used by another camera"), std::string::npos);

  c = mast_on_mount_1();
  c.mounts[0].tilt_sign = 0.5;
  EXPECT_FALSE(bridge::check_clearpath_cameras_config(cameras, c));

  c = mast_on_mount_1();
  c.mounts[0].zoom_min_factor = 0;  // one 0, not both
  EXPECT_FALSE(bridge::check_clearpath_cameras_config(cameras, c));

  c = mast_on_mount_1();
  c.mounts[0].pan_offset_deg = 150;  // pan +-90 deg reversed from 150: up to 240 deg
  ok = bridge::check_clearpath_cameras_config(cameras, c);
  EXPECT_TRUE(ok);  // still partly reachable: clipped to the mount's range

  c = mast_on_mount_1();
  c.data_rate_hz = 0;
  EXPECT_FALSE(bridge::check_clearpath_cameras_config(cameras, c));
}

// No cameras exist in an invalid state: the factory says why and makes none,
// and nothing reaches the platform (no subscription, no mount moved).
TEST(ClearpathCamerasConfig, AnInvalidMappingMakesNoCameras) {
  rt::VirtualTime time;
  sim::LoopbackClient loopback(time, time);
  bridge::PlatformConnection platform(loopback, time);
  components::SimulatedCameras images(two_cameras(), time);
  auto bad = mast_on_mount_1();
  bad.mounts[0].pan_sign = 2;
  const auto cameras = bridge::ClearpathCameras::make(platform, time, images, bad);
  ASSERT_FALSE(cameras);
  EXPECT_EQ(cameras.error().message(),
            bridge::check_clearpath_cameras_config(images.configs(), bad).error().message());
  time.advance(1s);
  EXPECT_EQ(loopback.platform().subscription_count(), 0u);
  EXPECT_NEAR(loopback.platform().vehicle().mounts()[1].pan, 0, 1e-9);
}

}  // namespace
