// Lua literals for the generated tables of the plugin (jaus_table.hpp,
// clearpath_table.hpp).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace jaus::wireshark {

// A Lua string literal (quotes, backslashes and control bytes escaped).
inline std::string lua_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\%03u", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Enough digits that Lua reads back the same double (limits must match the codec's).
inline std::string lua_number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace jaus::wireshark
