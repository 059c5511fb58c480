// Part 3's environment sensor bodies <-> the cameras' terms (see the header
// for the axis mapping and the frames). Values are clamped to what each field
// can encode, so a report never fails to encode because of a configuration.
#include "jaus/components/camera_reports.hpp"

#include <algorithm>
#include <cmath>

namespace jaus::components {

namespace {

// std::clamp without its precondition: a range given the wrong way round
// (a bad configuration) gives `high`, never undefined behaviour.
template <class T>
T within(T value, T low, T high) {
  return std::min(std::max(value, low), high);
}

double cosine(double v) { return within(v, -1.0, 1.0); }
double origin(double v) { return std::isfinite(v) ? within(v, -32.767, 32.767) : 0.0; }
double fov(double v) { return std::isfinite(v) ? within(v, 0.0, msg::kPi) : 0.0; }

std::optional<AxisCommand> axis_command(const std::optional<double>& percent, bool rate, const MountAxis& axis) {
  if (!percent || !std::isfinite(*percent)) return std::nullopt;
  if (rate) return AxisCommand{AxisMode::rate, percent_to_rate(*percent, axis)};
  return AxisCommand{AxisMode::position, percent_to_position(*percent, axis)};
}

// The zoom range the lens can reach (percent).
void zoom_range(const CameraConfig& camera, double& low, double& high) {
  low = high = 0;
  if (!camera.zoom.movable()) return;
  low = within(camera.zoom.min, 0.0, 100.0);
  high = within(camera.zoom.max, 0.0, 100.0);
}

}  // namespace

CameraSettings initial_settings(const CameraConfig& c) {
  CameraSettings s;
  s.width = within(c.width, c.min_width, c.max_width);
  s.height = within(c.height, c.min_height, c.max_height);
  s.frame_rate_fps = within(c.frame_rate_fps, c.min_frame_rate_fps, c.max_frame_rate_fps);
  if (s.frame_rate_fps == 0) s.frame_rate_fps = 1;
  s.image_format = c.image_formats.empty() ? image_format::kPng : c.image_formats.front();
  return s;
}

double percent_to_position(double percent, const MountAxis& axis) {
  const double full_scale = std::max(std::abs(axis.min), std::abs(axis.max));
  return within(within(percent, -100.0, 100.0) / 100 * full_scale, axis.min, axis.max);
}

double percent_to_rate(double percent, const MountAxis& axis) {
  return within(percent, -100.0, 100.0) / 100 * std::max(axis.max_rate, 0.0);
}

PoseCommand to_mount_command(const msg::CameraPoseCommandBody& b, const CameraConfig& camera) {
  namespace f = pose_field;
  PoseCommand out;
  const std::uint8_t mode = b.mode_indicator;
  const auto take = [&](const std::optional<double>& percent, std::uint8_t bit, const MountAxis& axis,
                        std::optional<AxisCommand>& into) {
    if (!percent) return;
    if (!axis.movable()) {
      out.ignored |= bit;
      return;
    }
    into = axis_command(percent, (mode & bit) != 0, axis);
  };
  take(b.y_angular_percent, f::kYAngular, camera.pan, out.command.pan);
  take(b.x_angular_percent, f::kXAngular, camera.tilt, out.command.tilt);
  take(b.z_linear_percent, f::kZLinear, camera.zoom, out.command.zoom);
  if (b.x_linear_percent) out.ignored |= f::kXLinear;
  if (b.y_linear_percent) out.ignored |= f::kYLinear;
  if (b.z_angular_percent) out.ignored |= f::kZAngular;
  return out;
}

CameraAxes camera_axes_in_vehicle(double yaw, double pitch) {
  CameraAxes a;
  a.z = {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), -std::sin(pitch)};
  a.x = {-std::sin(yaw), std::cos(yaw), 0};
  return a;
}

msg::CameraPoseReportBody to_camera_pose_body(const CameraConfig& c, const MountState& m) {
  msg::CameraPoseReportBody b;
  b.camera_id = c.id;
  b.camera_name = c.name.substr(0, 15);  // the field holds 15 characters
  b.x_origin_m = origin(c.x_m);
  b.y_origin_m = origin(c.y_m);
  b.z_origin_m = origin(c.z_m);
  const CameraAxes axes = camera_axes_in_vehicle(c.home_yaw_rad + m.pan_rad, c.home_pitch_rad + m.tilt_rad);
  if (std::isfinite(axes.x.x + axes.x.y + axes.z.x + axes.z.y + axes.z.z)) {
    b.x_axis_direction_cosine_x = cosine(axes.x.x);
    b.x_axis_direction_cosine_y = cosine(axes.x.y);
    b.x_axis_direction_cosine_z = cosine(axes.x.z);
    b.z_axis_direction_cosine_x = cosine(axes.z.x);
    b.z_axis_direction_cosine_y = cosine(axes.z.y);
    b.z_axis_direction_cosine_z = cosine(axes.z.z);
  }
  return b;
}

double horizontal_fov_rad(const CameraConfig& c, double zoom_percent) {
  const double t = within(zoom_percent, 0.0, 100.0) / 100;
  return c.widest_horizontal_fov_rad + (c.narrowest_horizontal_fov_rad - c.widest_horizontal_fov_rad) * t;
}

double vertical_fov_rad(double horizontal, std::uint16_t width, std::uint16_t height) {
  if (width == 0) return 0;
  return 2 * std::atan(std::tan(horizontal / 2) * height / width);
}

double horizontal_from_vertical_fov_rad(double vertical, std::uint16_t width, std::uint16_t height) {
  if (height == 0) return 0;
  return 2 * std::atan(std::tan(vertical / 2) * width / height);
}

std::optional<double> zoom_for_fov(const CameraConfig& c, double horizontal) {
  const double span = c.widest_horizontal_fov_rad - c.narrowest_horizontal_fov_rad;
  if (!c.zoom.movable() || !(std::abs(span) > 1e-9) || !std::isfinite(horizontal)) return std::nullopt;
  return (c.widest_horizontal_fov_rad - horizontal) / span * 100;
}

CameraSettings apply_capabilities(const msg::CameraCapabilitiesCommandBody& b, const CameraConfig& c,
                                  CameraSettings s) {
  if (b.horizontal_resolution) s.width = within(*b.horizontal_resolution, c.min_width, c.max_width);
  if (b.vertical_resolution) s.height = within(*b.vertical_resolution, c.min_height, c.max_height);
  if (b.frame_rate_fps)
    s.frame_rate_fps =
        std::max<std::uint16_t>(within(*b.frame_rate_fps, c.min_frame_rate_fps, c.max_frame_rate_fps), 1);
  return s;
}

msg::CameraCapabilitiesReportBody to_capabilities_body(const CameraConfig& c, const CameraSettings& s) {
  msg::CameraCapabilitiesReportBody b;
  b.camera_id = c.id;
  if (!c.description.empty()) b.description = c.description.substr(0, 50);  // the field holds 50 characters
  double zoom_low = 0, zoom_high = 0;
  zoom_range(c, zoom_low, zoom_high);
  const double a = horizontal_fov_rad(c, zoom_low), z = horizontal_fov_rad(c, zoom_high);
  b.max_horizontal_fov_rad = fov(std::max(a, z));
  b.min_horizontal_fov_rad = fov(std::min(a, z));
  b.max_vertical_fov_rad = fov(vertical_fov_rad(*b.max_horizontal_fov_rad, s.width, s.height));
  b.min_vertical_fov_rad = fov(vertical_fov_rad(*b.min_horizontal_fov_rad, s.width, s.height));
  b.max_horizontal_resolution = c.max_width;
  b.min_horizontal_resolution = c.min_width;
  b.max_vertical_resolution = c.max_height;
  b.min_vertical_resolution = c.min_height;
  b.min_frame_rate_fps = c.min_frame_rate_fps;
  b.max_frame_rate_fps = c.max_frame_rate_fps;
  b.imagery_control = 0x0100;  // nothing automatic; non-interlaced
  b.audio_control = 0;         // no audio
  return b;
}

msg::CameraFormatReportBody to_format_body(const CameraConfig& c, const CameraSettings& s) {
  msg::CameraFormatReportBody b;
  b.camera_id = c.id;
  std::vector<std::uint8_t> formats{s.image_format};
  for (auto f : c.image_formats)
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  std::optional<std::uint8_t>* slots[] = {&b.image_format_1, &b.image_format_2, &b.image_format_3, &b.image_format_4};
  for (std::size_t i = 0; i < formats.size() && i < 4; ++i) *slots[i] = formats[i];
  return b;
}

}  // namespace jaus::components
