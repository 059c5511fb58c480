// Encoding refuses what cannot go on the wire, naming the offset and field:
// values out of their bit range, and output buffers too small. Fixed-layout
// messages encode on an unchecked fast path and find these on a second,
// checked walk (describe.hpp); the errors are the same either way.
#include <gtest/gtest.h>

#include <array>

#include "jaus/messages/all.hpp"

namespace jaus {
namespace {

msg::ReportGlobalPose full_pose() {
  msg::ReportGlobalPose m;
  m.latitude_deg = 41.616;
  m.longitude_deg = -100.332;
  m.elevation_m = 1893.5;
  m.position_rms_m = 1.87;
  m.roll_rad = 0.0123;
  m.pitch_rad = -0.0456;
  m.yaw_rad = 2.5;
  m.attitude_rms_rad = 0.01;
  m.time_stamp = TimeStamp{789, 42, 37, 13, 21};
  return m;
}

TEST(EncodeErrors, ValueOutOfItsBitRangeNamesTheField) {
  auto m = full_pose();
  m.time_stamp->hour = 77;
  std::array<std::uint8_t, 256> out{};
  auto payload = wire::encode_payload(m, out);
  ASSERT_FALSE(payload);
  EXPECT_EQ(payload.error().code, ErrorCode::bad_value);
  EXPECT_EQ(payload.error().field, "time_stamp");
  EXPECT_EQ(payload.error().offset, 26u);
  // As a whole message the offset counts the header.
  auto packet = wire::encode_message(Header{}, m, out);
  ASSERT_FALSE(packet);
  EXPECT_EQ(packet.error().field, "time_stamp");
  EXPECT_EQ(packet.error().offset, 42u);
}

TEST(EncodeErrors, BufferTooSmallNamesTheFieldThatDoesNotFit) {
  std::array<std::uint8_t, 20> out{};
  auto pose = wire::encode_payload(full_pose(), out);
  ASSERT_FALSE(pose);
  EXPECT_EQ(pose.error().code, ErrorCode::output_too_small);
  EXPECT_EQ(pose.error().field, "pitch_rad");
  EXPECT_EQ(pose.error().offset, 20u);

  msg::SetWrenchEffort wrench;
  wrench.propulsive_linear_effort_x_percent = 10;
  wrench.propulsive_rotational_effort_z_percent = -20;
  wrench.resistive_linear_effort_y_percent = 30;
  // Only present fields take room: presence vector and two propulsive efforts
  // fill the 6 bytes, the resistive effort does not fit.
  auto effort = wire::encode_payload(wrench, std::span(out).first(6));
  ASSERT_FALSE(effort);
  EXPECT_EQ(effort.error().field, "resistive_linear_effort_y_percent");
  EXPECT_EQ(effort.error().offset, 6u);
}

TEST(EncodeErrors, TooSmallForThePresenceVectorNamesIt) {
  std::array<std::uint8_t, 1> out{};
  auto pose = wire::encode_payload(full_pose(), out);
  ASSERT_FALSE(pose);
  EXPECT_EQ(pose.error().field, "presence_vector");
  EXPECT_EQ(pose.error().offset, 0u);
}

}  // namespace
}  // namespace jaus
