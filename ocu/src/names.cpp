#include "jaus/ocu/names.hpp"

#include <cstdio>

#include "jaus/core/component_ids.hpp"
#include "jaus/runtime/lifecycle.hpp"

namespace jaus::ocu {

std::string component_kind(std::uint8_t id) {
  if (const std::string_view name = component_id::ra_name(id); !name.empty()) return std::string(name);
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
