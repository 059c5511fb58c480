// JSS <-> RA scaling (docs/jss.md, "Scaling"): its byte examples, JSS's
// missing zero made RA's exact 0, RA's narrower ranges clamped.
#include <gtest/gtest.h>

#include <vector>

#include "jaus/components_jss/local_waypoint_driver_jss.hpp"
#include "jaus/components_jss/primitive_driver_jss.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss_face/scaling.hpp"
#include "jaus/jss_face/translator_kit.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::components_jss {
namespace scaling_test {

namespace scaling = jss_face::scaling;

using Bytes = std::vector<std::uint8_t>;

Bytes ra_payload(const auto& message) { return *jss_face::kit::encode_ra(message); }

TEST(JssScaling, WrenchEffortExampleRescalesToRaSigned) {
  jss::msg::SetWrenchEffort jss{};
  jss.propulsive_linear_effort_x_percent = 50;
  jss.propulsive_rotational_effort_z_percent = -25;
  // The JSS bytes of docs/jss.md's "Byte examples": PV 0x0021, 49151, 24576.
  EXPECT_EQ(jss::encode_contents(jss), (Bytes{0x05, 0x04, 0x21, 0x00, 0xff, 0xbf, 0x00, 0x60}));
  // The same values in RA: 16384 and -8192, the same PV.
  msg::SetWrenchEffort exact{};
  exact.propulsive_linear_effort_x_percent = 50;
  exact.propulsive_rotational_effort_z_percent = -25;
  EXPECT_EQ(ra_payload(exact), (Bytes{0x21, 0x00, 0x00, 0x40, 0x00, 0xe0}));
  // Decoded from the JSS bytes and sent to RA: within one JSS step (49151 is
  // 49.9992 %, so RA's nearest integer is 16383), the same PV.
  auto decoded = jss::decode_contents<jss::msg::SetWrenchEffort>(jss::encode_contents(jss));
  ASSERT_TRUE(decoded);
  const auto ra = wrench_effort_to_ra(*decoded);
  EXPECT_NEAR(*ra.propulsive_linear_effort_x_percent, 50, scaling::kEffortStep);
  EXPECT_NEAR(*ra.propulsive_rotational_effort_z_percent, -25, scaling::kEffortStep);
  EXPECT_EQ(ra_payload(ra), (Bytes{0x21, 0x00, 0xff, 0x3f, 0x01, 0xe0}));
}

TEST(JssScaling, ZeroEffortFromAnyJssEncoderIsExactlyRaZero) {
  // 0 % has no JSS integer: we send 32768, JTS truncates to 32767.
  for (const std::uint16_t raw : {std::uint16_t{32767}, std::uint16_t{32768}}) {
    const Bytes contents{0x05, 0x04, 0x01, 0x00, static_cast<std::uint8_t>(raw & 0xff),
                         static_cast<std::uint8_t>(raw >> 8)};
    auto decoded = jss::decode_contents<jss::msg::SetWrenchEffort>(contents);
    ASSERT_TRUE(decoded) << raw;
    EXPECT_NE(*decoded->propulsive_linear_effort_x_percent, 0.0) << raw;
    const auto ra = wrench_effort_to_ra(*decoded);
    EXPECT_EQ(*ra.propulsive_linear_effort_x_percent, 0.0) << raw;
    EXPECT_EQ(ra_payload(ra), (Bytes{0x01, 0x00, 0x00, 0x00})) << raw;
  }
  // One step further is a real (tiny) command, kept.
  jss::msg::SetWrenchEffort small{};
  small.propulsive_linear_effort_x_percent = 3 * scaling::kEffortStep;
  EXPECT_GT(*wrench_effort_to_ra(small).propulsive_linear_effort_x_percent, 0.0);
}

TEST(JssScaling, ResistiveEffortsAndPresenceAreCopied) {
  jss::msg::SetWrenchEffort jss{};
  jss.resistive_linear_effort_x_percent = 40;
  jss.propulsive_rotational_effort_y_percent = -100;
  const auto ra = wrench_effort_to_ra(jss);
  EXPECT_FALSE(ra.propulsive_linear_effort_x_percent);
  EXPECT_EQ(ra.resistive_linear_effort_x_percent, 40);
  EXPECT_EQ(ra.propulsive_rotational_effort_y_percent, -100);
  EXPECT_EQ(wire::presence_of(static_cast<const msg::WrenchEffortBody&>(ra)),
            wire::presence_of(static_cast<const jss::msg::WrenchEffortBody&>(jss)));
}

TEST(JssScaling, LocalWaypointExampleAndRaRanges) {
  jss::msg::SetLocalWaypoint jss{};
  jss.x_m = 10;
  jss.y_m = -5;
  EXPECT_EQ(jss::encode_contents(jss),
            (Bytes{0x0d, 0x04, 0x00, 0xdc, 0x46, 0x03, 0x80, 0x91, 0x5c, 0xfe, 0x7f}));
  auto decoded = jss::decode_contents<jss::msg::SetLocalWaypoint>(jss::encode_contents(jss));
  ASSERT_TRUE(decoded);
  const auto ra = local_waypoint_to_ra(*decoded, 3);
  EXPECT_EQ(ra.waypoint_number, 3);
  EXPECT_NEAR(ra.x_m, 10, 1e-4);
  EXPECT_NEAR(ra.y_m, -5, 1e-4);
  EXPECT_FALSE(ra.z_m);
  // Z beyond RA's -10 km..35 km is clamped; tolerances stay out of RA.
  jss.z_m = 50'000;
  jss.yaw_rad = 0.5 * scaling::kAngleStep;  // JSS's "0"
  jss.waypoint_tolerance_m = 2;
  const auto clamped = local_waypoint_to_ra(jss, 0);
  EXPECT_EQ(clamped.z_m, 35'000);
  EXPECT_EQ(clamped.yaw_rad, 0.0);
  EXPECT_FALSE(clamped.waypoint_tolerance_m);  // one body, but RA has no tolerances
  jss.z_m = -50'000;
  EXPECT_EQ(local_waypoint_to_ra(jss, 0).z_m, -10'000);
}

TEST(JssScaling, TravelSpeedRanges) {
  // 1 m/s is 200 in JSS and 7 in RA (0..10000 m/s: one RA step is 0.153 m/s).
  EXPECT_EQ(jss::encode_contents(jss::msg::SetTravelSpeed{{1.0}}), (Bytes{0x0a, 0x04, 0xc8, 0x00}));
  EXPECT_EQ(ra_payload(msg::SetTravelSpeed{{scaling::travel_speed_to_ra(1.0)}}), (Bytes{0x07, 0x00}));
  EXPECT_EQ(scaling::travel_speed_to_jss(500), scaling::kMaxTravelSpeedMps);
  EXPECT_EQ(scaling::travel_speed_to_ra(-1), 0);
  // Execute List at 1.5 m/s from element 1: the bytes of "Byte examples".
  jss::msg::ExecuteList run{};
  run.speed_mps = 1.5;
  run.element_uid = 1;
  EXPECT_EQ(jss::encode_contents(run), (Bytes{0x1e, 0x04, 0x01, 0x2c, 0x01, 0x01, 0x00}));
}

TEST(JssScaling, AnRaReportSentAsItIsIsRescaledInJss) {
  // The face sends the RA component's report to the JSS client unchanged:
  // one body, encoded in the JSS dialect.
  msg::ReportVelocityState ra{};
  ra.velocity_x_mps = 1.25;
  ra.yaw_rate_rps = -0.5;
  ra.velocity_rms_mps = 0.02;
  auto decoded = jss::decode_contents<jss::msg::ReportVelocityState>(jss::encode_contents(ra));
  ASSERT_TRUE(decoded);
  EXPECT_NEAR(*decoded->velocity_x_mps, 1.25, 1e-5);
  EXPECT_NEAR(*decoded->yaw_rate_rps, -0.5, 1e-3);
  EXPECT_NEAR(*decoded->velocity_rms_mps, 0.02, 1e-6);
  EXPECT_FALSE(decoded->velocity_y_mps);
  EXPECT_FALSE(decoded->time_stamp);

  msg::ReportLocalPose pose{};
  pose.x_m = -12.5;
  pose.z_m = 34'000;
  pose.yaw_rad = 3.0;
  auto pose_back = jss::decode_contents<jss::msg::ReportLocalPose>(jss::encode_contents(pose));
  ASSERT_TRUE(pose_back);
  EXPECT_NEAR(*pose_back->x_m, -12.5, 1e-4);
  EXPECT_NEAR(*pose_back->z_m, 34'000, 1e-4);
  EXPECT_NEAR(*pose_back->yaw_rad, 3.0, 1e-4);
}

}  // namespace scaling_test
}  // namespace jaus::components_jss
