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
//     selected camera's, captured when sent, never queued, in Ready only
//     (Standby pauses a stream, Resume restarts it). A stream runs at the rate
//     asked for, at most the camera's frame rate when it was created. Report
//     Image is the camera ID, the format code (7 JPEG, 11 PNG) and the whole
//     file (the common RA 3.3 peer's layout); a frame over one packet goes as
//     a large data set (the node splits it).
//
// Safety: every mount holds where it is (rate motion stops) in
// command_stop(), which the component base calls on Standby, Emergency,
// Failure, Reset, Shutdown, control release or takeover, controller silence
// and a command service connection's deadman (rt::Component::enforce_stop).
// Nothing resumes a motion: the mounts stay until the controller sends a new
// Set Camera Pose.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "jaus/components/camera.hpp"
#include "jaus/components/camera_reports.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::components {

// Nothing to choose yet; here so that the host passes options as for every component.
struct VisualSensorOptions {};

struct VisualSensorCounters {
  std::uint64_t cameras_selected = 0;
  std::uint64_t poses_set = 0;
  std::uint64_t capabilities_set = 0;
  std::uint64_t formats_set = 0;
  std::uint64_t refused_unknown_camera = 0;  // commands and queries naming no configured camera
  std::uint64_t refused_formats = 0;         // Set Camera Format Options with a format the camera lacks
  std::uint64_t images_sent = 0;             // replies to Query Image and service connection frames
  std::uint64_t capture_errors = 0;
};

class VisualSensor final : public rt::Component {
 public:
  VisualSensor(rt::ComponentConfig config, rt::Environment env, Cameras& cameras, VisualSensorOptions options = {});
  ~VisualSensor() override;

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
  // The selected camera's frame now; nullopt (logged, counted) when it cannot be captured.
  std::optional<msg::ReportImage> image_report();

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
};

}  // namespace jaus::components
