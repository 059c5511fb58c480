// The plugin: the generated tables around the fixed Lua of lua/, which the
// build embeds (embed_lua.cmake: embedded_lua.hpp).
#include "embedded_lua.hpp"
#include "wireshark_plugin.hpp"

namespace jaus::wireshark {

std::string plugin_lua() {
  std::string out =
      "-- JAUS RA 3.x, SAE JAUS (AS5669A) and Clearpath over UDP: generated from the message descriptions and "
      "apps/wireshark/lua/ by `jausctl msg wireshark`; do not edit.\n";
  out += embedded::prelude_lua;
  // Each half in a block of its own, so its locals do not meet the other's.
  out += "\n-- JAUS RA 3.x and SAE JAUS (AS5669A)\ndo\n" + jaus_tables_lua() + jss_tables_lua();
  out += embedded::jaus_lua;
  out += embedded::jss_lua;
  out += embedded::register_lua;
  out += "end\n\n-- Clearpath over UDP\ndo\n" + clearpath_tables_lua();
  out += embedded::clearpath_lua;
  out += "end\n";
  return out;
}

}  // namespace jaus::wireshark
