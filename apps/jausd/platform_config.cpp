#include "platform_config.hpp"

#include <array>
#include <numbers>
#include <string_view>

namespace jausd {

using namespace yaml_reader;
using jaus::bridge::DeviceOutput;
using Kind = jaus::host::PlatformSettings::Kind;

namespace {

constexpr std::array kPlatformNames{std::string_view("sim"), std::string_view("model")};
constexpr std::array kDriveModes{std::string_view("differential_output"), std::string_view("differential_speeds"),
                                 std::string_view("velocity"), std::string_view("ackermann")};
constexpr std::array kBrakeModes{std::string_view("scale"), std::string_view("ignore")};
constexpr std::array kHeadingSources{std::string_view("orientation"), std::string_view("encoders")};

const NumberRange kMaxAgeRange{0.05, true, 10, "a number of seconds 0.05..10"};
const NumberRange kBatteryRange{1, true, 1000, "a number of volts 1..1000"};
const NumberRange kEncoderStepRange{0.01, true, 1000, "a number of metres 0.01..1000"};

// "HOST:PORT" for udp and tcp.
void endpoint_host_port(const Entry& e, jaus::clearpath::PlatformEndpoint& endpoint, std::string_view scheme) {
  const std::string& text = e.scalar("HOST:PORT");
  auto parsed = jaus::clearpath::parse_platform_endpoint(std::string(scheme) + ":" + text);
  if (!parsed) e.must_be("HOST:PORT");
  endpoint = *parsed;
}

// none | {safety_flag: BITS} | {gpio: PINS, active_high: BOOL}
DeviceOutput device(const Entry& e) {
  DeviceOutput out;
  if (e.value.IsScalar() && e.value.Scalar() == "none") return out;
  if (!e.value.IsMap()) e.must_be("none, {safety_flag: BITS} or {gpio: PINS, active_high: true|false}");
  read_map(e.value, e.key, e.key_line,
           {{"safety_flag",
             [&](const Entry& f) {
               out.kind = DeviceOutput::Kind::safety_flag;
               out.bits = bits(f, 1, 0xFFFF);
             }},
            {"gpio",
             [&](const Entry& f) {
               out.kind = DeviceOutput::Kind::gpio;
               out.bits = bits(f, 1, 0xFFFFFFFFu);
             }},
            {"active_high", [&](const Entry& f) { out.active_high = boolean(f); }}});
  if (out.kind == DeviceOutput::Kind::none) e.must_be("a map with safety_flag or gpio");
  return out;
}

const NumberRange kSignRange{-1, true, 1, "1 or -1"};
const NumberRange kOffsetDegRange{-180, true, 180, "a number of degrees -180..180"};
const NumberRange kZoomFactorRange{0, true, 320, "a zoom factor 0..320"};

double sign(const Entry& e) {
  const double v = number(e, kSignRange);
  if (v != 1 && v != -1) e.must_be("1 or -1");
  return v;
}

// {camera_id: N, mount: N, pan_sign: +-1, tilt_sign: +-1, pan_offset_deg, tilt_offset_deg, zoom_min_factor, zoom_max_factor}
jaus::bridge::ClearpathMountConfig mount(const Entry& item) {
  jaus::bridge::ClearpathMountConfig m;
  bool camera = false, mount_given = false;
  read_map(item.value, "clearpath.mounts entry", item.key_line,
           {{"camera_id", [&](const Entry& e) { camera = true; m.camera_id = integer<std::uint8_t>(e, 1, 255); }},
            {"mount", [&](const Entry& e) { mount_given = true; m.mount = integer<std::uint8_t>(e, 0, 255); }},
            {"pan_sign", [&](const Entry& e) { m.pan_sign = sign(e); }},
            {"tilt_sign", [&](const Entry& e) { m.tilt_sign = sign(e); }},
            {"pan_offset_deg", [&](const Entry& e) { m.pan_offset_deg = number(e, kOffsetDegRange); }},
            {"tilt_offset_deg", [&](const Entry& e) { m.tilt_offset_deg = number(e, kOffsetDegRange); }},
            {"zoom_min_factor", [&](const Entry& e) { m.zoom_min_factor = number(e, kZoomFactorRange); }},
            {"zoom_max_factor", [&](const Entry& e) { m.zoom_max_factor = number(e, kZoomFactorRange); }}});
  if (!camera || !mount_given) fail(item.key_line, "a clearpath.mounts entry needs camera_id and mount");
  return m;
}

// {clearpath_joint: N, sign: +-1, offset_deg: D}
jaus::bridge::ClearpathJointMapping arm_joint(const Entry& item) {
  jaus::bridge::ClearpathJointMapping j;
  bool id = false;
  read_map(item.value, "clearpath.arm_joints entry", item.key_line,
           {{"clearpath_joint", [&](const Entry& e) { id = true; j.clearpath_joint = integer<std::uint8_t>(e, 0, 255); }},
            {"sign", [&](const Entry& e) { j.sign = sign(e); }},
            {"offset_deg", [&](const Entry& e) { j.offset_rad = number(e, kOffsetDegRange) * std::numbers::pi / 180; }}});
  if (!id) fail(item.key_line, "a clearpath.arm_joints entry needs clearpath_joint");
  return j;
}

}  // namespace

jaus::bridge::DriveMode drive_mode(const ClearpathOptions& options, jaus::components::Steering steering) {
  if (options.drive) return *options.drive;
  return steering == jaus::components::Steering::ackermann ? jaus::bridge::DriveMode::ackermann
                                                           : jaus::bridge::DriveMode::differential_output;
}

std::vector<jaus::bridge::ClearpathMountConfig> camera_mounts(const ClearpathOptions& options,
                                                              const jaus::components::VisualSensorConfig& cameras) {
  if (options.mounts) return *options.mounts;
  std::vector<jaus::bridge::ClearpathMountConfig> mounts;
  for (const auto& camera : cameras.cameras) {
    if (!camera.pan.movable() && !camera.tilt.movable()) continue;
    jaus::bridge::ClearpathMountConfig m;
    m.camera_id = camera.id;
    m.mount = static_cast<std::uint8_t>(mounts.size());
    if (camera.zoom.movable()) m.zoom_max_factor = 10;  // 1x widest .. 10x narrowest
    mounts.push_back(m);
  }
  return mounts;
}

std::vector<jaus::bridge::ClearpathJointMapping> arm_joints(const ClearpathOptions& options,
                                                            const jaus::components::ArmConfig& arm) {
  if (options.arm_joints) return *options.arm_joints;
  std::vector<jaus::bridge::ClearpathJointMapping> joints;
  // Clearpath joints are angles: an arm with a slide stays simulated unless mapped explicitly.
  for (const auto& joint : arm.joints)
    if (joint.prismatic) return joints;
  for (std::size_t i = 0; i < arm.joints.size(); ++i)
    joints.push_back({static_cast<std::uint8_t>(i), 1, 0});
  return joints;
}

void read_platform(const Entry& e, PlatformChoice& platform) {
  if (e.value.IsScalar()) {
    platform.kind = choice(e, kPlatformNames) == "sim" ? Kind::clearpath_sim : Kind::model;
    return;
  }
  if (!e.value.IsMap())
    e.must_be("sim, model, {serial: DEVICE, baud: N}, {udp: HOST:PORT} or {tcp: HOST:PORT}");
  platform.kind = Kind::clearpath;
  int transports = 0;
  bool baud_given = false;
  read_map(e.value, "platform", e.key_line,
           {{"serial",
             [&](const Entry& s) {
               ++transports;
               platform.endpoint.kind = jaus::clearpath::PlatformEndpoint::Kind::serial;
               platform.endpoint.device = s.scalar("a device path such as /dev/ttyUSB0");
               if (platform.endpoint.device.empty()) s.must_be("a device path such as /dev/ttyUSB0");
             }},
            {"baud",
             [&](const Entry& s) {
               baud_given = true;
               platform.endpoint.baud = integer<unsigned>(s, 1200, 4000000);
             }},
            {"udp",
             [&](const Entry& s) {
               ++transports;
               const unsigned baud = platform.endpoint.baud;
               endpoint_host_port(s, platform.endpoint, "udp");
               platform.endpoint.baud = baud;
             }},
            {"tcp", [&](const Entry& s) {
               ++transports;
               const unsigned baud = platform.endpoint.baud;
               endpoint_host_port(s, platform.endpoint, "tcp");
               platform.endpoint.baud = baud;
             }}});
  if (transports != 1) fail(e.key_line, "'platform' needs exactly one of serial, udp or tcp");
  if (baud_given && platform.endpoint.kind != jaus::clearpath::PlatformEndpoint::Kind::serial)
    fail(e.key_line, "'platform': baud applies to a serial port only");
}

void read_clearpath(const Entry& section, ClearpathOptions& o) {
  read_map(section.value, "clearpath", section.key_line,
           {{"drive",
             [&](const Entry& e) {
               const auto mode = choice(e, kDriveModes);
               o.drive = mode == "differential_speeds" ? jaus::bridge::DriveMode::differential_speeds
                         : mode == "velocity"          ? jaus::bridge::DriveMode::velocity
                         : mode == "ackermann"         ? jaus::bridge::DriveMode::ackermann
                                                       : jaus::bridge::DriveMode::differential_output;
             }},
            {"brake",
             [&](const Entry& e) {
               o.brake = choice(e, kBrakeModes) == "ignore" ? jaus::bridge::BrakeMode::ignore
                                                            : jaus::bridge::BrakeMode::scale;
             }},
            {"gear", [&](const Entry& e) { o.gear = boolean(e); }},
            {"main_power", [&](const Entry& e) { o.main_power = device(e); }},
            {"parking_brake", [&](const Entry& e) { o.parking_brake = device(e); }},
            {"horn", [&](const Entry& e) { o.horn = device(e); }},
            {"heading", [&](const Entry& e) { o.heading_from_orientation = choice(e, kHeadingSources) == "orientation"; }},
            {"data_rate_hz", [&](const Entry& e) { o.data_rate_hz = integer<std::uint16_t>(e, 1, 100); }},
            {"setpoint_max_age_s", [&](const Entry& e) { o.setpoint_max_age_s = number(e, kMaxAgeRange); }},
            {"nominal_battery_v", [&](const Entry& e) { o.nominal_battery_v = number(e, kBatteryRange); }},
            {"max_encoder_step_m", [&](const Entry& e) { o.max_encoder_step_m = number(e, kEncoderStepRange); }},
            {"emergency_flags", [&](const Entry& e) { o.emergency_flags = static_cast<std::uint16_t>(bits(e, 0, 0xFFFF)); }},
            {"platform_stop_flags",
             [&](const Entry& e) { o.platform_stop_flags = static_cast<std::uint16_t>(bits(e, 0, 0xFFFF)); }},
            {"platform_status_flags",
             [&](const Entry& e) { o.platform_status_flags = static_cast<std::uint16_t>(bits(e, 0, 0xFFFF)); }},
            {"mounts",
             [&](const Entry& e) {
               o.mounts.emplace();
               for (const auto& item : read_list(e)) o.mounts->push_back(mount(Entry{"mounts", line_of(item), item}));
             }},
            {"arm_joints", [&](const Entry& e) {
               o.arm_joints.emplace();
               for (const auto& item : read_list(e))
                 o.arm_joints->push_back(arm_joint(Entry{"arm_joints", line_of(item), item}));
             }}});
}

}  // namespace jausd
