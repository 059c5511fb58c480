// The Wireshark Lua plugin for JAUS RA 3.x and Clearpath over UDP, generated
// from the message descriptions of jaus_core and jaus_clearpath, so the
// dissector knows every message the codecs know, field for field
// (docs/wireshark.md). Out of the codecs: only an app may combine the two
// (docs/architecture.md). Used by `jausctl msg wireshark` and by the build
// (jaus_wireshark_gen writes wireshark/jaus.lua); not on any hot path.
#pragma once

#include <string>

namespace jaus::wireshark {

// The whole plugin, one Lua file: the shared prelude (lua/prelude.lua), then
// in a block each the JAUS half (its tables, RA and JSS, and lua/jaus.lua:
// protocol "jaus", UDP port 3794 and a heuristic for the OPC, JUDP and
// AS5669A framings) and the
// Clearpath half (its tables and lua/clearpath.lua: protocol "clearpath", a
// heuristic on the frame's AA/LEN/~LEN/55 and a port preference).
std::string plugin_lua();

// The generated parts, which the fixed Lua reads:
// "local MESSAGES = {\n[0x4402]={name=...,body={...}},\n...}\n" (jaus_table.hpp);
std::string jaus_tables_lua();
// "local JSS_MESSAGES = {\n[0x4B00]={name=...,body={...}},\n...}\n": the JSS
// messages (AS5669A, version byte 0x02), in the JAUS half (jss_table.cpp);
std::string jss_tables_lua();
// "local CP_MESSAGES = {\n[0x0204]={name=...,kind=...,body={...}},\n...}\nlocal CP_ACK = {...}\n"
// (clearpath_table.hpp).
std::string clearpath_tables_lua();

}  // namespace jaus::wireshark
