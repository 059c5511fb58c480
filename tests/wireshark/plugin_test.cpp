// The plugin is one shared prelude, then the JAUS half and the Clearpath half,
// each its generated tables and its fixed Lua (apps/wireshark/lua) in a block
// of its own; the prelude's Lua is written once.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "wireshark_plugin.hpp"

namespace jaus::wireshark {
namespace {

std::size_t count(const std::string& text, std::string_view what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(WiresharkPlugin, OnePreludeThenEachHalfInABlockOfItsOwn) {
  const std::string lua = plugin_lua();
  const auto prelude = lua.find("local function field_registry()");
  const auto jaus_half = lua.find("do\n" + jaus_tables_lua());
  const auto jaus_proto = lua.find("local jaus = Proto(\"jaus\"");
  const auto clearpath_half = lua.find("do\n" + clearpath_tables_lua());
  const auto clearpath_proto = lua.find("local cp = Proto(\"clearpath\"");
  ASSERT_NE(prelude, std::string::npos);
  ASSERT_NE(jaus_half, std::string::npos);
  ASSERT_NE(clearpath_half, std::string::npos);
  EXPECT_LT(prelude, jaus_half);
  EXPECT_LT(jaus_half, jaus_proto);
  EXPECT_LT(jaus_proto, clearpath_half);
  EXPECT_LT(clearpath_half, clearpath_proto);
  EXPECT_EQ(count(lua, "local bit32 = "), 1u);
  EXPECT_EQ(count(lua, "ProtoField.new("), 1u);
  EXPECT_EQ(count(lua, "DissectorTable.get(\"udp.port\")"), 1u);
  EXPECT_EQ(count(lua, "register_udp(jaus, heuristic)"), 1u);
  EXPECT_EQ(count(lua, "register_udp(cp, heuristic)"), 1u);
  EXPECT_EQ(lua.substr(lua.size() - 4), "end\n");
}

}  // namespace
}  // namespace jaus::wireshark
