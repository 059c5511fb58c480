// Enumerations and bit fields by name (wire::Enum, wire::Flags): JSON shows
// names, accepts names or numbers, keeps unknown values visible as numbers,
// and the bytes are those of the plain integer.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "jaus/base/hex.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/messages/catalogue.hpp"

namespace jaus::msg {
namespace {

using Json = nlohmann::ordered_json;

Json decode_fields(const std::string& hex) {
  const auto bytes = parse_hex(hex);
  EXPECT_TRUE(bytes) << bytes.error().message();
  auto json = message_to_json(bytes ? *bytes : Bytes{});
  EXPECT_TRUE(json) << json.error().message();
  return json ? (*json)["fields"] : Json();
}

std::string encode_hex(const Json& message) {
  auto bytes = message_from_json(message);
  EXPECT_TRUE(bytes) << bytes.error().message();
  return bytes ? to_hex(*bytes) : "";
}

std::string encode_error(const Json& message) {
  auto bytes = message_from_json(message);
  EXPECT_FALSE(bytes);
  return bytes ? "" : bytes.error().message();
}

// A Report Discrete Devices from the RA 3.3 peer's vectors (tests/data):
// presence 0x0F, main propulsion 0x2D, brake and horn 0x03, gear 131, transfer case 2.
constexpr const char* kDiscreteDevices = "06020644012101010128010205000B0A0F2D038302";

TEST(NamedValues, DiscreteDevicesShowTheirBitsAndGearsByName) {
  const Json fields = decode_fields(kDiscreteDevices);
  EXPECT_EQ(fields["main_propulsion"],
            Json::parse(R"({"power_plant_on":true,"main_fuel_on":false,"auxiliary_fuel_on":true,
                            "auxiliary_devices_power_on":true,"starting_device_on":false,"cold_start":true,
                            "automatic_start":false,"automatic_shutdown":false})"));
  EXPECT_EQ(fields["parking_brake_and_horn"], Json::parse(R"({"parking_brake_set":true,"horn_on":true})"));
  EXPECT_EQ(fields["gear"], 131);         // a reverse gear: a range, not a name
  EXPECT_EQ(fields["transfer_case"], 2);  // low range
  // And back to the same bytes: the whole decoded message, header included.
  const auto bytes = parse_hex(kDiscreteDevices);
  ASSERT_TRUE(bytes);
  auto message = message_to_json(*bytes);
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["fields"], fields);
  EXPECT_EQ(encode_hex(*message), kDiscreteDevices);
}

TEST(NamedValues, NamedGearsAndMissingBitsReadAsOff) {
  const Json named{
      {"code", "0x0406"},
      {"fields", {{"main_propulsion", {{"power_plant_on", true}}}, {"gear", "neutral"}, {"transfer_case", "neutral"}}}};
  const Json numbers{{"code", "0x0406"}, {"fields", {{"main_propulsion", 1}, {"gear", 128}, {"transfer_case", 128}}}};
  EXPECT_EQ(encode_hex(named), encode_hex(numbers));
  EXPECT_EQ(encode_hex(named).substr(32),
            "0D"
            "01"
            "80"
            "80");
  auto bytes = message_from_json(named);
  ASSERT_TRUE(bytes);
  auto json = message_to_json(*bytes);
  ASSERT_TRUE(json);
  EXPECT_EQ((*json)["fields"]["gear"], "neutral");
  EXPECT_EQ((*json)["fields"]["main_propulsion"]["power_plant_on"], true);
  EXPECT_EQ((*json)["fields"]["main_propulsion"]["cold_start"], false);
}

TEST(NamedValues, EnumsRoundTripByNameAndByNumber) {
  // Report Component Status: primary status 1 (ready), secondary 0.
  const std::string hex = to_hex(
      *message_from_json(Json{{"code", "0x4002"}, {"fields", {{"primary_status", 1}, {"secondary_status", 0}}}}));
  const Json by_name{{"code", "0x4002"}, {"fields", {{"primary_status", "ready"}, {"secondary_status", 0}}}};
  EXPECT_EQ(encode_hex(by_name), hex);
  EXPECT_EQ(hex.substr(32),
            "01"
            "00000000");  // exactly the byte of an Int<u8>
  EXPECT_EQ(decode_fields(hex)["primary_status"], "ready");

  // Every value of every shared table, both ways.
  for (const auto& [value, name] : kComponentStates) {
    const Json by_number{{"code", "0x4002"}, {"fields", {{"primary_status", value}, {"secondary_status", 0}}}};
    const Json named{{"code", "0x4002"}, {"fields", {{"primary_status", name}, {"secondary_status", 0}}}};
    EXPECT_EQ(encode_hex(by_number), encode_hex(named)) << name;
    EXPECT_EQ(decode_fields(encode_hex(by_number))["primary_status"], std::string(name));
  }
  for (const auto& [value, name] : kImageFormats) {
    const Json named{{"code", "0x0806"}, {"fields", {{"camera_id", 1}, {"image_format", name}}}};
    EXPECT_EQ(decode_fields(encode_hex(named))["image_format"], std::string(name));
    EXPECT_EQ(encode_hex(named).substr(36), to_hex(std::vector<std::uint8_t>{static_cast<std::uint8_t>(value)}));
  }
}

TEST(NamedValues, UnknownValuesStayNumbers) {
  // Primary status 0x21: "ready" with an available bit set, which no name covers.
  const Json odd{{"code", "0x4002"}, {"fields", {{"primary_status", 0x21}, {"secondary_status", 0}}}};
  EXPECT_EQ(decode_fields(encode_hex(odd))["primary_status"], 0x21);
  // Confirm Service Connection response 9 (reserved).
  const Json reserved{
      {"code", "0x0009"},
      {"fields", {{"command_code", 0x4402}, {"instance_id", 0}, {"confirmed_rate_hz", 0}, {"response_code", 9}}}};
  EXPECT_EQ(decode_fields(encode_hex(reserved))["response_code"], 9);
  // Emergency code with a reserved bit: the named bit and the rest.
  const Json emergency{{"code", "0x0006"}, {"fields", {{"emergency_code", 0x8003}}}};
  const Json fields = decode_fields(encode_hex(emergency));
  EXPECT_EQ(fields["emergency_code"], Json::parse(R"({"stop":true,"other_bits":32770})"));
  const Json back{{"code", "0x0006"}, {"fields", fields}};
  EXPECT_EQ(encode_hex(back), encode_hex(emergency));
}

TEST(NamedValues, BadNamesAreRejectedNamingTheFieldAndTheValidNames) {
  const std::string status =
      encode_error(Json{{"code", "0x4002"}, {"fields", {{"primary_status", "redy"}, {"secondary_status", 0}}}});
  EXPECT_NE(status.find("'primary_status': unknown name 'redy'"), std::string::npos) << status;
  EXPECT_NE(status.find("initialize, ready, standby, shutdown, failure, emergency"), std::string::npos) << status;

  const std::string bit = encode_error(
      Json{{"code", "0x0805"}, {"fields", {{"camera_id", 1}, {"imagery_control", {{"autofocus", true}}}}}});
  EXPECT_NE(bit.find("'imagery_control': unknown bit field 'autofocus'"), std::string::npos) << bit;
  EXPECT_NE(bit.find("auto_focus, auto_exposure_iris"), std::string::npos) << bit;

  const std::string not_bool = encode_error(
      Json{{"code", "0x0805"}, {"fields", {{"camera_id", 1}, {"imagery_control", {{"auto_focus", "yes"}}}}}});
  EXPECT_NE(not_bool.find("'auto_focus': expected true or false"), std::string::npos) << not_bool;

  const std::string overlap =
      encode_error(Json{{"code", "0x0006"}, {"fields", {{"emergency_code", {{"other_bits", 1}}}}}});
  EXPECT_NE(overlap.find("'other_bits' overlaps the named bits"), std::string::npos) << overlap;

  const std::string too_big = encode_error(Json{{"code", "0x0406"}, {"fields", {{"gear", 256}}}});
  EXPECT_NE(too_big.find("'gear'"), std::string::npos) << too_big;

  const std::string wrong_type = encode_error(Json{{"code", "0x0406"}, {"fields", {{"gear", true}}}});
  EXPECT_NE(wrong_type.find("'gear': expected a name (park, neutral) or a number"), std::string::npos) << wrong_type;
}

TEST(NamedValues, CameraControlsAndPoseModesByName) {
  const Json set{{"code", "0x0805"},
                 {"fields",
                  {{"camera_id", 2},
                   {"imagery_control", {{"auto_focus", true}, {"auto_gain", true}, {"non_interlaced", true}}},
                   {"audio_control", {{"audio", true}, {"stereo", true}}}}}};
  const Json fields = decode_fields(encode_hex(set));
  EXPECT_EQ(fields["imagery_control"]["auto_focus"], true);
  EXPECT_EQ(fields["imagery_control"]["white_balance"], false);
  EXPECT_EQ(fields["imagery_control"]["non_interlaced"], true);
  EXPECT_FALSE(fields["imagery_control"].contains("other_bits"));
  EXPECT_EQ(fields["audio_control"]["stereo"], true);
  // Bits 0, 7 and 8; bits 0 and 2.
  const Json numbers{{"code", "0x0805"},
                     {"fields", {{"camera_id", 2}, {"imagery_control", 0x181}, {"audio_control", 5}}}};
  EXPECT_EQ(encode_hex(set), encode_hex(numbers));

  const Json pose{{"code", "0x0801"}, {"fields", {{"camera_id", 1}, {"mode_indicator", {{"z_angular_rate", true}}}}}};
  EXPECT_EQ(decode_fields(encode_hex(pose))["mode_indicator"]["z_angular_rate"], true);
  const Json pose_number{{"code", "0x0801"}, {"fields", {{"camera_id", 1}, {"mode_indicator", 0x20}}}};
  EXPECT_EQ(encode_hex(pose), encode_hex(pose_number));
}

TEST(NamedValues, EventTypesBoundariesAndLimitTypesByName) {
  const Json create{{"code", "0x01F0"},
                    {"fields",
                     {{"request_id", 1},
                      {"report_code", 0x4402},
                      {"event_type", "every_change"},
                      {"event_boundary", "outside_inclusive"},
                      {"limit_data_field", 1},
                      {"lower_limit", {{"type", "unsigned_short"}, {"bits", 300}}},
                      {"query_message", "0100"}}}};
  const Json numbers{{"code", "0x01F0"},
                     {"fields",
                      {{"request_id", 1},
                       {"report_code", 0x4402},
                       {"event_type", 1},
                       {"event_boundary", 4},
                       {"limit_data_field", 1},
                       {"lower_limit", {{"type", 4}, {"bits", 300}}},
                       {"query_message", "0100"}}}};
  EXPECT_EQ(encode_hex(create), encode_hex(numbers));
  const Json fields = decode_fields(encode_hex(numbers));
  EXPECT_EQ(fields["event_type"], "every_change");
  EXPECT_EQ(fields["event_boundary"], "outside_inclusive");
  EXPECT_EQ(fields["lower_limit"], Json::parse(R"({"type":"unsigned_short","bits":300})"));

  Json bad = create;
  bad["fields"]["lower_limit"]["type"] = "short";
  const std::string why = encode_error(bad);
  EXPECT_NE(why.find("'lower_limit': unknown event limit type 'short'"), std::string::npos) << why;
}

// A wider bit field, with and without value names, through the codec itself.
inline constexpr std::array<wire::NamedValue, 2> kModes{{{0, "off"}, {3, "auto"}}};
inline constexpr auto kWide =
    wire::flags_of<std::uint16_t>({{0, 1, "enabled"}, {4, 4, "mode", kModes}, {8, 3, "level"}});

TEST(NamedValues, WiderBitFieldsAreNumbersOrTheirNames) {
  EXPECT_EQ(kWide.to_json<Json>(0x0531), Json::parse(R"({"enabled":true,"mode":"auto","level":5})"));
  EXPECT_EQ(kWide.to_json<Json>(0x8050), Json::parse(R"({"enabled":false,"mode":5,"level":0,"other_bits":32768})"));
  std::uint16_t v = 0;
  // The reason a JSON value is refused: ErrorCode::json, its detail the words.
  const auto refusal = [&](const Json& j) {
    const auto r = kWide.from_json(j, v);
    EXPECT_FALSE(r);
    if (r) return std::string();
    EXPECT_EQ(r.error().code, ErrorCode::json);
    return r.error().detail;
  };
  auto r = kWide.from_json(Json::parse(R"({"mode":"auto","level":7})"), v);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(v, 0x0730);
  r = kWide.from_json(Json::parse(R"({"mode":9})"), v);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(v, 0x0090);
  r = kWide.from_json(Json(0x1234), v);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(v, 0x1234);
  EXPECT_EQ(refusal(Json::parse(R"({"level":8})")), "'level': 8 does not fit (at most 7)");
  EXPECT_EQ(refusal(Json::parse(R"({"mode":"manual"})")),
            "'mode': unknown name 'manual' (expected one of: off, auto, or a number)");
  EXPECT_EQ(refusal(Json("enabled")), "expected an object {enabled, mode, level, other_bits} or a number");
  // The walkers' view of the description.
  ASSERT_EQ(kWide.flag_fields().size(), 3u);
  EXPECT_EQ(kWide.flag_fields()[1].width, 4);
  EXPECT_EQ(kWide.flag_fields()[1].values.size(), 2u);
  EXPECT_EQ(kWide.doc(), "u16 bits: bit 0 enabled, bits 4-7 mode (0 off, 3 auto), bits 8-10 level");
}

TEST(NamedValues, DocumentationListsTheNames) {
  const MessageInfo* status = find_message(wire::Dialect::ra, 0x4002);
  ASSERT_NE(status, nullptr);
  EXPECT_NE(status->fields_doc().find("`primary_status`: u8 enum: 0 initialize, 1 ready, 2 standby"), std::string::npos)
      << status->fields_doc();
  const MessageInfo* devices = find_message(wire::Dialect::ra, 0x0406);
  ASSERT_NE(devices, nullptr);
  EXPECT_NE(devices->fields_doc().find("u8 bits: bit 0 power_plant_on, bit 1 main_fuel_on"), std::string::npos)
      << devices->fields_doc();
  static_assert(kServiceConnectionResponse.enum_names().size() == 7);
  static_assert(kServiceConnectionResponse.enum_names()[3].name == "insufficient_authority");
}

}  // namespace
}  // namespace jaus::msg
