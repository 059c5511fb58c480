#include "jaus/ocu/names.hpp"

#include <cstdio>
#include <map>

#include "jaus/runtime/lifecycle.hpp"

namespace jaus::ocu {

std::string component_kind(std::uint8_t id) {
  // RA 3.x component IDs (docs/wire-format.md, "Component IDs").
  static const std::map<std::uint8_t, const char*> kinds = {
      {1, "node manager"},           {32, "subsystem commander"},       {33, "primitive driver"},
      {34, "global vector driver"},  {35, "communicator"},              {36, "mission spooler"},
      {37, "visual sensor"},         {38, "global pose sensor"},        {39, "mission planner"},
      {40, "system commander"},      {41, "local pose sensor"},         {42, "velocity state sensor"},
      {43, "reflexive driver"},      {44, "local vector driver"},       {45, "global waypoint driver"},
      {46, "local waypoint driver"}, {47, "global path segment driver"}, {48, "local path segment driver"},
      {49, "primitive manipulator"}, {50, "range sensor"},              {61, "world model vector knowledge store"}};
  if (const auto it = kinds.find(id); it != kinds.end()) return it->second;
  if (id >= 51 && id <= 59) return "manipulator sensor/driver";
  return "component " + std::to_string(id);
}

std::string identification_class(std::uint16_t type) {
  if (type >= 50001) return "payload";
  if (type >= 40001) return "node";
  if (type >= 30001) return "other subsystem";
  if (type >= 20001) return "OCU";
  if (type >= 10001) return "vehicle";
  return "unspecified";
}

std::string control_response_text(std::uint8_t code) {
  switch (code) {
    case 0: return "granted";
    case 1: return "not supported";
    case 2: return "not available";
    default: return "response " + std::to_string(code);
  }
}

std::string service_connection_response_text(std::uint8_t code) {
  switch (code) {
    case 0: return "created";
    case 1: return "node not capable";
    case 2: return "component not capable";
    case 3: return "insufficient authority";
    case 4: return "refused";
    case 5: return "invalid parameters";
    case 6: return "command not supported";
    default: return "response " + std::to_string(code);
  }
}

std::string primary_status_text(std::uint8_t primary_status) {
  const unsigned code = primary_status & 0x0F;
  if (code > static_cast<unsigned>(jaus::msg::PrimaryStatus::emergency)) return "unknown (" + std::to_string(code) + ")";
  return std::string(jaus::rt::to_string(static_cast<jaus::msg::PrimaryStatus>(code)));
}

std::string seconds_text(jaus::rt::Duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", std::chrono::duration<double>(d).count());
  return text;
}

std::string elapsed_text(jaus::rt::Duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", std::chrono::duration<double>(d).count());
  return text;
}

std::string code_text(std::uint16_t code) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", code);
  return text;
}

std::string hz_text(double hz) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", hz);
  std::string out = text;
  // Scaled rates come back a hair off (5 Hz travels as 4.9989): the decimals that say nothing go.
  while (out.back() == '0') out.pop_back();
  if (out.back() == '.') out.pop_back();
  return out;
}

}  // namespace jaus::ocu
