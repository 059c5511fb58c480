#include "jaus/components/visual_sensor.hpp"

#include <algorithm>
#include <set>

#include "jaus/wire/describe.hpp"

namespace jaus::components {

using namespace rt;

namespace {

// Every field of Report Camera Pose (name, origin, direction cosines).
constexpr std::uint32_t kPoseReportFields = 0x03FF;
// Report Camera Capabilities: description, FOVs, resolutions, frame rates
// (bits 0-10), imagery and audio control (13, 14); no shutter.
constexpr std::uint32_t kCapabilitiesReportFields = 0x67FF;
// Report Camera Format Options: up to four image formats (bits 2-5), no audio.
constexpr std::uint32_t kFormatReportFields = 0x3C;
// Set Camera Capabilities fields acted on: the FOVs (bits 0, 1, through the
// zoom), the resolution (2, 3), the frame rate (7).
constexpr std::uint32_t kFovFields = 0x0003;
constexpr std::uint32_t kCapabilitiesCommandFields = 0x008C;
// Set Camera Format Options: the image format (bit 1).
constexpr std::uint32_t kFormatCommandFields = 0x02;

std::string id_text(std::uint8_t id) { return std::to_string(id); }

}  // namespace

VisualSensor::VisualSensor(ComponentConfig config, Environment env, Cameras& cameras, VisualSensorOptions options)
    : Component(std::move(config), std::move(env)), cameras_(cameras), options_(options) {
  using namespace msg;
  std::set<std::uint8_t> ids;
  for (const CameraConfig& c : cameras_.configs())
    if (c.id != 0 && ids.insert(c.id).second) cameras_in_use_.push_back(Camera{&c, initial_settings(c)});
  if (!cameras_in_use_.empty()) selected_ = cameras_in_use_.front().config->id;

  // Commands: the controller's, in Ready only (the base refuses the rest and counts them).
  handle<SelectCamera>(Access::controller, /*ready_only=*/true,
                       [this](const Header& h, const SelectCamera& m) { on_select_camera(h, m); });
  handle<SetCameraPose>(Access::controller, /*ready_only=*/true,
                        [this](const Header& h, const SetCameraPose& m) { on_set_camera_pose(h, m); });
  handle<SetCameraCapabilities>(Access::controller, /*ready_only=*/true,
                                [this](const Header& h, const SetCameraCapabilities& m) { on_set_capabilities(h, m); });
  handle<SetCameraFormatOptions>(Access::controller, /*ready_only=*/true,
                                 [this](const Header& h, const SetCameraFormatOptions& m) { on_set_format(h, m); });

  // Queries: anyone, in any state; images in Ready only.
  handle<QueryCameraCount>(Access::anyone, false, [this](const Header& h, const QueryCameraCount&) {
    send(h.source, ReportCameraCount{{static_cast<std::uint8_t>(cameras_in_use_.size())}});
  });
  handle<QuerySelectedCamera>(Access::anyone, false, [this](const Header& h, const QuerySelectedCamera&) {
    send(h.source, ReportSelectedCamera{{selected_}});
  });
  handle<QueryCameraPose>(Access::anyone, false, [this](const Header& h, const QueryCameraPose& q) {
    if (!queried_camera_exists(h, q.camera_id, QueryCameraPose::name)) return;
    auto report = *camera_pose_report(q.camera_id);
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryCameraCapabilities>(Access::anyone, false, [this](const Header& h, const QueryCameraCapabilities& q) {
    if (!queried_camera_exists(h, q.camera_id, QueryCameraCapabilities::name)) return;
    auto report = *capabilities_report(q.camera_id);
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryCameraFormatOptions>(Access::anyone, false,
                                   [this](const Header& h, const QueryCameraFormatOptions& q) {
                                     if (!queried_camera_exists(h, q.camera_id, QueryCameraFormatOptions::name)) return;
                                     auto report = *format_report(q.camera_id);
                                     wire::mask_presence(report, q.presence_vector);
                                     send(h.source, report);
                                   });
  handle<QueryImage>(Access::anyone, /*ready_only=*/true, [this](const Header& h, const QueryImage&) {
    if (auto report = image_report()) {
      ++sensor_counters_.images_sent;
      send(h.source, *report);
    }
  });

  // The same reports on service connections, for the selected camera.
  provide<ReportCameraCount>(0, [this] {
    return ReportCameraCount{{static_cast<std::uint8_t>(cameras_in_use_.size())}};
  });
  provide<ReportSelectedCamera>(0, [this] { return ReportSelectedCamera{{selected_}}; });
  provide_if<ReportCameraPose>(kPoseReportFields, [this] { return camera_pose_report(selected_); });
  provide_if<ReportCameraCapabilities>(kCapabilitiesReportFields, [this] { return capabilities_report(selected_); });
  provide_if<ReportCameraFormatOptions>(kFormatReportFields, [this] { return format_report(selected_); });
  provide_images();

  // Report Services: the fields each command acts on and each query can get.
  std::uint32_t pose_fields = 0, fov_fields = 0;
  for (const Camera& c : cameras_in_use_) {
    if (c.config->pan.movable()) pose_fields |= pose_field::kYAngular;
    if (c.config->tilt.movable()) pose_fields |= pose_field::kXAngular;
    if (c.config->zoom.movable()) pose_fields |= pose_field::kZLinear;
    if (zoom_for_fov(*c.config, c.config->widest_horizontal_fov_rad)) fov_fields = kFovFields;
  }
  declare_input_presence(SetCameraPose::code, pose_fields);
  declare_input_presence(SetCameraCapabilities::code, kCapabilitiesCommandFields | fov_fields);
  declare_input_presence(SetCameraFormatOptions::code, kFormatCommandFields);
  declare_input_presence(QueryCameraPose::code, kPoseReportFields);
  declare_input_presence(QueryCameraCapabilities::code, kCapabilitiesReportFields);
  declare_input_presence(QueryCameraFormatOptions::code, kFormatReportFields);
}

VisualSensor::~VisualSensor() = default;

// A configuration without a usable camera (none, or IDs 0 or repeated) is a
// failed initialisation: the operator sees Failure, not a sensor with no eyes.
bool VisualSensor::initialize() {
  const auto& configs = cameras_.configs();
  if (cameras_in_use_.empty()) {
    // A controller's Reset runs this again: limited like the rest of what a Reset repeats.
    log_repeated({"camera configurations refused", kNoteworthyBurst}, LogLevel::error,
                 [] { return std::string("no camera configured (IDs 1..255)"); });
    return false;
  }
  if (cameras_in_use_.size() != configs.size()) {
    log_repeated({"camera configurations refused", kNoteworthyBurst}, LogLevel::error,
                 [] { return std::string("camera IDs must be 1..255 and unique"); });
    return false;
  }
  return true;
}

VisualSensor::Camera* VisualSensor::find(std::uint8_t camera_id) {
  for (Camera& c : cameras_in_use_)
    if (c.config->id == camera_id) return &c;
  return nullptr;
}

const VisualSensor::Camera* VisualSensor::find(std::uint8_t camera_id) const {
  return const_cast<VisualSensor*>(this)->find(camera_id);
}

const CameraSettings* VisualSensor::settings(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  return c ? &c->settings : nullptr;
}

VisualSensor::Camera* VisualSensor::commanded_camera(const Header& h, std::uint8_t camera_id, std::string_view what) {
  Camera* c = find(camera_id);
  if (!c) {
    ++sensor_counters_.refused_unknown_camera;
    log_repeated("camera commands for no camera refused", LogLevel::warn, [&] {
      return std::string(what) + " from " + h.source.to_string() + " refused: no camera " + id_text(camera_id);
    });
  }
  return c;
}

bool VisualSensor::queried_camera_exists(const Header& h, std::uint8_t camera_id, std::string_view what) {
  if (find(camera_id)) return true;
  ++sensor_counters_.refused_unknown_camera;
  log_repeated("camera queries for no camera not answered", LogLevel::warn, [&] {
    return std::string(what) + " from " + h.source.to_string() + " for camera " + id_text(camera_id) +
           ", which does not exist: no reply";
  });
  return false;
}

// The image stream's source rate is the selected camera's frame rate; a
// connection keeps the rate it was confirmed with.
void VisualSensor::provide_images() {
  const Camera* c = find(selected_);
  provide_if<msg::ReportImage>(
      0,
      [this]() -> std::optional<msg::ReportImage> {
        if (state() != PrimaryStatus::ready) return std::nullopt;  // Standby pauses the stream
        auto report = image_report();
        if (report) ++sensor_counters_.images_sent;
        return report;
      },
      c ? c->settings.frame_rate_fps : 0);
}

std::optional<msg::ReportCameraPose> VisualSensor::camera_pose_report(std::uint8_t camera_id) {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraPose report;
  static_cast<msg::CameraPoseReportBody&>(report) = to_camera_pose_body(*c->config, cameras_.mount_state(camera_id));
  return report;
}

std::optional<msg::ReportCameraCapabilities> VisualSensor::capabilities_report(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraCapabilities report;
  static_cast<msg::CameraCapabilitiesReportBody&>(report) = to_capabilities_body(*c->config, c->settings);
  return report;
}

std::optional<msg::ReportCameraFormatOptions> VisualSensor::format_report(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraFormatOptions report;
  static_cast<msg::CameraFormatReportBody&>(report) = to_format_body(*c->config, c->settings);
  return report;
}

std::optional<msg::ReportImage> VisualSensor::image_report() {
  const Camera* c = find(selected_);
  if (!c) return std::nullopt;
  const CameraSettings& s = c->settings;
  auto image = cameras_.capture(selected_, ImageRequest{s.image_format, s.width, s.height, s.frame_rate_fps});
  std::optional<std::string> error;
  if (!image)
    error = image.error().message();
  else if (image->data.size() + 2 > kMaxLargeDataSetSize)
    error = std::to_string(image->data.size()) + " bytes, over a large data set's 1 MiB";
  if (error) {
    ++sensor_counters_.capture_errors;
    // Logged once per distinct error, not at the stream's rate.
    // Once per distinct error, and (a controller selecting cameras in turn repeats it) limited.
    if (capture_error_ != error)
      log_repeated({"cameras without images", kNoteworthyBurst}, LogLevel::warn,
                   [&] { return "camera " + id_text(selected_) + ": no image: " + *error; });
    capture_error_ = error;
    return std::nullopt;
  }
  if (capture_error_)
    log_repeated({"cameras with images again", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "camera " + id_text(selected_) + ": images again"; });
  capture_error_.reset();
  msg::ReportImage report;
  report.camera_id = selected_;
  report.image_format = image->format;
  report.data = std::move(image->data);
  return report;
}

void VisualSensor::on_select_camera(const Header& h, const msg::SelectCamera& m) {
  if (!commanded_camera(h, m.camera_id, msg::SelectCamera::name)) return;
  if (selected_ != m.camera_id) capture_error_.reset();
  selected_ = m.camera_id;
  ++sensor_counters_.cameras_selected;
  provide_images();
  log_repeated({"cameras selected", kNoteworthyBurst}, LogLevel::info,
               [&] { return "camera " + id_text(selected_) + " selected by " + h.source.to_string(); });
}

void VisualSensor::on_set_camera_pose(const Header& h, const msg::SetCameraPose& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraPose::name);
  if (!c) return;
  const PoseCommand pose = to_mount_command(m, *c->config);
  if (pose.ignored)
    log_repeated("Set Camera Pose bits without an axis ignored", LogLevel::debug, [&] {
      return "Set Camera Pose from " + h.source.to_string() + ": camera " + id_text(m.camera_id) +
             " has no axis for presence bits 0x" + wire::detail::hex_u32(pose.ignored);
    });
  if (pose.command == MountCommand{}) return;
  cameras_.command_mount(m.camera_id, pose.command);
  ++sensor_counters_.poses_set;
}

void VisualSensor::on_set_capabilities(const Header& h, const msg::SetCameraCapabilities& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraCapabilities::name);
  if (!c) return;
  const CameraSettings before = c->settings;
  c->settings = apply_capabilities(m, *c->config, c->settings);
  // The field of view is the zoom's: the horizontal one if given, else the
  // vertical one at the (new) aspect ratio.
  std::optional<double> fov = m.horizontal_fov_rad;
  if (!fov && m.vertical_fov_rad)
    fov = horizontal_from_vertical_fov_rad(*m.vertical_fov_rad, c->settings.width, c->settings.height);
  if (fov) {
    if (const auto zoom = zoom_for_fov(*c->config, *fov)) {
      MountCommand command;
      command.zoom = AxisCommand{AxisMode::position, std::clamp(*zoom, c->config->zoom.min, c->config->zoom.max)};
      cameras_.command_mount(m.camera_id, command);
    } else {
      log_repeated("Set Camera Capabilities of a fixed field of view ignored", LogLevel::debug, [&] {
        return "Set Camera Capabilities: camera " + id_text(m.camera_id) + " cannot change its FOV";
      });
    }
  }
  ++sensor_counters_.capabilities_set;
  if (c->settings.frame_rate_fps != before.frame_rate_fps && m.camera_id == selected_) provide_images();
  log_repeated({"cameras set", kNoteworthyBurst}, LogLevel::info, [&] {
    return "camera " + id_text(m.camera_id) + " set by " + h.source.to_string() + ": " +
           std::to_string(c->settings.width) + "x" + std::to_string(c->settings.height) + " at " +
           std::to_string(c->settings.frame_rate_fps) + " fps";
  });
}

void VisualSensor::on_set_format(const Header& h, const msg::SetCameraFormatOptions& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraFormatOptions::name);
  if (!c) return;
  const auto& formats = c->config->image_formats;
  std::string refusal;
  if (m.audio_format && *m.audio_format != 0)
    refusal = "audio format " + std::to_string(*m.audio_format) + " (this camera has no audio)";
  else if (m.image_format && std::find(formats.begin(), formats.end(), *m.image_format) == formats.end())
    refusal = "image format " + std::to_string(*m.image_format);
  if (!refusal.empty()) {
    ++sensor_counters_.refused_formats;
    log_repeated("Set Camera Format Options refused", LogLevel::warn, [&] {
      return "Set Camera Format Options from " + h.source.to_string() + " refused: camera " + id_text(m.camera_id) +
             " has no " + refusal;
    });
    return;
  }
  if (!m.image_format) return;  // the format option is reserved: nothing else to do
  c->settings.image_format = *m.image_format;
  ++sensor_counters_.formats_set;
  log_repeated({"image formats set", kNoteworthyBurst}, LogLevel::info, [&] {
    return "camera " + id_text(m.camera_id) + " sends image format " + std::to_string(*m.image_format);
  });
}

// Safety: the one place the mounts are told to hold (see the header).
void VisualSensor::command_stop(std::string_view why) {
  for (const Camera& c : cameras_in_use_) cameras_.hold(c.config->id);
  // Every Standby, Emergency, release or takeover holds the mounts: limited (the hold itself is not).
  log_repeated({"camera mounts held", kNoteworthyBurst}, LogLevel::info,
               [&] { return "camera mounts held: " + std::string(why); });
}

}  // namespace jaus::components
