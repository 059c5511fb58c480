// Clearpath fields a person reads by name: 0x8003's packed firmware write time
// as "YYYY-MM-DDTHH:MM" and the gear's park/neutral, both ways; values without
// such a form stay numbers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/message_json.hpp"
#include "jaus/clearpath/packed_date_time.hpp"

namespace cp = jaus::clearpath;
using Json = nlohmann::json;

namespace {

// 2024-03-05 14:07: minute 7, hour 14 << 6, day 5 << 11, month 3 << 17, year 24 << 21.
constexpr std::uint32_t kWriteTime = 7u | 14u << 6 | 5u << 11 | 3u << 17 | 24u << 21;

Json fields_of(const cp::AnyMessage& m) { return cp::fields_to_json(m); }

jaus::Expected<cp::AnyMessage> from_fields(const cp::AnyMessage& prototype, const Json& fields) {
  return cp::message_from_json(prototype, fields);
}

TEST(ClearpathPackedDateTime, PacksAndUnpacksThePartsOfTheDocument) {
  EXPECT_EQ(cp::pack_date_time({2024, 3, 5, 14, 7}), kWriteTime);
  ASSERT_TRUE(cp::unpack_date_time(kWriteTime));
  EXPECT_EQ(*cp::unpack_date_time(kWriteTime), (cp::DateTimeParts{2024, 3, 5, 14, 7}));
  EXPECT_EQ(cp::pack_date_time({2127, 12, 31, 23, 59}), 0x0FF8FDFBu);
  EXPECT_FALSE(cp::pack_date_time({2024, 13, 5, 14, 7}));
  EXPECT_FALSE(cp::unpack_date_time(0));                      // month 0, day 0
  EXPECT_FALSE(cp::unpack_date_time(kWriteTime | 60));        // minute 63
  EXPECT_FALSE(cp::unpack_date_time(kWriteTime | 1u << 28));  // an unused bit
  EXPECT_EQ(cp::format_date_time({2024, 3, 5, 14, 7}), "2024-03-05T14:07");
  EXPECT_EQ(cp::parse_date_time("2024-03-05T14:07"), (cp::DateTimeParts{2024, 3, 5, 14, 7}));
  for (const char* bad : {"2024-3-05T14:07", "2024-03-05 14:07", "1999-03-05T14:07", "2024-03-32T14:07",
                          "2024-03-05T24:00", "2024-03-05T14:07:00", "2024-03-05T1a:07"})
    EXPECT_FALSE(cp::parse_date_time(bad)) << bad;
}

TEST(ClearpathPackedDateTime, FirmwareWriteTimeIsADateInJsonBothWays) {
  cp::FirmwareInfo info;
  info.firmware_major = 1;
  info.write_time = kWriteTime;
  const Json fields = fields_of(info);
  EXPECT_EQ(fields["write_time"], "2024-03-05T14:07");

  auto back = from_fields(cp::FirmwareInfo{}, fields);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->get<cp::FirmwareInfo>().write_time, kWriteTime);

  // The raw number is still accepted.
  Json by_number = fields;
  by_number["write_time"] = kWriteTime;
  back = from_fields(cp::FirmwareInfo{}, by_number);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->get<cp::FirmwareInfo>().write_time, kWriteTime);

  // The bytes on the wire: the u32, little-endian, after the four version bytes.
  const auto payload = cp::encode_payload(cp::AnyMessage{info});
  ASSERT_TRUE(payload);
  EXPECT_EQ(*payload, (std::vector<std::uint8_t>{1, 0, 0, 0, 0x87, 0x2B, 0x06, 0x03}));
}

TEST(ClearpathPackedDateTime, AnInvalidPackedValueStaysVisibleAsItsNumber) {
  cp::FirmwareInfo info;
  info.write_time = 0xFFFFFFFF;
  const Json fields = fields_of(info);
  EXPECT_EQ(fields["write_time"], 0xFFFFFFFFu);
  auto back = from_fields(cp::FirmwareInfo{}, fields);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->get<cp::FirmwareInfo>().write_time, 0xFFFFFFFFu);
  // Out of the document's ranges, which the range check (encode, simulator) reports.
  const auto range = cp::check_ranges(cp::AnyMessage{info});
  ASSERT_FALSE(range);
  EXPECT_NE(range.error().message().find("write_time"), std::string::npos) << range.error().message();
  EXPECT_TRUE(cp::check_ranges(cp::AnyMessage{cp::FirmwareInfo{0, 0, 0, 0, kWriteTime}}));
}

TEST(ClearpathPackedDateTime, BadTextIsRejectedNamingTheField) {
  Json fields = fields_of(cp::FirmwareInfo{});
  fields["write_time"] = "2024-02-30 10:00";
  const auto back = from_fields(cp::FirmwareInfo{}, fields);
  ASSERT_FALSE(back);
  EXPECT_NE(back.error().message().find("write_time"), std::string::npos) << back.error().message();
  EXPECT_NE(back.error().message().find("YYYY-MM-DDTHH:MM"), std::string::npos) << back.error().message();
}

TEST(ClearpathGear, ParkAndNeutralByNameOtherGearsByNumber) {
  cp::GearData gear;
  gear.gear = -1;
  EXPECT_EQ(fields_of(gear)["gear"], "park");
  gear.gear = 0;
  EXPECT_EQ(fields_of(gear)["gear"], "neutral");
  gear.gear = 3;
  EXPECT_EQ(fields_of(gear)["gear"], 3);
  gear.gear = -2;
  EXPECT_EQ(fields_of(gear)["gear"], -2);

  auto change = from_fields(cp::ChangeGear{}, Json{{"gear", "park"}});
  ASSERT_TRUE(change) << change.error().message();
  EXPECT_EQ(change->get<cp::ChangeGear>().gear, -1);
  change = from_fields(cp::ChangeGear{}, Json{{"gear", -3}});
  ASSERT_TRUE(change) << change.error().message();
  EXPECT_EQ(change->get<cp::ChangeGear>().gear, -3);

  const auto bad = from_fields(cp::ChangeGear{}, Json{{"gear", "reverse"}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message().find("gear"), std::string::npos) << bad.error().message();
  EXPECT_NE(bad.error().message().find("unknown name 'reverse' (expected one of: park, neutral, or a number)"),
            std::string::npos)
      << bad.error().message();
}

}  // namespace
