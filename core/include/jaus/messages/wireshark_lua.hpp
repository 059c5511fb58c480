// The JAUS part of the Wireshark Lua plugin, generated from the message
// descriptions (wireshark_fields.hpp), so the dissector knows every message
// the codec knows, field for field. Used by `jausctl msg wireshark`, which
// adds the Clearpath part and writes the plugin (docs/wireshark.md); not on
// any hot path.
#pragma once

#include <string>

namespace jaus::msg {

// A self-contained Lua chunk registering the protocol "jaus" (UDP port 3794
// and a heuristic for the OPC and JUDP framings): header, every message body
// by name with its fields in engineering units, large data sets, messages
// inside events, preferences (dialect, port).
std::string wireshark_lua();

}  // namespace jaus::msg
