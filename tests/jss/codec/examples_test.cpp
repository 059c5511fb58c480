// The byte examples of docs/jss.md ("Byte examples") decode to the values it
// states and encode to the same bytes; JSS scaled integers (all unsigned)
// match its encodings ("Scaled values"); values a JTS peer truncated instead of rounding decode
// within one step.
#include <gtest/gtest.h>

#include "jaus/jss/all.hpp"
#include "jss_bytes.hpp"

namespace jaus::test::jss_examples {

using namespace jaus::jss;
namespace msg = jaus::jss::msg;

template <class M>
M decoded(const std::vector<std::uint8_t>& contents) {
  auto m = decode_contents<M>(contents);
  EXPECT_TRUE(m) << (m ? "" : m.error().message());
  return m ? *m : M{};
}

// A periodic 5 Hz event on Query Local Pose with PV 0x01FF, request ID 1.
TEST(JssExamples, CreateEvent) {
  const auto bytes = hex_bytes("f0 01 01 00 2c 01 04 00 00 00 03 24 ff 01");
  const auto create = decoded<msg::CreateEvent>(bytes);
  EXPECT_EQ(create.request_id, 1);
  EXPECT_EQ(create.event_type, msg::event_type::kPeriodic);
  EXPECT_NEAR(create.requested_rate_hz, 5.0, msg::kEventRate.step());
  const auto query = decode_contents<msg::QueryLocalPose>(create.query_message);
  ASSERT_TRUE(query);
  EXPECT_EQ(query->presence_vector, 0x01FF);

  msg::CreateEvent built;
  built.request_id = 1;
  built.event_type = msg::event_type::kPeriodic;
  built.requested_rate_hz = 5;
  built.query_message = encode_contents(msg::QueryLocalPose{0x01FF});
  EXPECT_EQ(encode_contents(built), bytes);
}

// An Event carrying Report Local Pose (PV 0x0003, X = 10 m, Y = -5 m), event 0, sequence 7.
TEST(JssExamples, EventWithReportLocalPose) {
  const auto bytes = hex_bytes("f1 41 00 07 0c 00 00 00 03 44 03 00 dc 46 03 80 91 5c fe 7f");
  const auto event = decoded<msg::Event>(bytes);
  EXPECT_EQ(event.event_id, 0);
  EXPECT_EQ(event.sequence_number, 7);
  const auto report = decode_contents<msg::ReportLocalPose>(event.report_message);
  ASSERT_TRUE(report);
  ASSERT_TRUE(report->x_m && report->y_m);
  EXPECT_NEAR(*report->x_m, 10.0, msg::kLocalXYZ.step());
  EXPECT_NEAR(*report->y_m, -5.0, msg::kLocalXYZ.step());
  EXPECT_FALSE(report->z_m);

  msg::ReportLocalPose pose;
  pose.x_m = 10;
  pose.y_m = -5;
  msg::Event built;
  built.event_id = 0;
  built.sequence_number = 7;
  built.report_message = encode_contents(pose);
  EXPECT_EQ(encode_contents(built), bytes);
}

// Report Identification of the subsystem, a vehicle named "Husky".
TEST(JssExamples, ReportIdentification) {
  const auto bytes = hex_bytes("00 4b 02 11 27 05 48 75 73 6b 79");
  const auto report = decoded<msg::ReportIdentification>(bytes);
  EXPECT_EQ(report.query_type, msg::identification::kSubsystem);
  EXPECT_EQ(report.type, msg::identification_type::kVehicle);
  EXPECT_EQ(report.identification, "Husky");
  EXPECT_EQ(encode_contents(msg::ReportIdentification{{msg::identification::kSubsystem,
                                                       msg::identification_type::kVehicle, "Husky"}}),
            bytes);
}

// Report Services: node 1, component 33 (instance 0), Transport 1.1 and PrimitiveDriver 1.0.
TEST(JssExamples, ReportServices) {
  const auto bytes = concat({hex_bytes("03 4b 01 01 01 21 00 02 1b"), ascii("urn:jaus:jss:core:Transport"),
                             hex_bytes("01 01 25"), ascii("urn:jaus:jss:mobility:PrimitiveDriver"), hex_bytes("01 00")});
  const auto report = decoded<msg::ReportServices>(bytes);
  ASSERT_EQ(report.nodes.size(), 1u);
  EXPECT_EQ(report.nodes[0].node_id, 1);
  ASSERT_EQ(report.nodes[0].components.size(), 1u);
  const auto& component = report.nodes[0].components[0];
  EXPECT_EQ(component.component_id, 33);
  EXPECT_EQ(component.instance_id, 0);
  ASSERT_EQ(component.services.size(), 2u);
  EXPECT_EQ(component.services[0], (msg::ServiceRecord{"urn:jaus:jss:core:Transport", 1, 1}));
  EXPECT_EQ(component.services[1], (msg::ServiceRecord{"urn:jaus:jss:mobility:PrimitiveDriver", 1, 0}));
  EXPECT_EQ(encode_contents(report), bytes);
}

// Set Wrench Effort, PV 0x0021, linear X = +50 %, rotational Z = -25 % -> 49151, 24576.
TEST(JssExamples, SetWrenchEffort) {
  const auto bytes = hex_bytes("05 04 21 00 ff bf 00 60");
  const auto set = decoded<msg::SetWrenchEffort>(bytes);
  constexpr double step = 200.0 / 65535;
  ASSERT_TRUE(set.propulsive_linear_effort_x_percent && set.propulsive_rotational_effort_z_percent);
  EXPECT_NEAR(*set.propulsive_linear_effort_x_percent, 50.0, step);
  EXPECT_NEAR(*set.propulsive_rotational_effort_z_percent, -25.0, step);
  EXPECT_FALSE(set.propulsive_linear_effort_y_percent);
  msg::SetWrenchEffort built;
  built.propulsive_linear_effort_x_percent = 50;
  built.propulsive_rotational_effort_z_percent = -25;
  EXPECT_EQ(encode_contents(built), bytes);
}

// Set Local Waypoint X = 10 m, Y = -5 m, no options.
TEST(JssExamples, SetLocalWaypoint) {
  const auto bytes = hex_bytes("0d 04 00 dc 46 03 80 91 5c fe 7f");
  const auto set = decoded<msg::SetLocalWaypoint>(bytes);
  EXPECT_NEAR(set.x_m, 10.0, msg::kLocalXYZ.step());
  EXPECT_NEAR(set.y_m, -5.0, msg::kLocalXYZ.step());
  EXPECT_FALSE(set.z_m || set.yaw_rad || set.waypoint_tolerance_m || set.path_tolerance_m);
  msg::SetLocalWaypoint built;
  built.x_m = 10;
  built.y_m = -5;
  EXPECT_EQ(encode_contents(built), bytes);
}

// Set Element: one head-and-tail element UID 1 holding that waypoint, request ID 7.
TEST(JssExamples, SetElement) {
  const auto bytes = hex_bytes("1a 04 07 01 01 00 00 00 00 00 00 0b 00 0d 04 00 dc 46 03 80 91 5c fe 7f");
  const auto set = decoded<msg::SetElement>(bytes);
  EXPECT_EQ(set.request_id, 7);
  ASSERT_EQ(set.elements.size(), 1u);
  const auto& element = set.elements[0];
  EXPECT_EQ(element.element_uid, 1);
  EXPECT_EQ(element.previous_uid, msg::element_uid::kNone);
  EXPECT_EQ(element.next_uid, msg::element_uid::kNone);
  EXPECT_EQ(element.format, msg::element_format::kJausMessage);
  const auto waypoint = decode_contents<msg::SetLocalWaypoint>(element.element_data);
  ASSERT_TRUE(waypoint);
  EXPECT_NEAR(waypoint->x_m, 10.0, msg::kLocalXYZ.step());

  msg::SetLocalWaypoint wp;
  wp.x_m = 10;
  wp.y_m = -5;
  msg::SetElement built;
  built.request_id = 7;
  built.elements.push_back({1, 0, 0, msg::element_format::kJausMessage, encode_contents(wp)});
  EXPECT_EQ(encode_contents(built), bytes);
}

// Execute List at 1.5 m/s from UID 1.
TEST(JssExamples, ExecuteList) {
  const auto bytes = hex_bytes("1e 04 01 2c 01 01 00");
  const auto execute = decoded<msg::ExecuteList>(bytes);
  EXPECT_NEAR(execute.speed_mps, 1.5, msg::kTravelSpeed.step());
  EXPECT_EQ(execute.element_uid, std::optional<std::uint16_t>(1));
  EXPECT_EQ(encode_contents(msg::ExecuteList{{1.5, 1}}), bytes);
}

// JSS scaled integers are unsigned, step (hi - lo) / (2^n - 1), bias lo, rounded.
TEST(JssExamples, ScaledIntegersAreUnsignedAndRounded) {
  EXPECT_EQ(encode_contents(msg::SetTravelSpeed{{1.5}}), hex_bytes("0a 04 2c 01"));
  EXPECT_EQ(encode_contents(msg::SetTravelSpeed{{1.0}}), hex_bytes("0a 04 c8 00"));  // 1 m/s = 200
  msg::CreateEvent ten_hz;
  ten_hz.requested_rate_hz = 10;
  ten_hz.query_message = encode_contents(msg::QueryHeartbeatPulse{});
  EXPECT_EQ(encode_contents(ten_hz)[4], 0x58);  // 600 = 0x0258
  EXPECT_EQ(encode_contents(ten_hz)[5], 0x02);
  // Symmetric ranges have no exact zero: 0 % is 32767.5, rounded to 32768.
  msg::SetWrenchEffort zero;
  zero.propulsive_linear_effort_x_percent = 0;
  EXPECT_EQ(encode_contents(zero), hex_bytes("05 04 01 00 00 80"));
  // Out of range clamps to the limits.
  EXPECT_EQ(encode_contents(msg::SetTravelSpeed{{1000}}), hex_bytes("0a 04 ff ff"));
  EXPECT_EQ(encode_contents(msg::SetTravelSpeed{{-1}}), hex_bytes("0a 04 00 00"));
}

// JTS-generated peers cast instead of rounding (docs/jss.md, "Scaled values"): 0 % arrives
// as 32767, 5 Hz as 300 either way; both decode within one step.
TEST(JssExamples, TruncatedValuesDecodeWithinOneStep) {
  const auto zero = decoded<msg::SetWrenchEffort>(hex_bytes("05 04 01 00 ff 7f"));
  ASSERT_TRUE(zero.propulsive_linear_effort_x_percent);
  EXPECT_NEAR(*zero.propulsive_linear_effort_x_percent, 0.0, 200.0 / 65535);
  // 10 m truncated: 2147698395 instead of 2147698396.
  const auto pose = decoded<msg::ReportLocalPose>(hex_bytes("03 44 01 00 db 46 03 80"));
  ASSERT_TRUE(pose.x_m);
  EXPECT_NEAR(*pose.x_m, 10.0, msg::kLocalXYZ.step());
  // 0 rad truncated in a [-pi, pi] u16.
  const auto yaw = decoded<msg::ReportLocalPose>(hex_bytes("03 44 40 00 ff 7f"));
  ASSERT_TRUE(yaw.yaw_rad);
  EXPECT_NEAR(*yaw.yaw_rad, 0.0, msg::kAngle.step());
}

}  // namespace jaus::test::jss_examples
