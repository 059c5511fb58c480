#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "jaus/base/hex.hpp"
#include "jaus/messages/catalogue.hpp"

namespace jaus::msg {
namespace {

using Json = nlohmann::ordered_json;

Expected<Bytes, Error> encode(const char* text) { return message_from_json(Json::parse(text)); }

TEST(MessageJson, EncodesFromCodeOrNameWithHeaderDefaults) {
  auto by_code = encode(R"({"code":"0x0405","fields":{"propulsive_linear_effort_x_percent":50,
                            "propulsive_rotational_effort_z_percent":-25,"resistive_linear_effort_x_percent":10}})");
  ASSERT_TRUE(by_code) << by_code.error().message();
  auto by_name = encode(R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":50,
                            "propulsive_rotational_effort_z_percent":-25,"resistive_linear_effort_x_percent":10}})");
  ASSERT_TRUE(by_name);
  EXPECT_EQ(*by_code, *by_name);
  // priority 6, version 2; presence vector 0x0061 (bits 0, 5, 6); data size 7.
  EXPECT_EQ(to_hex(*by_code), "06020504000000000000000007000000" "6100" "0040" "00E0" "1A");
}

TEST(MessageJson, DecodePrintsCodeNameHeaderAndFields) {
  auto bytes = encode(R"({"code":"0x4002","header":{"source":"1.1.33.1","destination":"2.1.40.1","sequence":7},
                          "fields":{"primary_status":1,"secondary_status":0}})");
  ASSERT_TRUE(bytes);
  auto json = message_to_json(*bytes);
  ASSERT_TRUE(json) << json.error().message();
  EXPECT_EQ((*json)["code"], "0x4002");
  EXPECT_EQ((*json)["name"], "Report Component Status");
  EXPECT_EQ((*json)["header"]["source"], "1.1.33.1");
  EXPECT_EQ((*json)["header"]["sequence"], 7);
  EXPECT_EQ((*json)["fields"]["primary_status"], "ready");
  // Decoding then encoding is the identity.
  auto again = message_from_json(*json);
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, *bytes);
}

struct BadInput {
  const char* json;
  const char* mentions;
};

class MessageJsonErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(MessageJsonErrors, AreReportedWithTheField) {
  auto result = encode(GetParam().json);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message().find(GetParam().mentions), std::string::npos) << result.error().message();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MessageJsonErrors,
    ::testing::Values(BadInput{R"({"fields":{}})", "'code' or 'name' is required"},
                      BadInput{R"({"code":"0x9999"})", "unknown command code"},
                      BadInput{R"({"code":"banana"})", "expected a command code"},
                      BadInput{R"({"code":"0x4402","fields":{"latitude":1}})", "unknown field 'latitude'"},
                      BadInput{R"({"code":"0x4402","fields":{"latitude_deg":"north"}})", "'latitude_deg': expected a number"},
                      BadInput{R"({"code":"0x000D","fields":{}})", "'authority' is missing"},
                      BadInput{R"({"code":"0x000D","fields":{"authority":256}})", "'authority': out of range"},
                      BadInput{R"({"code":"0x0601","fields":{"efforts_percent":[]}})", "count out of range"},
                      BadInput{R"({"code":"0x4B00","fields":{"query_type":2,"authority":0,"type":1,
                                 "identification":"a string that is much longer than eighty characters, which is what the field holds at most"}})",
                               "longer than 80"},
                      BadInput{R"({"code":"0x0607","fields":{"joint_count":2,"poses":[{"time_s":1,"joints":[
                                 {"position_rad":0,"max_velocity_rps":0,"max_acceleration_rps2":0,"max_deceleration_rps2":0}]}]}})",
                               "array length disagrees with its count"},
                      BadInput{R"({"code":"0x4402","header":{"priority":99}})", "bad value for 'priority'"},
                      BadInput{R"({"code":"0x4402","header":{"colour":"red"}})", "unknown key 'colour'"},
                      BadInput{R"({"code":"0x4807","fields":{"camera_id":1,"image_format":11,"data":"0G"}})", "not a hex digit"}));

TEST(MessageJson, RejectsPayloadsLargerThanOnePacket) {
  const std::string data(2 * 5000, 'A');
  auto result =
      message_from_json(Json{{"code", "0x4807"}, {"fields", {{"camera_id", 1}, {"image_format", 11}, {"data", data}}}});
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::payload_too_large);
}

}  // namespace
}  // namespace jaus::msg
