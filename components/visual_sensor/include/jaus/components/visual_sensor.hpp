// The visual sensor (component 37, RA 3.x Part 3 environment sensor
// subgroup): the configured cameras (camera.hpp), one of them selected.
//   - The controller, in Ready only, selects the camera (Select Camera), points
//     a camera's mount (Set Camera Pose: pan, tilt, zoom; the axis mapping is
//     in camera_reports.hpp), and chooses its resolution, frame rate and field
//     of view (Set Camera Capabilities, clamped to the camera's ranges; the FOV
//     through the zoom; focus, iris, gain, shutter and the control bits are
//     not acted on) and its image format (Set Camera Format Options: one of
//     the camera's formats and no audio, else refused whole). A command for a
//     camera that does not exist is refused (logged, counted), and changes nothing.
//   - Anyone may ask the camera count, the selected camera, and a camera's
//     pose, capabilities and formats (a query for a camera that does not exist
//     is logged and counted and gets no reply: Part 3 has no "no such camera",
//     and a report would have to invent one).
//   - Images (Query Image, and Report Image on service connections) are the
//     selected camera's, in Ready only (Standby pauses a stream, Resume
//     restarts it). A stream runs at the rate asked for, at most the camera's
//     frame rate when it was created. Report Image is the camera ID, the
//     format code (7 JPEG, 11 PNG) and the whole file (the common RA 3.3
//     peer's layout); a frame over one packet goes as a large data set (the
//     node splits it).
//
// Images never on the event loop (issue 28): frames are captured, encoded and
// read from a directory by a FrameWorker (frame_worker.hpp; the host's runs on
// a thread of its own), from a job that holds copies (Cameras::capture_job).
// The sensor keeps the newest finished frame of the selected camera at its
// format and size, and every stream period and Query Image is served from it:
// one capture per frame period, however many connections share it. A frame is
// asked for when the newest is older than the frame period, and, while
// someone asked for images in the last 2 s, again one frame period after the
// last capture began (so a stream slower than the frame rate still gets a
// recent frame). Nothing waits: a period without a fresh frame sends the
// newest there is (nothing before the first), and a Query Image without one
// is answered when the next frame is done. A frame whose settings changed
// meanwhile is dropped.
//
// Per requesting node (subsystem and node: its components together), so that
// one peer cannot fill the loop with image traffic: Query Image at most at the
// selected camera's frame rate (a burst of 2; beyond, ignored, counted and
// logged limited), and at most `image_connections_per_requester` Report Image
// service connections (beyond, Create Service Connection is refused, response 4).
//
// Safety: every mount holds where it is (rate motion stops) in
// command_stop(), which the component base calls on Standby, Emergency,
// Failure, Reset, Shutdown, control release or takeover, controller silence
// and a command service connection's deadman (rt::Component::enforce_stop).
// Nothing resumes a motion: the mounts stay until the controller sends a new
// Set Camera Pose.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "jaus/components/camera.hpp"
#include "jaus/components/camera_reports.hpp"
#include "jaus/components/frame_worker.hpp"
#include "jaus/components/jpeg_quality.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::components {

struct VisualSensorOptions {
  // Report Image service connections one requesting node may hold at once.
  std::size_t image_connections_per_requester = 2;
};

struct VisualSensorCounters {
  std::uint64_t cameras_selected = 0;
  std::uint64_t poses_set = 0;
  std::uint64_t capabilities_set = 0;
  std::uint64_t formats_set = 0;
  std::uint64_t refused_unknown_camera = 0;  // commands and queries naming no configured camera
  std::uint64_t refused_formats = 0;         // Set Camera Format Options with a format the camera lacks
  std::uint64_t images_sent = 0;             // replies to Query Image and service connection frames
  std::uint64_t capture_errors = 0;
  std::uint64_t frames_captured = 0;         // captures finished (each shared by every sender of it)
  std::uint64_t captures_refused = 0;        // the worker was full: the newest frame served instead
  std::uint64_t image_queries_limited = 0;   // Query Image beyond its requester's rate, ignored
  std::uint64_t image_queries_paused = 0;    // Query Image outside Ready and Emergency, ignored
  int jpeg_quality = kDefaultJpegQuality;    // of the next JPEG frame (lower on a slow link: jpeg_quality.hpp)
};

class VisualSensor final : public rt::Component {
 public:
  VisualSensor(rt::ComponentConfig config, rt::Environment env, Cameras& cameras, VisualSensorOptions options = {});
  ~VisualSensor() override;

  // Frames are captured by `worker` (by default, one of the sensor's own on
  // the scheduler), from `images` when given (the cameras whose images these
  // are, when `cameras` only moves their mounts: a platform's). Both outlive
  // the sensor, or the worker is stopped before the sensor goes. Before start().
  void use_frame_worker(FrameWorker& worker, Cameras* images = nullptr);

  const VisualSensorOptions& options() const { return options_; }
  const VisualSensorCounters& sensor_counters() const { return sensor_counters_; }
  std::uint8_t selected_camera() const { return selected_; }
  // What a camera is used with now, or nullptr for an unknown ID.
  const CameraSettings* settings(std::uint8_t camera_id) const;

  // The reports, with every field this sensor has (queries mask them with
  // the requested presence vector); nullopt for an unknown camera.
  std::optional<msg::ReportCameraPose> camera_pose_report(std::uint8_t camera_id);
  std::optional<msg::ReportCameraCapabilities> capabilities_report(std::uint8_t camera_id) const;
  std::optional<msg::ReportCameraFormatOptions> format_report(std::uint8_t camera_id) const;

 protected:
  bool initialize() override;
  void command_stop(std::string_view why) override;

 private:
  struct Camera {
    const CameraConfig* config;
    CameraSettings settings;
  };

  Camera* find(std::uint8_t camera_id);
  const Camera* find(std::uint8_t camera_id) const;
  Camera* commanded_camera(const Header& h, std::uint8_t camera_id, std::string_view what);
  bool queried_camera_exists(const Header& h, std::uint8_t camera_id, std::string_view what);
  void provide_images();

  // The image pipeline (see the header comment).
  struct FrameKey {
    std::uint8_t camera = 0;
    std::uint8_t format = 0;
    std::uint16_t width = 0;
    std::uint16_t height = 0;
    bool operator==(const FrameKey&) const = default;
  };
  std::optional<FrameKey> selected_key() const;
  rt::Duration frame_period() const;
  // Someone wants the selected camera's frame now: asks for a capture if due;
  // returns the newest frame (nullptr: none yet).
  std::shared_ptr<const msg::ReportImage> want_frame();
  bool frame_fresh();
  void request_capture();
  void capture_done(const FrameKey& key, std::uint64_t id, Expected<Image> image);
  void on_query_image(const Header& h);
  bool query_allowed(const Address& requester);

  void on_select_camera(const Header& h, const msg::SelectCamera& m);
  void on_set_camera_pose(const Header& h, const msg::SetCameraPose& m);
  void on_set_capabilities(const Header& h, const msg::SetCameraCapabilities& m);
  void on_set_format(const Header& h, const msg::SetCameraFormatOptions& m);

  Cameras& cameras_;
  VisualSensorOptions options_;
  VisualSensorCounters sensor_counters_;
  std::vector<Camera> cameras_in_use_;
  std::uint8_t selected_ = 0;
  std::optional<std::string> capture_error_;  // the last one logged, until a capture succeeds

  std::unique_ptr<ScheduledFrameWorker> own_worker_;
  FrameWorker* worker_ = nullptr;
  Cameras* images_ = nullptr;
  // The newest frame of `key` (when the selected camera's settings are `key`)
  // and the capture under way; a done whose key is no longer this one is dropped.
  FrameKey key_;
  std::shared_ptr<const msg::ReportImage> frame_;
  rt::TimePoint frame_at_{};     // when its capture began
  bool capturing_ = false;
  std::uint64_t capture_id_ = 0;  // the capture under way, or the last one
  bool captured_before_ = false;
  rt::TimePoint capture_began_{};  // the last capture (finished or not, failed or not)
  rt::TimePoint wanted_at_{};      // the last time someone asked for a frame
  rt::TimerId next_capture_ = rt::kNoTimer;
  std::vector<Address> waiting_;  // Query Image senders waiting for the capture under way
  struct QueryBucket {
    double tokens = 0;
    rt::TimePoint at{};
  };
  std::map<std::pair<std::uint8_t, std::uint8_t>, QueryBucket> query_buckets_;  // by (subsystem, node)
  // Checked by capture callbacks: the worker may call back after the sensor is gone.
  std::shared_ptr<char> alive_ = std::make_shared<char>(0);
};

}  // namespace jaus::components
