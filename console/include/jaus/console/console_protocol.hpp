// The JSON frames between jaus-console's server and its page (docs/console.md,
// "Protocol"): page frames parsed into structs, every malformed frame a clear
// error; server frames formatted from structs. No I/O, no JAUS here.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/core/address.hpp"

namespace jaus::console {

// A page (one browser tab's WebSocket), numbered by the server from 1.
using PageId = std::uint64_t;

// ---- page -> server

struct ControlFrame {
  jaus::Address target;
  bool request = false;  // request, else release
  std::uint8_t authority = 0;
  bool operator==(const ControlFrame&) const = default;
};

struct DriveFrame {
  jaus::Address target;
  double linear_percent = 0;   // -100..100
  double angular_percent = 0;  // -100..100
  bool held = false;
  bool operator==(const DriveFrame&) const = default;
};

struct EmergencyFrame {
  jaus::Address target;  // 255.255.255.255 for "all"
  bool set = false;      // set, else clear
  bool operator==(const EmergencyFrame&) const = default;
};

struct StateFrame {
  jaus::Address target;
  bool resume = false;  // resume, else standby
  bool operator==(const StateFrame&) const = default;
};

struct CameraFrame {
  jaus::Address target;
  bool watch = false;
  std::optional<double> pan_deg;  // -360..360, positive right
  std::optional<double> tilt_deg;  // -360..360, positive up
  bool operator==(const CameraFrame&) const = default;
};

struct ArmFrame {
  jaus::Address target;
  std::vector<double> joints;  // degrees (revolute) or metres (prismatic)
  bool operator==(const ArmFrame&) const = default;
};

struct LocalPoint {
  double x = 0;
  double y = 0;
  bool operator==(const LocalPoint&) const = default;
};

struct WaypointsFrame {
  jaus::Address target;
  std::vector<LocalPoint> points;
  double speed_mps = 0;
  bool operator==(const WaypointsFrame&) const = default;
};

using PageFrame =
    std::variant<ControlFrame, DriveFrame, EmergencyFrame, StateFrame, CameraFrame, ArmFrame, WaypointsFrame>;

// Limits a page cannot exceed (a frame over them is refused whole).
inline constexpr std::size_t kMaxWaypoints = 1000;
inline constexpr std::size_t kMaxJoints = 32;

// One text frame. Errors (ErrorCode::invalid_argument, the message alone): not JSON, not an object, no or an
// unknown "type", a field missing, of the wrong type or out of range; the
// detail names the field ("drive: 'linear' must be a number in -100..100").
jaus::Expected<PageFrame> parse_page_frame(std::string_view text);

// ---- server -> page

struct WelcomeFrame {
  jaus::Address self;
  PageId page = 0;  // the page's own ID (what `driving.by` says)
  std::string version;
  int deadman_ms = 250;
  // The operator views by component ID (kind_views.hpp): the page picks its
  // default targets by them and names no kind and no ID itself.
  std::map<std::uint8_t, std::vector<std::string>> views;
};

struct TreeComponent {
  jaus::Address address;
  std::string name;
  std::string state;  // "ready", "emergency", ... or "unknown"
  std::optional<jaus::Address> controller;
  std::uint8_t authority = 0;
};
struct TreeNode {
  std::uint8_t id = 0;
  std::string name;
  std::vector<TreeComponent> components;
};
struct TreeSubsystem {
  std::uint8_t id = 0;
  std::string name;
  std::vector<TreeNode> nodes;
};
struct TreeFrame {
  std::vector<TreeSubsystem> subsystems;
};

enum class ControlState : std::uint8_t { requesting, held, refused, lost, released };
std::string_view to_string(ControlState state);

struct ControlStateFrame {
  jaus::Address target;
  ControlState state = ControlState::released;
  std::string why;
};

struct DrivingFrame {
  jaus::Address target;
  bool sending = false;
  std::optional<PageId> by;
};

struct PoseFrame {
  jaus::Address source;
  double x = 0, y = 0, yaw_rad = 0;
  std::optional<double> latitude, longitude;
};

struct VelocityFrame {
  jaus::Address source;
  double vx_mps = 0, vy_mps = 0, yaw_rate_rps = 0;
};

struct ImageFrame {
  jaus::Address source;
  std::string format;  // "jpeg", "png", ...
  std::string data_base64;
  std::uint64_t frame = 0;
};

struct ArmJoint {
  double min = 0, max = 0, position = 0;
  std::string unit;  // "deg" or "m"
};
struct ArmStateFrame {
  jaus::Address source;
  std::vector<ArmJoint> joints;
};

struct EmergencyStateFrame {
  jaus::Address target;
  bool active = false;
  std::vector<jaus::Address> holders;
};

enum class EventLevel : std::uint8_t { info, warn, error };
struct EventFrame {
  std::string time;  // ISO 8601 UTC
  EventLevel level = EventLevel::info;
  std::string text;
};

struct LinkFrame {
  std::size_t peers = 0;
  std::optional<std::int64_t> last_heard_ms;  // null before anything was heard
};

struct ErrorFrame {
  std::string text;
};

using ServerFrame = std::variant<WelcomeFrame, TreeFrame, ControlStateFrame, DrivingFrame, PoseFrame, VelocityFrame,
                                 ImageFrame, ArmStateFrame, EmergencyStateFrame, EventFrame, LinkFrame, ErrorFrame>;

// One JSON text frame (compact).
std::string format_frame(const ServerFrame& frame);

// Standard base64 (with padding), for image data.
std::string base64(std::span<const std::uint8_t> bytes);

}  // namespace jaus::console
