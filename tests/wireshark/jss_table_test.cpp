// The JSS table of the plugin is generated from the JSS descriptions: every
// message of the JSS catalogue and every field of it is in the Lua, with the
// JSS codec kinds (str8, embedded messages, tagged variants, body JSS IDs)
// and unsigned scaled limits.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "jaus/jss/catalogue.hpp"
#include "wireshark_plugin.hpp"

namespace jaus {
namespace {

std::string jss_entry_of(const std::string& lua, std::uint16_t id) {
  char key[16];
  std::snprintf(key, sizeof key, "[0x%04X]={", id);
  const auto at = lua.find(key);
  if (at == std::string::npos) return {};
  return lua.substr(at, lua.find('\n', at) - at);
}

TEST(WiresharkJssLua, EveryJssMessageAndEveryFieldIsInThePlugin) {
  const std::string lua = wireshark::jss_tables_lua();
  ASSERT_EQ(lua.rfind("local JSS_MESSAGES = {\n", 0), 0u);
  std::size_t fields = 0;
  for (const auto& m : msg::catalogue(wire::Dialect::jss)) {
    const std::string entry = jss_entry_of(lua, m.code);
    ASSERT_FALSE(entry.empty()) << m.name << " is missing";
    EXPECT_NE(entry.find("name=\"" + std::string(m.name) + "\""), std::string::npos) << entry;
    const std::string doc = m.fields_doc();
    for (auto open = doc.find('`'); open != std::string::npos; open = doc.find('`', doc.find('`', open + 1) + 1)) {
      const auto name = doc.substr(open + 1, doc.find('`', open + 1) - open - 1);
      EXPECT_NE(entry.find("n=\"" + name + "\""), std::string::npos) << m.name << ": field " << name << " missing";
      ++fields;
    }
  }
  EXPECT_GT(fields, 150u);
}

TEST(WiresharkJssLua, JssCodecKindsAndUnsignedScaledLimits) {
  const std::string lua = wireshark::jss_tables_lua();
  EXPECT_NE(jss_entry_of(lua, 0x0405).find("{n=\"propulsive_linear_effort_x_percent\",bit=0,k=\"scaled\",s=2,lo=-100,hi=100}"),
            std::string::npos);
  EXPECT_NE(jss_entry_of(lua, 0x4B00).find("{n=\"identification\",k=\"str8\"}"), std::string::npos);
  EXPECT_NE(jss_entry_of(lua, 0x41F1).find("{n=\"report_message\",k=\"embedded\",size=4,min=2}"), std::string::npos);
  EXPECT_NE(jss_entry_of(lua, 0x041A).find("{n=\"element_data\",k=\"embedded\",size=2,min=0}"), std::string::npos);
  EXPECT_NE(jss_entry_of(lua, 0x400D).find("{n=\"controller\",k=\"jssid\",s=4}"), std::string::npos);
  EXPECT_NE(jss_entry_of(lua, 0x21F0).find("k=\"tagged\",alts={[0]={n=\"message_id\",s=2},"), std::string::npos)
      << jss_entry_of(lua, 0x21F0);
}

TEST(WiresharkJssLua, TheJausHalfCarriesTheJssTableAndItsDissector) {
  const std::string plugin = wireshark::plugin_lua();
  const auto tables = plugin.find(wireshark::jss_tables_lua());
  const auto jaus_lua = plugin.find("local jaus = Proto(\"jaus\"");
  const auto jss_lua = plugin.find("dissect_as5669a = function");
  const auto clearpath = plugin.find("local cp = Proto(\"clearpath\"");
  ASSERT_NE(tables, std::string::npos);
  EXPECT_LT(tables, jaus_lua);
  EXPECT_LT(jaus_lua, jss_lua);
  EXPECT_LT(jss_lua, clearpath);
}

}  // namespace
}  // namespace jaus
