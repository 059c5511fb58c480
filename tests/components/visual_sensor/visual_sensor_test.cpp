// The visual sensor on simulated cameras, under virtual time: every message,
// the refusals that change nothing, the mounts held on every stop path, and
// images decoded back, by query and streamed as large data sets.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "decoded_image.hpp"
#include "harness.hpp"
#include "jaus/components/image_codec.hpp"
#include "jaus/components/simulated_cameras.hpp"
#include "jaus/components/test_pattern.hpp"
#include "jaus/components/visual_sensor.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using namespace components;
constexpr double kPi = std::numbers::pi;

const Address kVisualSensor{1, 1, 37, 1};

VisualSensorConfig default_cameras() {
  CameraConfig front;
  front.id = 1;
  front.name = "front";
  front.description = "front pan-tilt-zoom camera";
  front.x_m = 0.3;
  front.z_m = -0.5;
  front.pan = {-kPi, kPi, 1.0};
  front.tilt = {-0.5, 1.0, 0.5};
  front.zoom = {0, 100, 50};
  front.widest_horizontal_fov_rad = 1.2;
  front.narrowest_horizontal_fov_rad = 0.2;
  CameraConfig rear;
  rear.id = 2;
  rear.name = "rear";
  rear.home_yaw_rad = kPi;
  rear.image_formats = {11};
  return VisualSensorConfig{{front, rear}};
}

class VisualSensorTest : public ::testing::Test {
 protected:
  VisualSensorTest() { make(default_cameras()); }

  void make(VisualSensorConfig config) {
    sensor.reset();
    worker.reset();
    cameras = std::make_unique<SimulatedCameras>(std::move(config), time);
    rt::ComponentConfig component;
    component.name = "visual sensor";
    component.address = kVisualSensor;
    component.authority = 5;
    outbox.clock = &time;
    const auto log = [this](rt::LogLevel, const std::string& l) { logs.push_back(l); };
    sensor = std::make_unique<VisualSensor>(component, rt::Environment{time, time, outbox, log}, *cameras);
    sensor->start();
  }

  template <class M>
  void deliver(const Address& from, const M& m) {
    deliver_to(*sensor, time, from, m);
  }
  void take_control(const Address& ocu, std::uint8_t authority = 5) {
    deliver(ocu, msg::RequestComponentControl{{authority}});
    ASSERT_TRUE(sensor->control().is_controller(ocu));
  }
  void pose(const Address& from, std::uint8_t camera, std::optional<double> pan, std::optional<double> tilt,
            std::optional<double> zoom, std::uint8_t rate_bits = 0) {
    msg::SetCameraPose m;
    m.camera_id = camera;
    m.mode_indicator = rate_bits;
    m.y_angular_percent = pan;
    m.x_angular_percent = tilt;
    m.z_linear_percent = zoom;
    deliver(from, m);
  }
  // Time passes with the controller alive (it queries the status each
  // second, as an OCU would; 3 s of silence would release control).
  void advance_with(const Address& controller, rt::Duration d) {
    while (d > rt::Duration::zero()) {
      const rt::Duration step = std::min<rt::Duration>(d, 1s);
      time.advance(step);
      d -= step;
      deliver(controller, msg::QueryComponentStatus{});
    }
  }
  template <class M>
  std::vector<M> reports_to(const Address& a) const {
    return outbox.to<M>(a);
  }
  std::optional<msg::ReportImage> query_image(const Address& from) {
    outbox.clear();
    deliver(from, msg::QueryImage{});
    const auto images = reports_to<msg::ReportImage>(from);
    if (images.size() != 1) return std::nullopt;
    return images.front();
  }
  bool logged(const std::string& text) const { return any_line_contains(logs, text); }
  // A worker the test sees (captures counted, slow at will) instead of the sensor's own.
  ScheduledFrameWorker& use_worker(std::size_t capacity = 4, rt::Duration delay = {}) {
    worker = std::make_unique<ScheduledFrameWorker>(time, time, capacity, delay);
    sensor->use_frame_worker(*worker);
    return *worker;
  }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  std::unique_ptr<SimulatedCameras> cameras;
  std::unique_ptr<ScheduledFrameWorker> worker;  // declared before the sensor: outlives it
  std::unique_ptr<VisualSensor> sensor;
};

TEST_F(VisualSensorTest, CountSelectionAndSelectCamera) {
  ASSERT_EQ(sensor->state(), msg::PrimaryStatus::ready);
  deliver(kOcuB, msg::QueryCameraCount{});
  deliver(kOcuB, msg::QuerySelectedCamera{});
  ASSERT_EQ(reports_to<msg::ReportCameraCount>(kOcuB).size(), 1u);
  EXPECT_EQ(reports_to<msg::ReportCameraCount>(kOcuB)[0].camera_count, 2);
  EXPECT_EQ(reports_to<msg::ReportSelectedCamera>(kOcuB).at(0).camera_id, 1);

  take_control(kOcuA);
  deliver(kOcuA, msg::SelectCamera{{2}});
  EXPECT_EQ(sensor->selected_camera(), 2);
  deliver(kOcuA, msg::SelectCamera{{9}});  // unknown: refused, selection unchanged
  EXPECT_EQ(sensor->selected_camera(), 2);
  EXPECT_EQ(sensor->sensor_counters().refused_unknown_camera, 1u);
  EXPECT_TRUE(logged("no camera 9"));
  outbox.clear();
  deliver(kOcuB, msg::QuerySelectedCamera{});
  EXPECT_EQ(reports_to<msg::ReportSelectedCamera>(kOcuB).at(0).camera_id, 2);
  const auto image = query_image(kOcuB);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->camera_id, 2);
}

TEST_F(VisualSensorTest, CommandsFromANonControllerOutsideReadyOrForAnUnknownCameraChangeNothing) {
  const CameraSettings before = *sensor->settings(1);
  const auto send_all = [&](const Address& from, std::uint8_t camera) {
    deliver(from, msg::SelectCamera{{2}});
    pose(from, camera, 50, std::nullopt, std::nullopt, pose_field::kYAngular);
    msg::SetCameraCapabilities caps;
    caps.camera_id = camera;
    caps.horizontal_resolution = 640;
    deliver(from, caps);
    msg::SetCameraFormatOptions format;
    format.camera_id = camera;
    format.image_format = 7;
    deliver(from, format);
  };
  const auto unchanged = [&] {
    time.advance(1s);
    EXPECT_EQ(sensor->selected_camera(), 1);
    EXPECT_EQ(*sensor->settings(1), before);
    EXPECT_EQ(cameras->mount_state(1).pan_rad, 0);
  };
  send_all(kOcuA, 1);  // nobody has control
  unchanged();
  EXPECT_EQ(sensor->counters().refused_not_controller, 4u);
  take_control(kOcuA);
  send_all(kOcuB, 1);  // not the controller
  unchanged();
  EXPECT_EQ(sensor->counters().refused_not_controller, 8u);
  deliver(kOcuA, msg::Standby{});
  send_all(kOcuA, 1);  // the controller, in Standby
  unchanged();
  EXPECT_EQ(sensor->counters().refused_wrong_state, 4u);
  deliver(kOcuA, msg::Resume{});
  ASSERT_EQ(sensor->state(), msg::PrimaryStatus::ready);

  // Unknown camera: the three camera commands are refused (Select Camera 2 is fine, undo it).
  send_all(kOcuA, 7);
  deliver(kOcuA, msg::SelectCamera{{1}});
  unchanged();
  EXPECT_EQ(sensor->sensor_counters().refused_unknown_camera, 3u);

  // A format the camera lacks is refused whole, and so is any audio format.
  msg::SetCameraFormatOptions format;
  format.camera_id = 2;
  format.image_format = 7;  // the rear camera has PNG only
  deliver(kOcuA, format);
  EXPECT_EQ(sensor->settings(2)->image_format, 11);
  format.camera_id = 1;
  format.audio_format = 4;
  deliver(kOcuA, format);
  EXPECT_EQ(sensor->settings(1)->image_format, 11);
  EXPECT_EQ(sensor->sensor_counters().refused_formats, 2u);
  EXPECT_EQ(sensor->sensor_counters().formats_set, 0u);
}

TEST_F(VisualSensorTest, SetCameraPoseMovesTheMountAndReportCameraPoseFollowsIt) {
  take_control(kOcuA);
  pose(kOcuA, 1, 50, 100, 40);  // positions: pan pi/2, tilt 1.0 (clipped), zoom 40
  time.advance(1s);  // (3 s without the controller's traffic would release control)
  EXPECT_NEAR(cameras->mount_state(1).pan_rad, 1.0, 1e-9);  // on its way at 1 rad/s
  time.advance(2s);
  const MountState m = cameras->mount_state(1);
  EXPECT_NEAR(m.pan_rad, kPi / 2, 1e-4);  // percentages travel as 16-bit scaled integers
  EXPECT_NEAR(m.tilt_rad, 1.0, 1e-9);
  EXPECT_NEAR(m.zoom_percent, 40, 1e-2);

  deliver(kOcuB, msg::QueryCameraPose{{0x03FF, 1}});
  const auto reports = reports_to<msg::ReportCameraPose>(kOcuB);
  ASSERT_EQ(reports.size(), 1u);
  const auto& r = reports[0];
  EXPECT_EQ(r.camera_name, "front");
  EXPECT_NEAR(*r.x_origin_m, 0.3, 1e-3);
  EXPECT_NEAR(*r.z_origin_m, -0.5, 1e-3);
  const CameraAxes axes = camera_axes_in_vehicle(kPi / 2, 1.0);  // looking right and up
  EXPECT_NEAR(*r.z_axis_direction_cosine_x, axes.z.x, 1e-4);
  EXPECT_NEAR(*r.z_axis_direction_cosine_y, axes.z.y, 1e-4);
  EXPECT_NEAR(*r.z_axis_direction_cosine_z, axes.z.z, 1e-4);
  EXPECT_NEAR(*r.x_axis_direction_cosine_x, -1, 1e-4);
  EXPECT_LT(*r.z_axis_direction_cosine_z, 0);  // up is -z

  // A presence vector asks for some fields; absent axes keep their pose.
  outbox.clear();
  pose(kOcuA, 1, std::nullopt, 0, std::nullopt);  // tilt home only
  advance_with(kOcuA, 3s);
  EXPECT_NEAR(cameras->mount_state(1).pan_rad, kPi / 2, 1e-4);
  EXPECT_NEAR(cameras->mount_state(1).tilt_rad, 0, 1e-9);
  deliver(kOcuB, msg::QueryCameraPose{{0x0001, 2}});
  const auto rear = reports_to<msg::ReportCameraPose>(kOcuB);
  ASSERT_EQ(rear.size(), 1u);
  EXPECT_EQ(rear[0].camera_id, 2);
  EXPECT_EQ(wire::presence_of(rear[0]), 0x0001u);
  EXPECT_EQ(rear[0].camera_name, "rear");
  EXPECT_EQ(sensor->sensor_counters().poses_set, 2u);
}

TEST_F(VisualSensorTest, AQueryForAnUnknownCameraIsLoggedAndNotAnswered) {
  deliver(kOcuB, msg::QueryCameraPose{{0x03FF, 5}});
  deliver(kOcuB, msg::QueryCameraCapabilities{{0x7FFF, 5}});
  deliver(kOcuB, msg::QueryCameraFormatOptions{{0x7F, 5}});
  EXPECT_TRUE(outbox.sent.empty());
  EXPECT_EQ(sensor->sensor_counters().refused_unknown_camera, 3u);
  EXPECT_TRUE(logged("does not exist"));
}

TEST_F(VisualSensorTest, RateModeMovesUntilALimitOrANewCommand) {
  take_control(kOcuA);
  pose(kOcuA, 1, std::nullopt, 100, std::nullopt, pose_field::kXAngular);  // tilt up at 0.5 rad/s
  advance_with(kOcuA, 1s);
  EXPECT_NEAR(cameras->mount_state(1).tilt_rad, 0.5, 1e-9);
  advance_with(kOcuA, 5s);
  EXPECT_NEAR(cameras->mount_state(1).tilt_rad, 1.0, 1e-9);  // the limit
  pose(kOcuA, 1, std::nullopt, -50, std::nullopt, pose_field::kXAngular);  // down at 0.25 rad/s
  advance_with(kOcuA, 2s);
  EXPECT_NEAR(cameras->mount_state(1).tilt_rad, 0.5, 1e-4);
  pose(kOcuA, 1, std::nullopt, 0, std::nullopt, pose_field::kXAngular);  // rate 0: stop
  advance_with(kOcuA, 2s);
  EXPECT_NEAR(cameras->mount_state(1).tilt_rad, 0.5, 1e-4);
}

TEST_F(VisualSensorTest, EveryStopPathHoldsTheMountsAndNothingResumesTheMotion) {
  const auto check = [&](const std::string& what, auto trigger, auto recover) {
    SCOPED_TRACE(what);
    take_control(kOcuA);
    pose(kOcuA, 1, 20, std::nullopt, std::nullopt, pose_field::kYAngular);  // pan at 0.2 rad/s
    const double start = cameras->mount_state(1).pan_rad;
    time.advance(1s);
    ASSERT_TRUE(cameras->mount_state(1).moving);
    trigger();
    const double held = cameras->mount_state(1).pan_rad;
    EXPECT_GT(held, start);
    EXPECT_FALSE(cameras->mount_state(1).moving);
    recover();
    time.advance(2s);
    EXPECT_EQ(cameras->mount_state(1).pan_rad, held);
    EXPECT_FALSE(cameras->mount_state(1).moving);
  };
  check("standby", [&] { deliver(kOcuA, msg::Standby{}); }, [&] { deliver(kOcuA, msg::Resume{}); });
  check(
      "emergency", [&] { deliver(kOcuB, msg::SetEmergency{{1}}); },
      [&] { deliver(kOcuB, msg::ClearEmergency{{1}}); });
  ASSERT_EQ(sensor->state(), msg::PrimaryStatus::ready);
  check("control released", [&] { deliver(kOcuA, msg::ReleaseComponentControl{}); }, [] {});
  check("control taken over", [&] { take_control(kOcuB, 9); }, [&] { deliver(kOcuB, msg::ReleaseComponentControl{}); });
  check("controller silent", [&] { time.advance(4s); }, [] {});
  EXPECT_FALSE(sensor->control().is_controller(kOcuA));
  check("reset", [&] { deliver(kOcuA, msg::Reset{}); }, [] {});
  check("shutdown", [&] { deliver(kOcuA, msg::Shutdown{}); }, [] {});
  EXPECT_EQ(sensor->state(), msg::PrimaryStatus::shutdown);
}

TEST_F(VisualSensorTest, SetCameraCapabilitiesClampsToTheCameraAndSetsTheFieldOfViewThroughTheZoom) {
  take_control(kOcuA);
  msg::SetCameraCapabilities caps;
  caps.camera_id = 1;
  caps.horizontal_resolution = 5000;
  caps.vertical_resolution = 8;
  caps.frame_rate_fps = 100;
  caps.horizontal_fov_rad = 0.7;  // zoom 50 %
  caps.gain_percent = 20;         // not acted on
  deliver(kOcuA, caps);
  const CameraSettings s = *sensor->settings(1);
  EXPECT_EQ(s.width, 1280);
  EXPECT_EQ(s.height, 16);
  EXPECT_EQ(s.frame_rate_fps, 30);
  time.advance(2s);
  EXPECT_NEAR(cameras->mount_state(1).zoom_percent, 50, 1e-2);  // the FOV travels as a 16-bit scaled integer
  EXPECT_EQ(sensor->sensor_counters().capabilities_set, 1u);

  deliver(kOcuB, msg::QueryCameraCapabilities{{0x7FFF, 1}});
  const auto reports = reports_to<msg::ReportCameraCapabilities>(kOcuB);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].description, "front pan-tilt-zoom camera");
  EXPECT_NEAR(*reports[0].max_horizontal_fov_rad, 1.2, 1e-3);
  EXPECT_NEAR(*reports[0].min_horizontal_fov_rad, 0.2, 1e-3);
  EXPECT_EQ(reports[0].max_horizontal_resolution, 1280);
  EXPECT_EQ(reports[0].min_frame_rate_fps, 1);
  EXPECT_EQ(reports[0].max_frame_rate_fps, 30);
  outbox.clear();
  deliver(kOcuB, msg::QueryCameraCapabilities{{0x0060, 2}});  // max/min horizontal resolution only
  const auto masked = reports_to<msg::ReportCameraCapabilities>(kOcuB);
  ASSERT_EQ(masked.size(), 1u);
  EXPECT_EQ(wire::presence_of(masked[0]), 0x0060u);

  // A camera without a zoom cannot change its FOV: the rest still applies.
  caps.camera_id = 2;
  caps.horizontal_resolution = 640;
  deliver(kOcuA, caps);
  EXPECT_EQ(sensor->settings(2)->width, 640);
  EXPECT_EQ(cameras->mount_state(2).zoom_percent, 0);
}

TEST_F(VisualSensorTest, QueryImageSendsTheSelectedCamerasFrameAsARealPngOverOnePacket) {
  const auto image = query_image(kOcuB);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->camera_id, 1);
  EXPECT_EQ(image->image_format, image_format::kPng);
  // Over one packet: the component hands the node the whole frame (the node
  // splits it into a large data set).
  ASSERT_EQ(outbox.sent.size(), 1u);
  EXPECT_GT(outbox.sent[0].payload.size(), kMaxPayloadSize);
  const auto decoded = decode_png(image->data);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->width, 320u);
  EXPECT_EQ(decoded->height, 240u);

  time.advance(100ms);  // the next frame at 10 fps
  const auto next = query_image(kOcuB);
  ASSERT_TRUE(next);
  EXPECT_NE(next->data, image->data);
  EXPECT_EQ(sensor->sensor_counters().images_sent, 2u);
}

TEST_F(VisualSensorTest, FormatAndResolutionChosenByTheControllerAreWhatImagesUse) {
  take_control(kOcuA);
  msg::SetCameraFormatOptions format;
  format.camera_id = 1;
  format.image_format = image_format::kJpeg;
  deliver(kOcuA, format);
  msg::SetCameraCapabilities caps;
  caps.camera_id = 1;
  caps.horizontal_resolution = 160;
  caps.vertical_resolution = 120;
  deliver(kOcuA, caps);
  EXPECT_EQ(sensor->sensor_counters().formats_set, 1u);

  deliver(kOcuB, msg::QueryCameraFormatOptions{{0x7F, 1}});
  const auto formats = reports_to<msg::ReportCameraFormatOptions>(kOcuB);
  ASSERT_EQ(formats.size(), 1u);
  EXPECT_EQ(formats[0].image_format_1, image_format::kJpeg);  // in use first
  EXPECT_EQ(formats[0].image_format_2, image_format::kPng);
  EXPECT_FALSE(formats[0].image_format_3);
  EXPECT_FALSE(formats[0].audio_format_1);

  const auto image = query_image(kOcuB);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->image_format, image_format::kJpeg);
  const auto decoded = decode_jpeg(image->data);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->width, 160u);
  EXPECT_EQ(decoded->height, 120u);
}

TEST_F(VisualSensorTest, QueryImageIsAnsweredInReadyAndEmergencyNotInStandby) {
  take_control(kOcuA);
  deliver(kOcuA, msg::Standby{});
  EXPECT_FALSE(query_image(kOcuB));
  EXPECT_EQ(sensor->sensor_counters().image_queries_paused, 1u);
  EXPECT_TRUE(logged("Query Image from 3.1.40.1 not answered in Standby"));
  deliver(kOcuA, msg::Resume{});
  EXPECT_TRUE(query_image(kOcuB));
  deliver(kOcuB, msg::SetEmergency{{1}});
  ASSERT_EQ(sensor->state(), msg::PrimaryStatus::emergency);
  time.advance(200ms);  // a frame period on: a fresh capture
  EXPECT_TRUE(query_image(kOcuC)) << "a stop holds the mounts, not the picture";
}

// Frames streamed to `to` in [from, until).
std::vector<Sent> frames(const RecordingOutbox& outbox, const Address& to, rt::TimePoint from, rt::TimePoint until) {
  std::vector<Sent> out;
  for (const auto& s : outbox.sent)
    if (s.header.command_code == msg::ReportImage::code && s.header.destination == to && s.at >= from && s.at < until)
      out.push_back(s);
  return out;
}

TEST_F(VisualSensorTest, ImagesStreamAtTheRequestedRateCappedAtTheFrameRateAsLargeDataSets) {
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportImage::code, 5, 0}});
  const auto confirms = reports_to<msg::ConfirmServiceConnection>(kOcuB);
  ASSERT_EQ(confirms.size(), 1u);
  EXPECT_EQ(confirms[0].response_code, 0);
  EXPECT_NEAR(confirms[0].confirmed_rate_hz, 5, 0.01);
  const auto start = time.now();
  time.advance(1s);
  // The first period comes before the first frame is done (nothing waits for
  // it): the four after it each send the newest frame.
  const auto sent = frames(outbox, kOcuB, start, start + 1s);
  EXPECT_EQ(sent.size(), 4u);
  for (std::size_t i = 1; i < sent.size(); ++i) EXPECT_NE(sent[i].payload, sent[i - 1].payload);
  for (const auto& s : sent) {
    EXPECT_TRUE(s.header.service_connection);
    EXPECT_GT(s.payload.size(), kMaxPayloadSize);  // each whole, the node sends a large data set
    const auto report = wire::decode_payload<msg::ReportImage>(s.payload);
    ASSERT_TRUE(report);
    const auto decoded = decode_png(report->data);
    ASSERT_TRUE(decoded);
    EXPECT_EQ(decoded->width, 320u);
  }
  EXPECT_NE(sent.front().payload, sent.back().payload);  // captured when sent

  // Asked faster than the camera's 10 fps: confirmed at 10.
  outbox.clear();
  deliver(kOcuC, msg::CreateServiceConnection{{msg::ReportImage::code, 50, 0}});
  EXPECT_NEAR(reports_to<msg::ConfirmServiceConnection>(kOcuC).at(0).confirmed_rate_hz, 10, 0.01);
  const auto start_c = time.now();
  time.advance(1s);
  EXPECT_EQ(frames(outbox, kOcuC, start_c, start_c + 1s).size(), 10u);
}

TEST_F(VisualSensorTest, StandbyPausesTheStreamAndResumeRestartsItWithoutABacklog) {
  take_control(kOcuA);
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportImage::code, 10, 0}});
  time.advance(500ms);
  deliver(kOcuA, msg::Standby{});
  const auto paused = time.now();
  time.advance(2s);
  EXPECT_TRUE(frames(outbox, kOcuB, paused, time.now()).empty());
  deliver(kOcuA, msg::Resume{});
  const auto resumed = time.now();
  time.advance(50ms);
  EXPECT_LE(frames(outbox, kOcuB, resumed, time.now()).size(), 1u);  // no burst of the missed frames
  time.advance(950ms);
  const auto after = frames(outbox, kOcuB, resumed, time.now());
  EXPECT_GE(after.size(), 9u);
  EXPECT_LE(after.size(), 11u);
  // The stream's frames are the camera's at the time each was sent.
  const auto first = wire::decode_payload<msg::ReportImage>(after.front().payload);
  ASSERT_TRUE(first);
  const auto now_frame = query_image(kOcuC);
  ASSERT_TRUE(now_frame);
  EXPECT_NE(first->data, now_frame->data);
}

TEST_F(VisualSensorTest, TheStreamGoesOnInEmergencyWhileTheMountsAreHeld) {
  take_control(kOcuA);
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportImage::code, 10, 0}});
  pose(kOcuA, 1, 20, std::nullopt, std::nullopt, pose_field::kYAngular);  // pan at 0.2 rad/s
  time.advance(500ms);
  deliver(kOcuC, msg::SetEmergency{{1}});
  const double held = cameras->mount_state(1).pan_rad;
  const auto stopped = time.now();
  time.advance(1s);
  EXPECT_FALSE(cameras->mount_state(1).moving);
  EXPECT_EQ(cameras->mount_state(1).pan_rad, held);
  const auto during = frames(outbox, kOcuB, stopped, time.now());
  EXPECT_GE(during.size(), 9u);
  EXPECT_LE(during.size(), 11u);
  // The mounts stay refused until the emergency is cleared.
  pose(kOcuA, 1, 20, std::nullopt, std::nullopt, pose_field::kYAngular);
  time.advance(500ms);
  EXPECT_EQ(cameras->mount_state(1).pan_rad, held);
}

TEST_F(VisualSensorTest, CameraPoseAndSelectionAlsoStreamOnServiceConnections) {
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportCameraPose::code, 2, 0x0001}});
  deliver(kOcuB, msg::CreateServiceConnection{{msg::ReportSelectedCamera::code, 2, 0}});
  time.advance(1s);
  const auto poses = reports_to<msg::ReportCameraPose>(kOcuB);
  ASSERT_GE(poses.size(), 2u);
  EXPECT_EQ(poses[0].camera_name, "front");
  EXPECT_EQ(wire::presence_of(poses[0]), 0x0001u);
  EXPECT_GE(reports_to<msg::ReportSelectedCamera>(kOcuB).size(), 2u);
}

TEST_F(VisualSensorTest, ImagesFromADirectoryAreItsFilesInNameOrder) {
  const auto dir = std::filesystem::temp_directory_path() / ("jaus-visual-sensor-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::vector<std::vector<std::uint8_t>> files;
  for (int i = 0; i < 2; ++i) {
    files.push_back(*encode_png(test_pattern(48, 32, static_cast<std::uint64_t>(i))));
    std::ofstream out(dir / ("frame-" + std::to_string(i) + ".png"), std::ios::binary);
    out.write(reinterpret_cast<const char*>(files.back().data()), static_cast<std::streamsize>(files.back().size()));
  }
  VisualSensorConfig config = default_cameras();
  config.cameras[0].image_directory = dir.string();
  make(config);
  const auto first = query_image(kOcuB);
  time.advance(100ms);
  const auto second = query_image(kOcuB);
  time.advance(100ms);
  const auto third = query_image(kOcuB);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(first && second && third);
  EXPECT_EQ(first->data, files[0]);
  EXPECT_EQ(second->data, files[1]);
  EXPECT_EQ(third->data, files[0]);
  EXPECT_EQ(first->image_format, image_format::kPng);
  EXPECT_EQ(decode_png(second->data)->width, 48u);  // as the file is, not the camera's resolution
}

TEST_F(VisualSensorTest, AnUnreadableImageDirectoryIsLoggedOnceAndNothingIsSent) {
  VisualSensorConfig config = default_cameras();
  config.cameras[0].image_directory = "/nonexistent/jaus-images";
  make(config);
  EXPECT_FALSE(query_image(kOcuB));
  time.advance(100ms);  // (a failed capture is tried again a frame period later)
  EXPECT_FALSE(query_image(kOcuB));
  EXPECT_EQ(sensor->sensor_counters().capture_errors, 2u);
  int lines = 0;
  for (const auto& l : logs) lines += l.find("no image") != std::string::npos;
  EXPECT_EQ(lines, 1);
  EXPECT_EQ(sensor->state(), msg::PrimaryStatus::ready);  // the other camera still works
}

TEST_F(VisualSensorTest, AConfigurationWithoutUsableCamerasFailsInitialisation) {
  make(VisualSensorConfig{});
  EXPECT_EQ(sensor->state(), msg::PrimaryStatus::failure);
  VisualSensorConfig repeated = default_cameras();
  repeated.cameras[1].id = 1;
  make(repeated);
  EXPECT_EQ(sensor->state(), msg::PrimaryStatus::failure);
}

TEST_F(VisualSensorTest, ServicesListWhatItAcceptsAndProvides) {
  const auto entry = sensor->service_entry();
  EXPECT_EQ(entry.type, 37);
  std::map<std::uint16_t, std::uint32_t> inputs, outputs;
  for (const auto& i : entry.inputs) inputs[i.command_code] = i.presence_vector;
  for (const auto& o : entry.outputs) outputs[o.command_code] = o.presence_vector;
  for (std::uint16_t code : {0x0801, 0x0802, 0x0805, 0x0806, 0x2800, 0x2801, 0x2804, 0x2805, 0x2806, 0x2807})
    EXPECT_TRUE(inputs.contains(code)) << code;
  EXPECT_EQ(inputs.at(0x0801), pose_field::kYAngular | pose_field::kXAngular | pose_field::kZLinear);
  EXPECT_EQ(inputs.at(0x0805), 0x008Fu);
  EXPECT_EQ(inputs.at(0x0806), 0x02u);
  for (std::uint16_t code : {0x4800, 0x4801, 0x4804, 0x4805, 0x4806, 0x4807})
    EXPECT_TRUE(outputs.contains(code)) << code;
  EXPECT_EQ(outputs.at(0x4800), 0x03FFu);
}

// ---- images off the event loop, limited per requester (issue 28) ----------------

TEST_F(VisualSensorTest, ConnectionsOfOneFormatShareOneCapturePerFramePeriod) {
  ScheduledFrameWorker& w = use_worker();
  // Eight streams at the camera's 10 fps from eight nodes, half of them 37 ms
  // out of phase with the others, and queries besides.
  std::vector<Address> requesters;
  for (std::uint8_t n = 10; n < 18; ++n) requesters.push_back(Address{1, n, 40, 1});
  for (std::size_t i = 0; i < requesters.size(); ++i) {
    if (i == 4) time.advance(37ms);
    deliver(requesters[i], msg::CreateServiceConnection{{msg::ReportImage::code, 10, 0}});
  }
  const auto start = time.now();
  for (int i = 0; i < 20; ++i) {
    deliver(kOcuC, msg::QueryImage{});
    time.advance(100ms);
  }
  // One capture per frame period over the 2 s (and the first), whatever the
  // number of connections and queries.
  EXPECT_GE(w.ran(), 20u);
  EXPECT_LE(w.ran(), 22u);
  EXPECT_EQ(sensor->sensor_counters().frames_captured, w.ran());
  for (const Address& r : requesters) {
    const auto sent = frames(outbox, r, start, time.now());
    EXPECT_GE(sent.size(), 19u) << r.to_string();
    EXPECT_LE(sent.size(), 21u) << r.to_string();
  }
  EXPECT_EQ(reports_to<msg::ReportImage>(kOcuC).size(), 20u);
  // Every stream's frames are the same encoded bytes at the same moment: shared.
  const auto a = frames(outbox, requesters[0], start, start + 500ms);
  const auto b = frames(outbox, requesters[1], start, start + 500ms);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].payload, b[i].payload);
}

TEST_F(VisualSensorTest, ASlowCaptureNeverDelaysOtherMessagesAndItsQueryIsAnsweredWhenItIsDone) {
  use_worker(4, 3s);  // a camera that takes 3 s per frame
  outbox.clear();
  deliver(kOcuB, msg::QueryImage{});
  EXPECT_TRUE(reports_to<msg::ReportImage>(kOcuB).empty());  // nothing waited on the loop
  deliver(kOcuC, msg::QueryComponentStatus{});
  EXPECT_EQ(reports_to<msg::ReportComponentStatus>(kOcuC).size(), 1u);  // answered meanwhile
  deliver(kOcuA, msg::RequestComponentControl{{5}});
  EXPECT_TRUE(sensor->control().is_controller(kOcuA));
  deliver(kOcuC, msg::CreateServiceConnection{{msg::ReportImage::code, 10, 0}});
  time.advance(2900ms);
  EXPECT_TRUE(reports_to<msg::ReportImage>(kOcuB).empty());
  EXPECT_TRUE(reports_to<msg::ReportImage>(kOcuC).empty());  // no frame yet: the stream's periods send nothing
  time.advance(100ms);
  ASSERT_EQ(reports_to<msg::ReportImage>(kOcuB).size(), 1u);
  EXPECT_TRUE(decode_png(reports_to<msg::ReportImage>(kOcuB)[0].data));
  time.advance(100ms);
  EXPECT_EQ(reports_to<msg::ReportImage>(kOcuC).size(), 1u);  // the newest frame, from then on
}

TEST_F(VisualSensorTest, AFullWorkerRefusesWithoutGrowingAndTheNewestFrameServesMeanwhile) {
  rt::VirtualTime t;
  ScheduledFrameWorker bounded(t, t, 2);
  int done = 0;
  const auto job = [] { return Expected<Image>(Image{}); };
  const auto count = [&](Expected<Image>) { ++done; };
  EXPECT_TRUE(bounded.submit(job, count));
  EXPECT_TRUE(bounded.submit(job, count));
  EXPECT_FALSE(bounded.submit(job, count));
  EXPECT_EQ(bounded.pending(), 2u);
  EXPECT_EQ(bounded.refused(), 1u);
  t.run_ready();
  EXPECT_EQ(done, 2);
  EXPECT_EQ(bounded.pending(), 0u);

  // The sensor: a capture of camera 1 under way fills a worker of one; the
  // controller selects camera 2, whose capture is refused and counted.
  ScheduledFrameWorker& w = use_worker(1, 1s);
  take_control(kOcuA);
  deliver(kOcuB, msg::QueryImage{});
  deliver(kOcuA, msg::SelectCamera{{2}});
  deliver(kOcuC, msg::QueryImage{});
  EXPECT_EQ(w.pending(), 1u);
  EXPECT_EQ(w.refused(), 1u);
  EXPECT_EQ(sensor->sensor_counters().captures_refused, 1u);
  time.advance(1s);  // camera 1's frame is dropped: camera 2 is selected now
  EXPECT_TRUE(reports_to<msg::ReportImage>(kOcuB).empty());
  time.advance(100ms);
  outbox.clear();
  deliver(kOcuC, msg::QueryImage{});
  time.advance(1s);
  const auto images = reports_to<msg::ReportImage>(kOcuC);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0].camera_id, 2);
}

TEST_F(VisualSensorTest, QueryImageBeyondTheFrameRatePerRequesterIsIgnoredAndCounted) {
  use_worker();
  // 100 queries a second for 2 s from one node (two of its components): at
  // most the camera's 10 fps (and a burst of 2) are answered.
  const Address other_component{kOcuB.subsystem, kOcuB.node, 41, 1};
  outbox.clear();
  for (int i = 0; i < 200; ++i) {
    deliver(i % 2 ? kOcuB : other_component, msg::QueryImage{});
    if (i % 10 == 0) deliver(kOcuC, msg::QueryImage{});  // another node at 10 Hz: untouched
    time.advance(10ms);
  }
  const std::size_t answered = reports_to<msg::ReportImage>(kOcuB).size() + reports_to<msg::ReportImage>(other_component).size();
  EXPECT_GE(answered, 19u);
  EXPECT_LE(answered, 22u);
  EXPECT_EQ(sensor->sensor_counters().image_queries_limited, 200u - answered);
  EXPECT_EQ(reports_to<msg::ReportImage>(kOcuC).size(), 20u);
  int lines = 0;
  for (const auto& l : logs) lines += l.find("beyond the camera's frame rate") != std::string::npos;
  EXPECT_LE(lines, 2);  // limited: a line, then a count
}

TEST_F(VisualSensorTest, ARequestingNodesThirdImageConnectionIsRefused) {
  // Three components of one node ask for image streams: two are confirmed
  // (the default), the third refused; another node still gets its own.
  const auto response = [&](const Address& from) {
    outbox.clear();
    deliver(from, msg::CreateServiceConnection{{msg::ReportImage::code, 10, 0}});
    const auto confirms = reports_to<msg::ConfirmServiceConnection>(from);
    return confirms.size() == 1 ? confirms[0].response_code : 255;
  };
  const Address first{kOcuB.subsystem, kOcuB.node, 40, 1}, second{kOcuB.subsystem, kOcuB.node, 41, 1},
      third{kOcuB.subsystem, kOcuB.node, 42, 1};
  EXPECT_EQ(response(first), msg::sc_response::kCreated);
  EXPECT_EQ(response(second), msg::sc_response::kCreated);
  EXPECT_EQ(response(third), msg::sc_response::kRefused);
  EXPECT_EQ(response(first), msg::sc_response::kCreated);  // a Create again updates its own
  EXPECT_EQ(response(kOcuC), msg::sc_response::kCreated);
  // Other reports are not capped by it.
  outbox.clear();
  deliver(third, msg::CreateServiceConnection{{msg::ReportCameraPose::code, 1, 0x0001}});
  EXPECT_EQ(reports_to<msg::ConfirmServiceConnection>(third).at(0).response_code, msg::sc_response::kCreated);
  // Once one ends, the third may have its stream.
  deliver(second, msg::TerminateServiceConnection{{msg::ReportImage::code, 0}});
  EXPECT_EQ(response(third), msg::sc_response::kCreated);

  // The option: one per node.
  VisualSensorOptions one;
  one.image_connections_per_requester = 1;
  rt::ComponentConfig component;
  component.address = kVisualSensor;
  sensor = std::make_unique<VisualSensor>(component, rt::Environment{time, time, outbox}, *cameras, one);
  sensor->start();
  EXPECT_EQ(response(first), msg::sc_response::kCreated);
  EXPECT_EQ(response(second), msg::sc_response::kRefused);
}

}  // namespace
}  // namespace jaus::test
