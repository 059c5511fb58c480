// The fixed part of the JAUS dissector: Lua that reads the generated table
// MESSAGES (code -> name and body description) and dissects with it.
#pragma once

#include <string_view>

namespace jaus::msg::wireshark {

std::string_view jaus_lua_runtime();

}  // namespace jaus::msg::wireshark
