// The conversions between Part 3's camera bodies and the cameras' terms, the
// image codecs and the test pattern: pure functions, no time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "decoded_image.hpp"
#include "jaus/components/camera_reports.hpp"
#include "jaus/components/image_codec.hpp"
#include "jaus/components/test_pattern.hpp"

namespace jaus::test {
namespace {

using namespace components;
constexpr double kPi = std::numbers::pi;

CameraConfig ptz_camera() {
  CameraConfig c;
  c.pan = {-kPi, kPi / 2, 1.0};  // full scale pi: +50 % is pi/2
  c.tilt = {-0.5, 1.0, 0.5};
  c.zoom = {0, 100, 50};
  c.widest_horizontal_fov_rad = 1.2;
  c.narrowest_horizontal_fov_rad = 0.2;
  return c;
}

TEST(CameraReports, PositionIsPercentOfTheGreaterLimitClippedAndRateIsPercentOfMaxRate) {
  const MountAxis pan{-kPi, kPi / 2, 1.0};
  EXPECT_DOUBLE_EQ(percent_to_position(0, pan), 0);  // 0 % is home
  EXPECT_DOUBLE_EQ(percent_to_position(-50, pan), -kPi / 2);
  EXPECT_DOUBLE_EQ(percent_to_position(40, pan), 0.4 * kPi);
  EXPECT_DOUBLE_EQ(percent_to_position(80, pan), kPi / 2);  // 0.8 pi clipped to the maximum
  const MountAxis zoom{0, 100, 50};
  EXPECT_DOUBLE_EQ(percent_to_position(-30, zoom), 0);  // Part 3: <= 0 % of a 0..max axis is 0
  EXPECT_DOUBLE_EQ(percent_to_position(30, zoom), 30);
  EXPECT_DOUBLE_EQ(percent_to_rate(-50, pan), -0.5);
  EXPECT_DOUBLE_EQ(percent_to_rate(250, pan), 1.0);
}

TEST(CameraReports, SetCameraPoseFieldsMapToPanTiltZoomAndTheOthersAreIgnored) {
  CameraConfig c = ptz_camera();
  msg::CameraPoseCommandBody b;
  b.y_angular_percent = 50;   // field 8: pan, position
  b.x_angular_percent = -20;  // field 7: tilt, rate
  b.z_linear_percent = 40;    // field 6: zoom, position
  b.x_linear_percent = 10;    // fields 4, 5, 9: not ours
  b.z_angular_percent = 10;
  b.mode_indicator = pose_field::kXAngular;
  const PoseCommand p = to_mount_command(b, c);
  ASSERT_TRUE(p.command.pan && p.command.tilt && p.command.zoom);
  EXPECT_EQ(p.command.pan->mode, AxisMode::position);
  EXPECT_DOUBLE_EQ(p.command.pan->value, kPi / 2);
  EXPECT_EQ(p.command.tilt->mode, AxisMode::rate);
  EXPECT_DOUBLE_EQ(p.command.tilt->value, -0.1);
  EXPECT_DOUBLE_EQ(p.command.zoom->value, 40);
  EXPECT_EQ(p.ignored, pose_field::kXLinear | pose_field::kZAngular);

  c.tilt = {};  // a camera without tilt ignores it
  b = {};
  b.x_angular_percent = 50;
  const PoseCommand q = to_mount_command(b, c);
  EXPECT_EQ(q.command, MountCommand{});
  EXPECT_EQ(q.ignored, pose_field::kXAngular);
}

void expect_vec(const Vec3& v, double x, double y, double z) {
  EXPECT_NEAR(v.x, x, 1e-12);
  EXPECT_NEAR(v.y, y, 1e-12);
  EXPECT_NEAR(v.z, z, 1e-12);
}

TEST(CameraReports, CameraAxesInTheVehicleFrame) {
  // Home: looking forward (x), right is the vehicle's y.
  auto a = camera_axes_in_vehicle(0, 0);
  expect_vec(a.z, 1, 0, 0);
  expect_vec(a.x, 0, 1, 0);
  // Panned 90 degrees right: looking along y, its right is backwards.
  a = camera_axes_in_vehicle(kPi / 2, 0);
  expect_vec(a.z, 0, 1, 0);
  expect_vec(a.x, -1, 0, 0);
  // Tilted 90 degrees up: looking up (-z, the vehicle's z is down); right unchanged.
  a = camera_axes_in_vehicle(0, kPi / 2);
  expect_vec(a.z, 0, 0, -1);
  expect_vec(a.x, 0, 1, 0);
  // Both: orthonormal.
  a = camera_axes_in_vehicle(0.7, -0.3);
  EXPECT_NEAR(a.x.x * a.z.x + a.x.y * a.z.y + a.x.z * a.z.z, 0, 1e-12);
  EXPECT_NEAR(a.z.x * a.z.x + a.z.y * a.z.y + a.z.z * a.z.z, 1, 1e-12);
  EXPECT_GT(a.z.z, 0);  // pitched down: the optical axis points down (+z)
}

TEST(CameraReports, PoseReportAddsHomeToTheMountAndClampsToTheFields) {
  CameraConfig c = ptz_camera();
  c.name = "a name longer than fifteen";
  c.x_m = 0.4;
  c.y_m = -0.1;
  c.z_m = 40;  // beyond the field: clamped
  c.home_yaw_rad = kPi / 4;
  MountState m;
  m.pan_rad = kPi / 4;  // home + pan = 90 degrees right
  const auto b = to_camera_pose_body(c, m);
  EXPECT_EQ(b.camera_name, "a name longer t");
  EXPECT_DOUBLE_EQ(*b.x_origin_m, 0.4);
  EXPECT_DOUBLE_EQ(*b.z_origin_m, 32.767);
  EXPECT_NEAR(*b.z_axis_direction_cosine_y, 1, 1e-12);
  EXPECT_NEAR(*b.x_axis_direction_cosine_x, -1, 1e-12);
}

TEST(CameraReports, FieldOfViewFollowsTheZoomAndTheAspectRatio) {
  const CameraConfig c = ptz_camera();
  EXPECT_DOUBLE_EQ(horizontal_fov_rad(c, 0), 1.2);
  EXPECT_DOUBLE_EQ(horizontal_fov_rad(c, 100), 0.2);
  EXPECT_DOUBLE_EQ(horizontal_fov_rad(c, 50), 0.7);
  EXPECT_NEAR(*zoom_for_fov(c, 0.7), 50, 1e-9);
  const double v = vertical_fov_rad(1.2, 320, 240);
  EXPECT_LT(v, 1.2);
  EXPECT_NEAR(horizontal_from_vertical_fov_rad(v, 320, 240), 1.2, 1e-12);
  CameraConfig fixed = c;
  fixed.zoom = {};
  EXPECT_FALSE(zoom_for_fov(fixed, 0.7));
}

TEST(CameraReports, CapabilitiesAreClampedToTheCamerasRangesAndReportedFromTheConfiguration) {
  CameraConfig c = ptz_camera();
  c.description = "front camera";
  msg::CameraCapabilitiesCommandBody b;
  b.horizontal_resolution = 5000;
  b.vertical_resolution = 2;
  b.frame_rate_fps = 0;
  b.focus_percent = 30;  // not acted on
  const CameraSettings s = apply_capabilities(b, c, initial_settings(c));
  EXPECT_EQ(s.width, c.max_width);
  EXPECT_EQ(s.height, c.min_height);
  EXPECT_EQ(s.frame_rate_fps, c.min_frame_rate_fps);

  const auto r = to_capabilities_body(c, initial_settings(c));
  EXPECT_EQ(r.description, "front camera");
  EXPECT_NEAR(*r.max_horizontal_fov_rad, 1.2, 1e-12);
  EXPECT_NEAR(*r.min_horizontal_fov_rad, 0.2, 1e-12);
  EXPECT_NEAR(*r.max_vertical_fov_rad, vertical_fov_rad(1.2, 320, 240), 1e-12);
  EXPECT_EQ(r.max_horizontal_resolution, 1280);
  EXPECT_EQ(r.min_vertical_resolution, 16);
  EXPECT_EQ(r.min_frame_rate_fps, 1);
  EXPECT_EQ(r.max_frame_rate_fps, 30);
  EXPECT_FALSE(r.min_shutter_inverse_s);
}

TEST(CameraReports, FormatReportListsTheFormatInUseFirstAndAtMostFour) {
  CameraConfig c;
  c.image_formats = {11, 7, 12, 14, 15};
  CameraSettings s = initial_settings(c);
  EXPECT_EQ(s.image_format, 11);
  s.image_format = 7;
  const auto b = to_format_body(c, s);
  EXPECT_EQ(b.image_format_1, 7);
  EXPECT_EQ(b.image_format_2, 11);
  EXPECT_EQ(b.image_format_3, 12);
  EXPECT_EQ(b.image_format_4, 14);
  EXPECT_FALSE(b.audio_format_1);
}

TEST(ImageCodec, PngAndJpegDecodeBackWithTheirSize) {
  const RgbImage picture = test_pattern(64, 48, 3);
  const auto png = encode_image(picture, image_format::kPng);
  ASSERT_TRUE(png) << png.error().message();
  EXPECT_EQ(sniff_image_format(png->data), image_format::kPng);
  EXPECT_EQ(encoded_image_size(png->data)->width, 64);
  const auto decoded = decode_png(png->data);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->width, 64u);
  EXPECT_EQ(decoded->height, 48u);
  EXPECT_EQ(decoded->rgb, picture.rgb);  // lossless

  const auto jpeg = encode_image(picture, image_format::kJpeg);
  ASSERT_TRUE(jpeg) << jpeg.error().message();
  EXPECT_EQ(sniff_image_format(jpeg->data), image_format::kJpeg);
  EXPECT_EQ(encoded_image_size(jpeg->data)->height, 48);
  const auto from_jpeg = decode_jpeg(jpeg->data);
  ASSERT_TRUE(from_jpeg);
  EXPECT_EQ(from_jpeg->width, 64u);
  EXPECT_EQ(from_jpeg->height, 48u);

  EXPECT_FALSE(encode_image(picture, 12));  // BMP: not produced
  // libjpeg's own errors come back as values (its limit is 65500 pixels a side).
  const auto too_wide = encode_jpeg(RgbImage{65535, 1, std::vector<std::uint8_t>(65535 * 3)});
  ASSERT_FALSE(too_wide);
  EXPECT_NE(too_wide.error().message().find("JPEG"), std::string::npos);
  EXPECT_FALSE(encode_png(RgbImage{4, 4, {}}));
  EXPECT_FALSE(sniff_image_format(std::vector<std::uint8_t>{'G', 'I', 'F', '8'}));
}

TEST(TestPattern, ConsecutiveFramesDifferAndAFrameIsAlwaysTheSame) {
  EXPECT_NE(test_pattern(320, 240, 7).rgb, test_pattern(320, 240, 8).rgb);
  EXPECT_EQ(test_pattern(320, 240, 7).rgb, test_pattern(320, 240, 7).rgb);
  const auto tiny = test_pattern(1, 1, 0);
  EXPECT_EQ(tiny.rgb.size(), 3u);
}

}  // namespace
}  // namespace jaus::test
