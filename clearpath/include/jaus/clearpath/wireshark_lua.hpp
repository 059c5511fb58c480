// The Clearpath part of the Wireshark Lua plugin, generated from the message
// descriptions (each message's describe(), walked by a visitor like the
// codec's), so the dissector knows every type the codec knows. Used by
// `jausctl msg wireshark` (docs/wireshark.md); not on any hot path.
#pragma once

#include <string>

namespace jaus::clearpath {

// A self-contained Lua chunk registering the protocol "clearpath" over UDP (a
// heuristic on the frame's AA/LEN/~LEN/55 and a port preference): frame
// header, type by name, payload fields in engineering units, CRC checked.
std::string wireshark_lua();

}  // namespace jaus::clearpath
