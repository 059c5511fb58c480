#include "platform_config.hpp"

#include <array>
#include <numbers>
#include <string_view>

#include "jaus/host/platform_kinds.hpp"

namespace jausd {

using namespace yaml_reader;
using jaus::bridge::DeviceOutput;

namespace {

constexpr std::array kDriveModes{std::string_view("differential_output"), std::string_view("differential_speeds"),
                                 std::string_view("velocity"), std::string_view("ackermann")};
constexpr std::array kBrakeModes{std::string_view("scale"), std::string_view("ignore")};
constexpr std::array kHeadingSources{std::string_view("orientation"), std::string_view("encoders")};

const NumberRange kMaxAgeRange{0.05, true, 10, "a number of seconds 0.05..10"};
const NumberRange kBatteryRange{1, true, 1000, "a number of volts 1..1000"};
const NumberRange kEncoderStepRange{0.01, true, 1000, "a number of metres 0.01..1000"};

// How `platform:` may name each kind alone, and every kind's option keys, in the list's order.
std::vector<std::string_view> written_kinds() {
  std::vector<std::string_view> names;
  for (const auto& kind : jaus::host::platform_kinds())
    if (!kind.written.empty()) names.push_back(kind.written);
  return names;
}

std::vector<std::string_view> platform_options() {
  std::vector<std::string_view> keys;
  for (const auto& kind : jaus::host::platform_kinds()) keys.insert(keys.end(), kind.options.begin(), kind.options.end());
  return keys;
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
  platform.options.clear();
  platform.option_lines.clear();
  if (e.value.IsScalar()) {
    platform.kind = std::string(jaus::host::platform_kind_written(choice(e, written_kinds()))->name);
    return;
  }
  const auto keys = platform_options();
  if (!e.value.IsMap())
    e.must_be(join(written_kinds()) + " or a map of a platform's options (" + join(keys) + ")");
  // The first option names the kind; the kind checks them all (validate()).
  const jaus::host::PlatformKind* kind = nullptr;
  std::vector<Key> readers;
  for (const auto key : keys)
    readers.push_back({key, [&](const Entry& o) {
                         const jaus::host::PlatformKind* owner = jaus::host::platform_kind_with_option(o.key);
                         if (kind == nullptr) kind = owner;
                         if (owner != kind)
                           fail(o.key_line, "'platform': '" + o.key + "' is an option of platform " +
                                                std::string(owner->name) + ", not of " + std::string(kind->name));
                         platform.options[o.key] = o.is_null() ? std::string() : o.scalar("a value");
                         platform.option_lines[o.key] = o.value_line();
                       }});
  read_map(e.value, "platform", e.key_line, readers);
  if (kind == nullptr) e.must_be("a map of a platform's options (" + join(keys) + ")");
  platform.kind = std::string(kind->name);
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
