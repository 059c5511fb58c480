#include "jaus/console/console_protocol.hpp"

#include <cmath>
#include <nlohmann/json.hpp>


namespace jaus::console {

namespace {

using nlohmann::json;

jaus::Unexpected<jaus::Error> refuse(std::string_view type, const std::string& why) {
  return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, std::string(type) + ": " + why));
}

// The fields of one frame, each read with its check; the first error wins.
class Fields {
 public:
  Fields(const json& object, std::string_view type) : object_(object), type_(type) {}

  jaus::Expected<jaus::Address> address(const char* name) const {
    const auto* value = find(name);
    if (!value || !value->is_string())
      return refuse(type_, std::string("'") + name + "' must be a JAUS ID as text (\"1.1.33.1\")");
    const auto& text = value->get_ref<const std::string&>();
    if (text == "all") return jaus::Address{255, 255, 255, 255};
    auto parsed = jaus::Address::parse(text);
    if (!parsed) return refuse(type_, std::string("'") + name + "' is not a JAUS ID: \"" + text + "\"");
    return *parsed;
  }
  jaus::Expected<double> number(const char* name, double low, double high) const {
    const auto* value = find(name);
    if (!value || !value->is_number() || !std::isfinite(value->get<double>()) || value->get<double>() < low ||
        value->get<double>() > high)
      return refuse(type_, std::string("'") + name + "' must be a number in " + text(low) + ".." + text(high));
    return value->get<double>();
  }
  jaus::Expected<std::optional<double>> optional_number(const char* name, double low, double high) const {
    if (!find(name)) return std::optional<double>{};
    auto n = number(name, low, high);
    if (!n) return jaus::unexpected(n.error());
    return std::optional<double>{*n};
  }
  jaus::Expected<bool> boolean(const char* name) const {
    const auto* value = find(name);
    if (!value || !value->is_boolean()) return refuse(type_, std::string("'") + name + "' must be true or false");
    return value->get<bool>();
  }
  // One of two words: true for `yes`, false for `no`.
  jaus::Expected<bool> choice(const char* name, std::string_view yes, std::string_view no) const {
    const auto* value = find(name);
    if (value && value->is_string()) {
      const auto& word = value->get_ref<const std::string&>();
      if (word == yes) return true;
      if (word == no) return false;
    }
    return refuse(type_, std::string("'") + name + "' must be \"" + std::string(yes) + "\" or \"" + std::string(no) +
                             "\"");
  }
  jaus::Expected<const json*> array(const char* name, std::size_t max) const {
    const auto* value = find(name);
    if (!value || !value->is_array() || value->size() > max)
      return refuse(type_, std::string("'") + name + "' must be an array of at most " + std::to_string(max));
    return value;
  }
  std::string_view type() const { return type_; }

 private:
  const json* find(const char* name) const {
    const auto it = object_.find(name);
    return it == object_.end() ? nullptr : &*it;
  }
  static std::string text(double v) {
    const auto whole = static_cast<long long>(v);
    return static_cast<double>(whole) == v ? std::to_string(whole) : std::to_string(v);
  }
  const json& object_;
  std::string_view type_;
};

// Unwraps each Expected field or returns its error from the caller.
#define JAUS_CONSOLE_TAKE(var, expr) \
  auto var##_taken = (expr);         \
  if (!var##_taken) return jaus::unexpected(var##_taken.error()); \
  auto var = *var##_taken

jaus::Expected<PageFrame> parse_control(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(request, f.choice("action", "request", "release"));
  ControlFrame frame{target, request, 0};
  if (request) {
    JAUS_CONSOLE_TAKE(authority, f.number("authority", 0, 255));
    if (authority != std::floor(authority)) return refuse(f.type(), "'authority' must be a whole number");
    frame.authority = static_cast<std::uint8_t>(authority);
  }
  return PageFrame{frame};
}

jaus::Expected<PageFrame> parse_drive(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(linear, f.number("linear", -100, 100));
  JAUS_CONSOLE_TAKE(angular, f.number("angular", -100, 100));
  JAUS_CONSOLE_TAKE(held, f.boolean("held"));
  return PageFrame{DriveFrame{target, linear, angular, held}};
}

jaus::Expected<PageFrame> parse_emergency(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(set, f.choice("action", "set", "clear"));
  return PageFrame{EmergencyFrame{target, set}};
}

jaus::Expected<PageFrame> parse_state(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(resume, f.choice("action", "resume", "standby"));
  return PageFrame{StateFrame{target, resume}};
}

jaus::Expected<PageFrame> parse_camera(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(watch, f.boolean("watch"));
  JAUS_CONSOLE_TAKE(pan, f.optional_number("pan_deg", -360, 360));
  JAUS_CONSOLE_TAKE(tilt, f.optional_number("tilt_deg", -360, 360));
  return PageFrame{CameraFrame{target, watch, pan, tilt}};
}

jaus::Expected<PageFrame> parse_arm(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(joints, f.array("joints", kMaxJoints));
  ArmFrame frame{target, {}};
  for (const auto& joint : *joints) {
    if (!joint.is_number() || !std::isfinite(joint.get<double>()))
      return refuse(f.type(), "'joints' must hold numbers (degrees or metres)");
    frame.joints.push_back(joint.get<double>());
  }
  if (frame.joints.empty()) return refuse(f.type(), "'joints' must not be empty");
  return PageFrame{frame};
}

jaus::Expected<PageFrame> parse_waypoints(const Fields& f) {
  JAUS_CONSOLE_TAKE(target, f.address("target"));
  JAUS_CONSOLE_TAKE(points, f.array("points", kMaxWaypoints));
  JAUS_CONSOLE_TAKE(speed, f.number("speed_mps", 0, 327.67));
  WaypointsFrame frame{target, {}, speed};
  constexpr double kLocalLimit = 100'000;  // the Local Waypoint's x/y range (m)
  for (const auto& point : *points) {
    const auto coordinate = [&](const char* name) -> std::optional<double> {
      if (!point.is_object() || !point.contains(name) || !point[name].is_number()) return std::nullopt;
      const double v = point[name].get<double>();
      if (!std::isfinite(v) || std::abs(v) > kLocalLimit) return std::nullopt;
      return v;
    };
    const auto x = coordinate("x");
    const auto y = coordinate("y");
    if (!x || !y) return refuse(f.type(), "each of 'points' must be {\"x\": m, \"y\": m} within +-100000 m");
    frame.points.push_back(LocalPoint{*x, *y});
  }
  if (frame.points.empty()) return refuse(f.type(), "'points' must not be empty");
  return PageFrame{frame};
}

#undef JAUS_CONSOLE_TAKE

std::string address_text(const jaus::Address& a) { return a.to_string(); }


std::string_view to_string(EventLevel level) {
  switch (level) {
    case EventLevel::info: return "info";
    case EventLevel::warn: return "warn";
    case EventLevel::error: return "error";
  }
  return "info";
}

json to_json(const WelcomeFrame& f) {
  json views = json::object();  // JSON's keys are text: {"33": ["drive", "emergency"], ...}
  for (const auto& [id, names] : f.views) views[std::to_string(id)] = names;
  return {{"type", "welcome"},    {"self", address_text(f.self)}, {"page", f.page},
          {"version", f.version}, {"deadman_ms", f.deadman_ms},  {"views", std::move(views)}};
}

json to_json(const TreeFrame& f) {
  json subsystems = json::array();
  for (const auto& s : f.subsystems) {
    json nodes = json::array();
    for (const auto& n : s.nodes) {
      json components = json::array();
      for (const auto& c : n.components)
        components.push_back({{"address", address_text(c.address)},
                              {"name", c.name},
                              {"state", c.state},
                              {"controller", c.controller ? json(address_text(*c.controller)) : json(nullptr)},
                              {"authority", c.authority}});
      nodes.push_back({{"id", n.id}, {"name", n.name}, {"components", std::move(components)}});
    }
    subsystems.push_back({{"id", s.id}, {"name", s.name}, {"nodes", std::move(nodes)}});
  }
  return {{"type", "tree"}, {"subsystems", std::move(subsystems)}};
}

json to_json(const ControlStateFrame& f) {
  return {{"type", "control"}, {"target", address_text(f.target)}, {"state", to_string(f.state)}, {"why", f.why}};
}

json to_json(const DrivingFrame& f) {
  return {{"type", "driving"},
          {"target", address_text(f.target)},
          {"sending", f.sending},
          {"by", f.by ? json(*f.by) : json(nullptr)}};
}

json to_json(const PoseFrame& f) {
  json j = {{"type", "pose"}, {"source", address_text(f.source)}, {"x", f.x}, {"y", f.y}, {"yaw_rad", f.yaw_rad}};
  if (f.latitude) j["latitude"] = *f.latitude;
  if (f.longitude) j["longitude"] = *f.longitude;
  return j;
}

json to_json(const VelocityFrame& f) {
  return {{"type", "velocity"},
          {"source", address_text(f.source)},
          {"vx_mps", f.vx_mps},
          {"vy_mps", f.vy_mps},
          {"yaw_rate_rps", f.yaw_rate_rps}};
}

json to_json(const ImageFrame& f) {
  return {{"type", "image"},
          {"source", address_text(f.source)},
          {"format", f.format},
          {"data", f.data_base64},
          {"frame", f.frame}};
}

json to_json(const ArmStateFrame& f) {
  json joints = json::array();
  for (const auto& j : f.joints)
    joints.push_back({{"min", j.min}, {"max", j.max}, {"position", j.position}, {"unit", j.unit}});
  return {{"type", "arm"}, {"source", address_text(f.source)}, {"joints", std::move(joints)}};
}

json to_json(const EmergencyStateFrame& f) {
  json holders = json::array();
  for (const auto& h : f.holders) holders.push_back(address_text(h));
  return {{"type", "emergency"},
          {"target", f.target == jaus::Address{255, 255, 255, 255} ? std::string("all") : address_text(f.target)},
          {"active", f.active},
          {"holders", std::move(holders)}};
}

json to_json(const EventFrame& f) {
  return {{"type", "event"}, {"time", f.time}, {"level", to_string(f.level)}, {"text", f.text}};
}

json to_json(const LinkFrame& f) {
  return {{"type", "link"},
          {"peers", f.peers},
          {"last_heard_ms", f.last_heard_ms ? json(*f.last_heard_ms) : json(nullptr)}};
}

json to_json(const ErrorFrame& f) { return {{"type", "error"}, {"text", f.text}}; }

}  // namespace

std::string_view to_string(ControlState state) {
  switch (state) {
    case ControlState::requesting: return "requesting";
    case ControlState::held: return "held";
    case ControlState::refused: return "refused";
    case ControlState::lost: return "lost";
    case ControlState::released: return "released";
  }
  return "released";
}

jaus::Expected<PageFrame> parse_page_frame(std::string_view text) {
  const json frame = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (frame.is_discarded()) return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, "not JSON"));
  if (!frame.is_object())
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, "a frame must be a JSON object"));
  const auto type_it = frame.find("type");
  if (type_it == frame.end() || !type_it->is_string())
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, "a frame must have a \"type\" (text)"));
  const auto& type = type_it->get_ref<const std::string&>();
  const Fields fields(frame, type);
  if (type == "control") return parse_control(fields);
  if (type == "drive") return parse_drive(fields);
  if (type == "emergency") return parse_emergency(fields);
  if (type == "state") return parse_state(fields);
  if (type == "camera") return parse_camera(fields);
  if (type == "arm") return parse_arm(fields);
  if (type == "waypoints") return parse_waypoints(fields);
  return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, "unknown frame type \"" + type + "\""));
}

std::string format_frame(const ServerFrame& frame) {
  return std::visit([](const auto& f) { return to_json(f).dump(-1, ' ', false, json::error_handler_t::replace); },
                    frame);
}

std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t{bytes[i + 1]} << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace jaus::console
