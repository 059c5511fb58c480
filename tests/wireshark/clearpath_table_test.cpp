// The Clearpath half of the Wireshark plugin is generated from the
// descriptions (apps/wireshark): every type of the catalogue with its name and
// kind, the ACK, and a layout chosen by payload size where decoding does so
// (Change Gear).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "jaus/clearpath/messages.hpp"
#include "wireshark_plugin.hpp"

namespace jaus::clearpath {
namespace {

TEST(ClearpathWiresharkLua, EveryTypeOfTheCatalogueIsInThePlugin) {
  const std::string lua = jaus::wireshark::clearpath_tables_lua();
  for (const auto& info : message_catalogue()) {
    char key[64];
    std::snprintf(key, sizeof key, "[0x%04X]={name=\"", info.type);
    const auto at = lua.find(key);
    ASSERT_NE(at, std::string::npos) << info.name;
    const auto entry = lua.substr(at, lua.find('\n', at) - at);
    EXPECT_NE(entry.find("name=\"" + std::string(info.name) + "\",kind=\"" + std::string(to_string(info.kind)) + "\""),
              std::string::npos)
        << entry;
  }
  EXPECT_NE(lua.find("local CP_ACK = {{k=\"num\",n=\"result\",s=2},}"), std::string::npos);
}

TEST(ClearpathWiresharkLua, FieldsCarryTheirWireTypeAndScale) {
  const std::string lua = jaus::wireshark::clearpath_tables_lua();
  // 0x0204 Set Velocity: i16 m/s x 100.
  EXPECT_NE(lua.find("{k=\"num\",n=\"translational\",s=2,signed=true,scale=100,unit=\"m/s\"}"), std::string::npos);
  // 0x0212 Change Gear: two bytes are [flags, gear].
  const auto gear = lua.substr(lua.find("[0x0212]="), 400);
  EXPECT_NE(gear.find("by_size={[2]={{k=\"flag\",n=\"with_flags\",v=true},{k=\"num\",n=\"flags\",s=1}"),
            std::string::npos)
      << gear;
}

}  // namespace
}  // namespace jaus::clearpath
