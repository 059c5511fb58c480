// The fixed part of the Clearpath dissector: Lua that reads the generated
// tables CP_MESSAGES and CP_ACK and dissects frames with them.
#pragma once

#include <string_view>

namespace jaus::clearpath::wireshark {

std::string_view clearpath_lua_runtime();

}  // namespace jaus::clearpath::wireshark
