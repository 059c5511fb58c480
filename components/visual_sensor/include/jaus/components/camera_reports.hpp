// Part 3's environment sensor bodies <-> the cameras' terms (camera.hpp),
// one place for each field's meaning (camera_reports.cpp).
//
// Set Camera Pose, axis mapping. Part 3's camera frame: Z the optical axis
// (forward at home), X to the right, Y down; pan is a rotation about Y,
// positive to the viewer's right; tilt a rotation about X, positive up.
//   field 8, Y angle/rate  (bit 4) -> pan
//   field 7, X angle/rate  (bit 3) -> tilt
//   field 6, Z displacement/rate (bit 2) -> zoom (not a pose: our mounts have
//            no Z translation, and a zoom lens moves the view along Z)
//   fields 4, 5 and 9 (bits 0, 1, 5): axes our mounts do not have, ignored.
// Mode indicator bit n set: field 4 + n is a rate; clear: a position.
//   position: percent of full scale, full scale being the greater of |min| and
//             |max| (so 0 % is home), then clipped to [min, max];
//   rate:     percent of max_rate; the mount moves until its limit or a new command.
//
// Report Camera Pose: the origin is the configured mount point (vehicle
// frame, metres); the direction cosines are those of the camera's X and Z
// axes in the vehicle frame (x forward, y right, z down), for yaw = home yaw
// + pan and pitch = home pitch + tilt: the mount pans about the vehicle's
// vertical, then tilts about the camera's X axis, which stays level:
//   Z = (cos(pitch) cos(yaw), cos(pitch) sin(yaw), -sin(pitch))
//   X = (-sin(yaw), cos(yaw), 0)
#pragma once

#include <cstdint>
#include <optional>

#include "jaus/components/camera.hpp"
#include "jaus/messages/environment_messages.hpp"

namespace jaus::components {

// Set Camera Pose's presence and mode bits (field 4 + bit).
namespace pose_field {
inline constexpr std::uint8_t kXLinear = 0x01;
inline constexpr std::uint8_t kYLinear = 0x02;
inline constexpr std::uint8_t kZLinear = 0x04;   // zoom
inline constexpr std::uint8_t kXAngular = 0x08;  // tilt
inline constexpr std::uint8_t kYAngular = 0x10;  // pan
inline constexpr std::uint8_t kZAngular = 0x20;
}  // namespace pose_field

// What the component uses a camera with: Set Camera Capabilities and Set
// Camera Format Options change it, within the camera's configuration.
struct CameraSettings {
  std::uint16_t width = 320;
  std::uint16_t height = 240;
  std::uint16_t frame_rate_fps = 10;
  std::uint8_t image_format = image_format::kPng;
  bool operator==(const CameraSettings&) const = default;
};

// The settings a camera starts with: its configured ones, within its ranges.
CameraSettings initial_settings(const CameraConfig& camera);

// A Set Camera Pose for `camera`: the mount command, and the presence bits
// of fields it had to ignore (axes the camera does not have).
struct PoseCommand {
  MountCommand command;
  std::uint8_t ignored = 0;
};
PoseCommand to_mount_command(const msg::CameraPoseCommandBody& body, const CameraConfig& camera);
double percent_to_position(double percent, const MountAxis& axis);
double percent_to_rate(double percent, const MountAxis& axis);

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
struct CameraAxes {
  Vec3 x;  // the camera's right
  Vec3 z;  // the optical axis
};
CameraAxes camera_axes_in_vehicle(double yaw_rad, double pitch_rad);
msg::CameraPoseReportBody to_camera_pose_body(const CameraConfig& camera, const MountState& mount);

// The lens: horizontal FOV linear in zoom between the widest (0 %) and the
// narrowest (100 %); vertical FOV from the image's aspect ratio.
double horizontal_fov_rad(const CameraConfig& camera, double zoom_percent);
double vertical_fov_rad(double horizontal_fov_rad, std::uint16_t width, std::uint16_t height);
double horizontal_from_vertical_fov_rad(double vertical_fov_rad, std::uint16_t width, std::uint16_t height);
// The zoom that gives `horizontal_fov_rad`, or nullopt when the zoom cannot change it.
std::optional<double> zoom_for_fov(const CameraConfig& camera, double horizontal_fov_rad);

// Set Camera Capabilities: the settings it asks for, clamped to the camera's
// ranges (fields this component does not act on are left alone).
CameraSettings apply_capabilities(const msg::CameraCapabilitiesCommandBody& body, const CameraConfig& camera,
                                  CameraSettings settings);
msg::CameraCapabilitiesReportBody to_capabilities_body(const CameraConfig& camera, const CameraSettings& settings);
// The image formats, the one in use first, at most four; no audio.
msg::CameraFormatReportBody to_format_body(const CameraConfig& camera, const CameraSettings& settings);

}  // namespace jaus::components
