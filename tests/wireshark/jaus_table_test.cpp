// The JAUS half of the Wireshark plugin is generated from the descriptions
// (apps/wireshark): every catalogue message and every field of it is in the
// Lua, and the enumeration and bit-field codecs (detected by
// enum_names()/flag_fields()) become value strings and bit fields. The tshark
// tests of this folder run the plugin.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>

#include "jaus/messages/catalogue.hpp"
#include "jaus_table.hpp"
#include "wireshark_plugin.hpp"

namespace jaus {
namespace {

// The message's line of the generated MESSAGES table.
std::string entry_of(const std::string& lua, std::uint16_t code) {
  char key[16];
  std::snprintf(key, sizeof key, "[0x%04X]={", code);
  const auto at = lua.find(key);
  if (at == std::string::npos) return {};
  return lua.substr(at, lua.find('\n', at) - at);
}

TEST(WiresharkLua, EveryCatalogueMessageAndEveryFieldIsInThePlugin) {
  const std::string lua = wireshark::jaus_tables_lua();
  std::size_t fields = 0;
  for (const auto& m : msg::catalogue(wire::Dialect::ra)) {
    const std::string entry = entry_of(lua, m.code);
    ASSERT_FALSE(entry.empty()) << m.name << " is missing";
    EXPECT_NE(entry.find("name=\"" + std::string(m.name) + "\""), std::string::npos) << entry;
    // fields_doc names each field in backquotes, nested records' fields included.
    const std::string doc = m.fields_doc();
    for (auto open = doc.find('`'); open != std::string::npos; open = doc.find('`', doc.find('`', open + 1) + 1)) {
      const auto name = doc.substr(open + 1, doc.find('`', open + 1) - open - 1);
      EXPECT_NE(entry.find("n=\"" + name + "\""), std::string::npos) << m.name << ": field " << name << " missing";
      ++fields;
    }
  }
  EXPECT_GT(fields, 300u);
}

TEST(WiresharkLua, ScaledFieldsCarryTheCodecsLimitsExactly) {
  const std::string entry = entry_of(wireshark::jaus_tables_lua(), 0x4402);  // Report Global Pose
  EXPECT_NE(entry.find("{n=\"latitude_deg\",bit=0,k=\"scaled\",s=4,signed=true,lo=-90,hi=90}"), std::string::npos)
      << entry;
  EXPECT_NE(entry.find("k=\"pv\",s=2"), std::string::npos) << entry;
  const std::string relative = entry_of(wireshark::jaus_tables_lua(), 0x4802);  // Report Relative Object Position
  EXPECT_NE(relative.find("only=\"openjaus\""), std::string::npos) << relative;
}

TEST(WiresharkLua, LuaStringsAreEscaped) { EXPECT_EQ(wireshark::lua_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\010\""); }

// Codecs shaped like the enumeration and bit-field codecs: the generator
// finds them by enum_names() and flag_fields() alone.
struct FakeName {
  std::uint32_t value;
  std::string_view name;
};
struct FakeBits {
  std::uint8_t first_bit;
  std::uint8_t width;
  std::string_view name;
  std::span<const FakeName> values{};
};
inline constexpr std::array<FakeName, 2> kModes{{{0, "off"}, {7, "auto"}}};
inline constexpr std::array<FakeName, 2> kLevels{{{1, "low"}, {2, "high"}}};
inline constexpr std::array<FakeBits, 2> kFlagFields{{{0, 1, "enabled", {}}, {4, 2, "level", kLevels}}};

struct FakeEnum : wire::Int<std::uint8_t> {
  constexpr std::span<const FakeName> enum_names() const { return kModes; }
};
struct FakeFlags : wire::Int<std::uint16_t> {
  constexpr std::span<const FakeBits> flag_fields() const { return kFlagFields; }
};

struct FakeBody {
  std::uint8_t mode = 0;
  std::uint16_t flags = 0;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("mode", &FakeBody::mode, FakeEnum{}),
                           wire::field("flags", &FakeBody::flags, FakeFlags{}));
  }
};

TEST(WiresharkLua, EnumerationsBecomeValueStringsAndBitFieldsBitmasks) {
  const std::string lua = wireshark::jaus_table::body_lua<FakeBody>();
  EXPECT_NE(lua.find("{n=\"mode\",k=\"int\",s=1,vs={[0]=\"off\",[7]=\"auto\",}}"), std::string::npos) << lua;
  EXPECT_NE(lua.find("{n=\"flags\",k=\"flags\",s=2,bits={{first=0,width=1,n=\"enabled\"},"
                     "{first=4,width=2,n=\"level\",vs={[1]=\"low\",[2]=\"high\",}},}}"),
            std::string::npos)
      << lua;
}

}  // namespace
}  // namespace jaus
