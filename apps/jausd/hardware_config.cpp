#include "hardware_config.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>

#include "jaus/components/camera.hpp"
#include "jaus/components/camera_rules.hpp"

namespace jausd {

using namespace yaml_reader;
using jaus::components::ArmConfig;
using jaus::components::CameraConfig;
using jaus::components::JointConfig;
using jaus::components::MountAxis;
using jaus::components::VisualSensorConfig;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

// Image format codes of Set Camera Format Options the cameras can send.
using jaus::components::image_format::kJpeg;
using jaus::components::image_format::kPng;
constexpr std::array<std::string_view, 2> kFormatNames{"png", "jpeg"};
constexpr std::array<std::string_view, 2> kJointTypes{"revolute", "prismatic"};

constexpr NumberRange kAngleDeg{-360, true, 360, "a number of degrees -360..360"};
constexpr NumberRange kRateDeg{0, true, 3600, "a number of degrees per second 0..3600"};
constexpr NumberRange kZoomRate{0, true, 1000, "a number of percent per second 0..1000"};
constexpr NumberRange kFovDeg{0, false, 180, "a number of degrees > 0 and <= 180"};
constexpr NumberRange kCameraOffset{-32.767, true, 32.767, "a number of metres -32.767..32.767"};
// Report Manipulator Specifications carries lengths in millimetres (u16) and
// positions in +-30 m; joint ranges are those Set Joint Positions can encode.
constexpr NumberRange kLinkLength{0, true, 65.535, "a number of metres 0..65.535"};
constexpr NumberRange kBasePosition{-30, true, 30, "a number of metres -30..30"};
constexpr NumberRange kQuaternion{-1, true, 1, "a number -1..1"};
constexpr NumberRange kJointDeg{-1440, true, 1440, "a number of degrees -1440..1440"};
constexpr NumberRange kJointSpeedDeg{0, false, 1800, "a number of degrees per second > 0 and <= 1800"};
constexpr NumberRange kPrismatic{-10, true, 10, "a number of metres -10..10"};
constexpr NumberRange kPrismaticSpeed{0, false, 5, "a number of metres per second > 0 and <= 5"};
constexpr NumberRange kEffort{0, false, 1000, "a number > 0 and <= 1000"};
constexpr NumberRange kArmRate{1, true, 1000, "a number 1..1000"};

bool printable(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char ch) { return ch >= 0x20 && ch < 0x7F; });
}

std::string text(const Entry& e, std::size_t min, std::size_t max) {
  const std::string what = std::to_string(min) + ".." + std::to_string(max) + " printable ASCII characters";
  const std::string& value = e.scalar(what);
  if (value.size() < min || value.size() > max || !printable(value)) e.must_be(what);
  return value;
}

// [a, b, c, ...] of exactly `n` numbers in `range`.
std::vector<double> numbers(const Entry& e, std::size_t n, const NumberRange& range) {
  const std::string what = "a list of " + std::to_string(n) + " numbers, each " + std::string(range.text);
  if (!e.value.IsSequence() || e.value.size() != n) e.must_be(what);
  std::vector<double> out;
  for (const auto& item : e.value) out.push_back(number(Entry{e.key, line_of(item), item}, range));
  return out;
}

std::function<void(const Entry&)> degrees(double& target, const NumberRange& range) {
  return [&target, &range](const Entry& e) { target = number(e, range) * kDeg; };
}

void read_axis(const Entry& s, std::string_view where, MountAxis& axis) {
  axis = MountAxis{};  // an axis named without limits does not move
  read_map(s.value, where, s.key_line,
           {{"min_deg", degrees(axis.min, kAngleDeg)},
            {"max_deg", degrees(axis.max, kAngleDeg)},
            {"max_rate_deg_s", degrees(axis.max_rate, kRateDeg)}});
}

CameraConfig camera(const YAML::Node& node, std::size_t index) {
  CameraConfig c;
  c.id = static_cast<std::uint8_t>(std::min<std::size_t>(index + 1, 255));
  c.pan = c.tilt = c.zoom = MountAxis{};  // a fixed camera unless its mount is described
  const int line = line_of(node);
  if (!node.IsMap()) fail(line, "a camera must be a map with an 'id' and a 'name', got " + describe(node));
  read_map(
      node, "cameras", line,
      {{"id", [&](const Entry& e) { c.id = integer<std::uint8_t>(e, 1, 255); }},
       {"name", [&](const Entry& e) { c.name = text(e, 1, 15); }},
       {"description", [&](const Entry& e) { c.description = text(e, 0, 50); }},
       {"position_m",
        [&](const Entry& e) {
          const auto p = numbers(e, 3, kCameraOffset);
          c.x_m = p[0], c.y_m = p[1], c.z_m = p[2];
        }},
       {"home_yaw_deg", degrees(c.home_yaw_rad, kAngleDeg)},
       {"home_pitch_deg", degrees(c.home_pitch_rad, kAngleDeg)},
       {"pan", [&](const Entry& e) { read_axis(e, "cameras.pan", c.pan); }},
       {"tilt", [&](const Entry& e) { read_axis(e, "cameras.tilt", c.tilt); }},
       {"zoom",
        [&](const Entry& e) {
          c.zoom = MountAxis{0, 100, 0};
          read_map(e.value, "cameras.zoom", e.key_line,
                   {{"max_rate_percent_s", [&](const Entry& r) { c.zoom.max_rate = number(r, kZoomRate); }}});
        }},
       {"field_of_view_deg",
        [&](const Entry& e) {
          read_map(e.value, "cameras.field_of_view_deg", e.key_line,
                   {{"widest", degrees(c.widest_horizontal_fov_rad, kFovDeg)},
                    {"narrowest", degrees(c.narrowest_horizontal_fov_rad, kFovDeg)}});
        }},
       {"width", [&](const Entry& e) { c.width = integer<std::uint16_t>(e, 1, 65535); }},
       {"height", [&](const Entry& e) { c.height = integer<std::uint16_t>(e, 1, 65535); }},
       {"min_width", [&](const Entry& e) { c.min_width = integer<std::uint16_t>(e, 1, 65535); }},
       {"min_height", [&](const Entry& e) { c.min_height = integer<std::uint16_t>(e, 1, 65535); }},
       {"max_width", [&](const Entry& e) { c.max_width = integer<std::uint16_t>(e, 1, 65535); }},
       {"max_height", [&](const Entry& e) { c.max_height = integer<std::uint16_t>(e, 1, 65535); }},
       {"frame_rate_fps", [&](const Entry& e) { c.frame_rate_fps = integer<std::uint16_t>(e, 1, 1000); }},
       {"min_frame_rate_fps", [&](const Entry& e) { c.min_frame_rate_fps = integer<std::uint16_t>(e, 1, 1000); }},
       {"max_frame_rate_fps", [&](const Entry& e) { c.max_frame_rate_fps = integer<std::uint16_t>(e, 1, 1000); }},
       {"formats",
        [&](const Entry& e) {
          c.image_formats.clear();
          for (const auto& item : read_list(e))
            c.image_formats.push_back(choice(Entry{"formats", line_of(item), item}, kFormatNames) == "png" ? kPng
                                                                                                           : kJpeg);
        }},
       {"image_directory", [&](const Entry& e) {
          c.image_directory = e.scalar("a directory of PNG or JPEG files");
          std::error_code ec;
          if (!std::filesystem::is_directory(c.image_directory, ec))
            fail(e.value_line(), "'image_directory' " + jaus::quoted(c.image_directory) + " is not a directory");
        }}});
  if (auto ok = jaus::components::check_cameras_config(VisualSensorConfig{{c}}); !ok) fail(line, ok.error().message());
  return c;
}

// A joint's values are in degrees (revolute) or metres (prismatic); a key of
// the other kind is an error, so a copied line cannot silently change units.
JointConfig joint(const YAML::Node& node, std::size_t index) {
  JointConfig j;
  const int line = line_of(node);
  if (!node.IsMap()) fail(line, "a joint must be a map with a 'type', got " + describe(node));
  std::map<std::string, std::pair<double, int>> values;  // key -> (value as written, line)
  const auto keep = [&](const NumberRange& range) {
    return [&values, &range](const Entry& e) { values[e.key] = {number(e, range), e.key_line}; };
  };
  bool typed = false;
  read_map(node, "manipulator.joints", line,
           {{"name", [&](const Entry& e) { j.name = text(e, 1, 40); }},
            {"type", [&](const Entry& e) { j.prismatic = choice(e, kJointTypes) == "prismatic", typed = true; }},
            {"link_length_m", [&](const Entry& e) { j.link_length_m = number(e, kLinkLength); }},
            {"twist_deg", degrees(j.twist_angle_rad, kAngleDeg)},
            {"offset_m", keep(kPrismatic)},
            {"offset_deg", keep(kAngleDeg)},
            {"min_deg", keep(kJointDeg)},
            {"max_deg", keep(kJointDeg)},
            {"initial_deg", keep(kJointDeg)},
            {"max_speed_deg_s", keep(kJointSpeedDeg)},
            {"max_torque_nm", keep(kEffort)},
            {"min_m", keep(kPrismatic)},
            {"max_m", keep(kPrismatic)},
            {"initial_m", keep(kPrismatic)},
            {"max_speed_m_s", keep(kPrismaticSpeed)},
            {"max_force_n", keep(kEffort)}});
  const std::string label = jaus::components::joint_label(j, index);
  if (!typed) fail(line, label + " needs a 'type' (revolute or prismatic)");
  // revolute key, prismatic key, target, scale
  struct Pair {
    const char* revolute;
    const char* prismatic;
    double* target;
    double revolute_scale;
  };
  const Pair pairs[] = {{"offset_m", "offset_deg", &j.offset, 1},
                        {"min_deg", "min_m", &j.min_position, kDeg},
                        {"max_deg", "max_m", &j.max_position, kDeg},
                        {"initial_deg", "initial_m", &j.initial_position, kDeg},
                        {"max_speed_deg_s", "max_speed_m_s", &j.max_velocity, kDeg},
                        {"max_torque_nm", "max_force_n", &j.max_effort, 1}};
  for (const auto& p : pairs) {
    const char* mine = j.prismatic ? p.prismatic : p.revolute;
    const char* other = j.prismatic ? p.revolute : p.prismatic;
    if (auto it = values.find(other); it != values.end())
      fail(it->second.second, "'" + std::string(other) + "' is for " + (j.prismatic ? "revolute" : "prismatic") +
                                  " joints; " + label + " is " +
                                  (j.prismatic ? "prismatic: use '" : "revolute: use '") + mine + "'");
    if (auto it = values.find(mine); it != values.end()) {
      // The prismatic joint's offset is an angle (degrees in the file).
      const double scale = j.prismatic ? (p.target == &j.offset ? kDeg : 1) : p.revolute_scale;
      *p.target = it->second.first * scale;
    }
  }
  if (j.prismatic && !values.contains("min_m") && !values.contains("max_m")) j.min_position = 0, j.max_position = 0.5;
  if (auto ok = jaus::components::check_joint_config(j, label); !ok) fail(line, ok.error().message());
  return j;
}

}  // namespace

VisualSensorConfig default_cameras() {
  CameraConfig front;
  front.id = 1;
  front.name = "front_ptz";
  front.description = "front pan-tilt-zoom camera";
  front.x_m = 0.30, front.y_m = 0, front.z_m = -0.40;
  front.pan = MountAxis{-170 * kDeg, 170 * kDeg, 60 * kDeg};
  front.tilt = MountAxis{-30 * kDeg, 90 * kDeg, 30 * kDeg};
  front.zoom = MountAxis{0, 100, 50};
  front.widest_horizontal_fov_rad = 60 * kDeg;
  front.narrowest_horizontal_fov_rad = 6 * kDeg;

  CameraConfig rear;
  rear.id = 2;
  rear.name = "rear_fixed";
  rear.description = "rear-facing fixed camera";
  rear.x_m = -0.35, rear.y_m = 0, rear.z_m = -0.30;
  rear.home_yaw_rad = kPi;
  rear.home_pitch_rad = -10 * kDeg;
  rear.widest_horizontal_fov_rad = rear.narrowest_horizontal_fov_rad = 90 * kDeg;
  rear.width = 160, rear.height = 120;
  rear.frame_rate_fps = 5;
  rear.image_formats = {kPng};
  return {{front, rear}};
}

ArmConfig default_arm() {
  // A six-joint arm on the deck, 0.2 m ahead of the centre: base yaw,
  // shoulder, elbow, wrist pitch, wrist roll and tool roll; reach ~0.7 m.
  ArmConfig arm;
  arm.base_x_m = 0.2, arm.base_y_m = 0, arm.base_z_m = -0.25;
  const auto revolute = [](std::string name, double a, double alpha_deg, double d, double min_deg, double max_deg,
                           double speed_deg_s, double torque) {
    JointConfig j;
    j.name = std::move(name);
    j.link_length_m = a, j.twist_angle_rad = alpha_deg * kDeg, j.offset = d;
    j.min_position = min_deg * kDeg, j.max_position = max_deg * kDeg;
    j.max_velocity = speed_deg_s * kDeg, j.max_effort = torque;
    return j;
  };
  arm.joints = {revolute("base_yaw", 0, 90, 0.15, -170, 170, 60, 80),
                revolute("shoulder", 0.30, 0, 0, -90, 90, 45, 120),
                revolute("elbow", 0.25, 0, 0, -150, 150, 60, 60),
                revolute("wrist_pitch", 0, 90, 0, -120, 120, 90, 20),
                // Rolls short of a full turn: Report Manipulator Specifications sends a
                // negative limit modulo 2 pi, so -180..180 would read as one angle.
                revolute("wrist_roll", 0, 270, 0.10, -175, 175, 120, 10),
                revolute("tool_roll", 0, 0, 0.05, -175, 175, 180, 5)};
  return arm;
}

void read_cameras(const Entry& section, VisualSensorConfig& cameras) {
  cameras.cameras.clear();
  std::map<int, int> seen;  // id -> line
  const auto items = read_list(section);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const CameraConfig c = camera(items[i], i);
    if (const auto [it, inserted] = seen.emplace(c.id, line_of(items[i])); !inserted)
      fail(line_of(items[i]), "duplicate camera id " + std::to_string(c.id) + first_at(it->second));
    cameras.cameras.push_back(c);
  }
  if (auto ok = jaus::components::check_cameras_config(cameras); !ok) fail(section.key_line, ok.error().message());
}

void read_manipulator(const Entry& section, ArmConfig& arm) {
  read_map(
      section.value, "manipulator", section.key_line,
      {{"base",
        [&](const Entry& s) {
          read_map(s.value, "manipulator.base", s.key_line,
                   {{"position_m",
                     [&](const Entry& e) {
                       const auto p = numbers(e, 3, kBasePosition);
                       arm.base_x_m = p[0], arm.base_y_m = p[1], arm.base_z_m = p[2];
                     }},
                    {"quaternion", [&](const Entry& e) {
                       const auto q = numbers(e, 4, kQuaternion);
                       arm.base_quaternion_d = q[0], arm.base_quaternion_a = q[1];
                       arm.base_quaternion_b = q[2], arm.base_quaternion_c = q[3];
                       if (std::abs(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] - 1) > 1e-3)
                         e.must_be("a unit quaternion [d, a, b, c]");
                     }}});
        }},
       {"update_rate_hz", [&](const Entry& e) { arm.update_rate_hz = number(e, kArmRate); }},
       {"joints", [&](const Entry& e) {
          arm.joints.clear();
          const auto items = read_list(e);
          for (std::size_t i = 0; i < items.size(); ++i) arm.joints.push_back(joint(items[i], i));
          if (arm.joints.empty() || arm.joints.size() > 255) e.must_be("a list of 1..255 joints");
        }}});
  // The component's rules, so jausd refuses at load what the manipulator would refuse to run.
  if (auto ok = jaus::components::check_arm_config(arm); !ok) fail(section.key_line, ok.error().message());
}

}  // namespace jausd
