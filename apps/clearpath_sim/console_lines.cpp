#include "console_lines.hpp"

#include <chrono>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace jaus::clearpath::sim::console {
namespace {

using Json = nlohmann::ordered_json;  // keys in the documented order

std::vector<std::string> words(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::int64_t steady_ns(rt::TimePoint at) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(at.time_since_epoch()).count();
}

}  // namespace

Line parse_line(std::string_view text) {
  const auto w = words(text);
  if (w.empty()) return Blank{};
  if (w.size() == 1 && w[0] == "status") return StatusNow{};
  if (w.size() == 2 && (w[0] == "estop" || w[0] == "pause") && (w[1] == "on" || w[1] == "off"))
    return Press{w[0] == "estop" ? HardwareInput::estop : HardwareInput::pause, w[1] == "on"};
  if (w.size() == 2 && w[0] == "deaf" && (w[1] == "on" || w[1] == "off")) return Deaf{w[1] == "on"};
  if (w.size() == 3 && (w[0] == "estop" || w[0] == "pause") && w[1] == "for" && !w[2].empty() && w[2].size() <= 5 &&
      w[2].find_first_not_of("0123456789") == std::string::npos) {
    const int ms = std::stoi(w[2]);
    if (ms >= 1 && ms <= 10000)
      return PressFor{w[0] == "estop" ? HardwareInput::estop : HardwareInput::pause, std::chrono::milliseconds(ms)};
  }
  // Without the line ending, which a terminal or a Windows editor may add.
  auto line = std::string(text);
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
  return Unknown{line};
}

const char* input_name(HardwareInput input) { return input == HardwareInput::estop ? "estop" : "pause"; }

std::string press_answer(const Press& press, std::uint16_t safety_flags) {
  return Json{{"input", input_name(press.input)}, {"on", press.on}, {"safety_flags", safety_flags}}.dump();
}

std::string deaf_answer(const Deaf& deaf) { return Json{{"deaf", deaf.on}}.dump(); }

std::string error_line(const Unknown& unknown) {
  // dump() escapes what the line holds and replaces invalid UTF-8.
  return Json{{"error", "unknown input line '" + unknown.line + "': expected estop on|off, pause on|off, estop|pause for MS, deaf on|off"}}.dump(
      -1, ' ', false, Json::error_handler_t::replace);
}

std::string status_line(const SimPlatform& platform, bool deaf) {
  const auto& v = platform.vehicle();
  const auto& c = platform.counters();
  return fmt::format(
      "{{\"status\":{{\"left_mps\":{:.3f},\"right_mps\":{:.3f},\"speed_mps\":{:.3f},"
      "\"yaw_rate_rps\":{:.3f},\"yaw_rad\":{:.3f},\"x_m\":{:.3f},\"y_m\":{:.3f},"
      "\"watchdog_expired\":{},\"safety_flags\":{},\"hardware_inputs\":{},\"commands_applied\":{},"
      "\"frames_rejected\":{},\"steering_percent\":{:.1f},\"deaf\":{}}}}}",
      v.left().speed, v.right().speed, v.linear_speed(), v.yaw_rate(), v.yaw(), v.x(), v.y(), v.watchdog_expired(),
      v.safety_flags(), v.hardware_inputs(), c.commands_applied, platform.parser_counters().errors(),
      v.ackermann_output()[0], deaf);
}

std::string event_line(const PlatformEvent& event) {
  Json j;
  switch (event.kind) {
    case PlatformEvent::Kind::zero_command: j["event"] = "zero_command"; break;
    case PlatformEvent::Kind::wheels_stopped: j["event"] = "wheels_stopped"; break;
    case PlatformEvent::Kind::safety:
      j["event"] = "safety";
      j["flags"] = event.flags;
      break;
    case PlatformEvent::Kind::input:
      j["event"] = "input";
      j["input"] = input_name(event.input);
      j["on"] = event.on;
      break;
  }
  j["steady_ns"] = steady_ns(event.at);
  return j.dump();
}

}  // namespace jaus::clearpath::sim::console
