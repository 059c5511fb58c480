#include <gtest/gtest.h>

#include <set>

#include "jaus/messages/catalogue.hpp"
#include "message_types.hpp"

namespace jaus::msg {
namespace {

constexpr auto kRa = wire::Dialect::ra;

// The codes the RA 3.x Part 3 message set defines, plus the component control
// query/report, discovery and events of RA 3.2/3.3.
const std::vector<std::uint16_t> kRequiredCodes = {
    0x0001, 0x0002, 0x0003, 0x0004, 0x0005, 0x0006, 0x0007, 0x0008, 0x0009, 0x000A, 0x000B, 0x000C, 0x000D, 0x000E,
    0x000F, 0x0010, 0x0011, 0x0200, 0x0201, 0x0405, 0x0406, 0x0407, 0x0408, 0x040A, 0x040C, 0x040D, 0x040F, 0x0410,
    0x0601, 0x0602, 0x0603, 0x0604, 0x0605, 0x0606, 0x0607, 0x0608, 0x0801, 0x0802, 0x0805, 0x0806, 0x2001, 0x2002,
    0x2011, 0x2200, 0x2201, 0x2202, 0x2400, 0x2401, 0x2402, 0x2403, 0x2404, 0x2405, 0x2406, 0x2407, 0x2408, 0x240A,
    0x240B, 0x240C, 0x240D, 0x240E, 0x240F, 0x2410, 0x2600, 0x2601, 0x2602, 0x2603, 0x2604, 0x2605, 0x2800, 0x2801,
    0x2802, 0x2804, 0x2805, 0x2806, 0x2807, 0x4001, 0x4002, 0x4011, 0x4200, 0x4201, 0x4202, 0x4400, 0x4401, 0x4402,
    0x4403, 0x4404, 0x4405, 0x4406, 0x4407, 0x4408, 0x440A, 0x440B, 0x440C, 0x440D, 0x440E, 0x440F, 0x4410, 0x4600,
    0x4601, 0x4602, 0x4603, 0x4604, 0x4605, 0x4800, 0x4801, 0x4802, 0x4804, 0x4805, 0x4806, 0x4807,
    // beyond Part 3
    0x200D, 0x400D, 0x2B00, 0x2B01, 0x2B02, 0x2B03, 0x4B00, 0x4B01, 0x4B02, 0x4B03, 0x01F0, 0x01F1, 0x01F2, 0x01F3,
    0x41F1};

TEST(Catalogue, HoldsEveryMessageOfTheSetOnce) {
  EXPECT_EQ(kRequiredCodes.size(), 110u + 15u);
  for (auto code : kRequiredCodes) EXPECT_NE(find_message(kRa, code), nullptr) << std::hex << code;
  EXPECT_EQ(catalogue(kRa).size(), kRequiredCodes.size());
  std::set<std::string_view> names;
  for (const auto& m : catalogue(kRa)) {
    EXPECT_FALSE(m.name.empty());
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate name " << m.name;
  }
  EXPECT_TRUE(std::is_sorted(catalogue(kRa).begin(), catalogue(kRa).end(),
                             [](const auto& a, const auto& b) { return a.code < b.code; }));
}

TEST(Catalogue, EveryTypeAppearsUnderItsOwnCode) {
  std::size_t count = 0;
  test::for_each_message_type([&]<class M>() {
    ++count;
    const auto* info = find_message(kRa, M::code);
    ASSERT_NE(info, nullptr);
    EXPECT_EQ(info->name, M::name);
    EXPECT_EQ(find_message(kRa, M::name), info);
    EXPECT_EQ(find_message(kRa, info->type_name), info);
    EXPECT_EQ(info->set, kRa);
  });
  EXPECT_EQ(count, kRequiredCodes.size());
}

TEST(Catalogue, ClassAndSubgroupFollowTheCode) {
  EXPECT_EQ(find_message(kRa, 0x0405)->message_class, MessageClass::command);
  EXPECT_EQ(find_message(kRa, 0x2402)->message_class, MessageClass::query);
  EXPECT_EQ(find_message(kRa, 0x4402)->message_class, MessageClass::inform);
  EXPECT_EQ(find_message(kRa, 0x01F0)->message_class, MessageClass::command);
  EXPECT_EQ(to_string(message_class_of(kRa, 0x6000)), "event setup");
  EXPECT_EQ(to_string(message_class_of(kRa, 0xD000)), "node management");
  EXPECT_EQ(to_string(message_class_of(wire::Dialect::jss, 0xD000)), "command");  // JSS has three classes
  EXPECT_EQ(message_subgroup(0x4402), "platform");
  EXPECT_EQ(message_subgroup(0x0601), "manipulator");
  EXPECT_EQ(message_subgroup(0x4807), "environment sensor");
  EXPECT_EQ(message_subgroup(0x4202), "communications");
  EXPECT_EQ(message_subgroup(0x01F0), "core");
  EXPECT_EQ(message_subgroup(0x2B00), "discovery");
}

TEST(Catalogue, UnknownCodesAreNotFound) {
  EXPECT_EQ(find_message(kRa, 0x0000), nullptr);
  EXPECT_EQ(find_message(kRa, 0x4409), nullptr);
  EXPECT_EQ(find_message(kRa, "Report Nothing"), nullptr);
}

}  // namespace
}  // namespace jaus::msg
