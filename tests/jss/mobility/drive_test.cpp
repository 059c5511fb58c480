// A JSS client drives the simulated vehicle through the face: Primitive
// Driver's Set Wrench Effort under the RA component's rules (control, Ready),
// the Velocity State and Local Pose reports (queried and by periodic event)
// following the motion, and what the face does not support.
#include "jss_vehicle.hpp"

namespace jaus::test {
namespace drive_test {

jss::msg::SetWrenchEffort forward(double percent) {
  jss::msg::SetWrenchEffort m{};
  m.propulsive_linear_effort_x_percent = percent;
  m.propulsive_rotational_effort_z_percent = 0;
  return m;
}

// Set Wrench Effort every 100 ms for `d` (the primitive driver's command timeout wants it renewed).
void drive(JssVehicle& v, double percent, rt::Duration d) {
  const auto end = v.time().now() + d;
  while (v.time().now() < end) {
    v.send(kJssPrimitiveDriver, forward(percent));
    v.run_for(100ms);
  }
}

double distance_from(const components::PoseSample& a, const components::PoseSample& b) {
  return std::hypot(a.local_position->x_m - b.local_position->x_m, a.local_position->y_m - b.local_position->y_m);
}

TEST(JssMobilityDrive, WrenchEffortDrivesAndTheSensorsFollow) {
  JssVehicle v;
  ASSERT_TRUE(v.wait_ready());
  // A periodic event on the velocity state, 5 Hz.
  jss::msg::CreateEvent create{};
  create.request_id = 7;
  create.event_type = jss::msg::event_type::kPeriodic;
  create.requested_rate_hz = 5;
  create.query_message = jss::encode_contents(jss::msg::QueryVelocityState{{0x0001}});
  const auto confirmed = v.ask<jss::msg::ConfirmEventRequest>(kJssVelocityState, create);
  ASSERT_TRUE(confirmed);
  EXPECT_EQ(confirmed->request_id, 7);

  const auto start_pose = v.ask<jss::msg::ReportLocalPose>(kJssLocalPose, jss::msg::QueryLocalPose{{0x0003}});
  ASSERT_TRUE(start_pose);
  ASSERT_TRUE(start_pose->x_m && start_pose->y_m);
  EXPECT_FALSE(start_pose->yaw_rad);  // the query's presence vector is the RA query's

  ASSERT_EQ(v.request_control(kJssPrimitiveDriver), jss::msg::confirm_control::kControlAccepted);
  v.send(kJssPrimitiveDriver, jss::msg::Resume{});
  v.drop<jss::msg::Event>();
  const auto before = v.pose();
  drive(v, 60, 3s);
  EXPECT_GT(v.speed_mps(), 0.3);
  EXPECT_GT(distance_from(v.pose(), before), 0.5);

  const auto velocity = v.ask<jss::msg::ReportVelocityState>(kJssVelocityState, jss::msg::QueryVelocityState{{0x0001}});
  ASSERT_TRUE(velocity);
  ASSERT_TRUE(velocity->velocity_x_mps);
  EXPECT_GT(*velocity->velocity_x_mps, 0.3);
  const auto pose = v.ask<jss::msg::ReportLocalPose>(kJssLocalPose, jss::msg::QueryLocalPose{{0x0003}});
  ASSERT_TRUE(pose);
  EXPECT_GT(std::hypot(*pose->x_m - *start_pose->x_m, *pose->y_m - *start_pose->y_m), 0.5);
  const auto effort = v.ask<jss::msg::ReportWrenchEffort>(kJssPrimitiveDriver, jss::msg::QueryWrenchEffort{{0x0001}});
  ASSERT_TRUE(effort);
  ASSERT_TRUE(effort->propulsive_linear_effort_x_percent);
  EXPECT_NEAR(*effort->propulsive_linear_effort_x_percent, 60, 0.01);

  // The event's reports followed the motion: about 15 in 3 s, the speed rising.
  std::vector<double> speeds;
  while (auto event = v.take<jss::msg::Event>(kJssVelocityState)) {
    auto report = jss::decode_contents<jss::msg::ReportVelocityState>(event->report_message);
    ASSERT_TRUE(report);
    ASSERT_TRUE(report->velocity_x_mps);
    speeds.push_back(*report->velocity_x_mps);
  }
  EXPECT_GE(speeds.size(), 12u);
  ASSERT_FALSE(speeds.empty());
  EXPECT_LT(speeds.front(), 0.2);
  EXPECT_GT(speeds.back(), 0.3);

  // Zero effort (JSS's "0" is RA's exact 0) stops it.
  drive(v, 0, 3s);
  EXPECT_LT(v.speed_mps(), 0.02);
  // The RA component's controller is the client's alias.
  const auto& controller = v.host().node().find(kRaPrimitiveDriver)->control().controller();
  ASSERT_TRUE(controller);
  EXPECT_EQ(controller->address.subsystem, v.face().config().client_alias_subsystem);
}

TEST(JssMobilityDrive, WrenchEffortWithoutControlOrInStandbyDoesNothing) {
  JssVehicle v;
  ASSERT_TRUE(v.wait_ready());
  const auto& driver = *v.host().node().find(kRaPrimitiveDriver);
  drive(v, 80, 1s);
  EXPECT_LT(v.speed_mps(), 0.01);
  EXPECT_GT(driver.counters().refused_not_controller, 0u);

  ASSERT_EQ(v.request_control(kJssPrimitiveDriver), jss::msg::confirm_control::kControlAccepted);
  v.send(kJssPrimitiveDriver, jss::msg::Standby{});
  ASSERT_TRUE(v.run_until([&] { return v.state_of(kRaPrimitiveDriver) == rt::PrimaryStatus::standby; }, 1s));
  const auto refused_before = driver.counters().refused_wrong_state;
  drive(v, 80, 1s);
  EXPECT_LT(v.speed_mps(), 0.01);
  EXPECT_GT(driver.counters().refused_wrong_state, refused_before);

  // Resumed by its controller, the same command drives.
  v.send(kJssPrimitiveDriver, jss::msg::Resume{});
  ASSERT_TRUE(v.run_until([&] { return v.state_of(kRaPrimitiveDriver) == rt::PrimaryStatus::ready; }, 1s));
  drive(v, 80, 2s);
  EXPECT_GT(v.speed_mps(), 0.3);
}

TEST(JssMobilityDrive, PoseSettingsAreUnsupportedAndChangeNothing) {
  JssVehicle v;
  ASSERT_TRUE(v.wait_ready());
  ASSERT_EQ(v.request_control(kJssLocalPose), jss::msg::confirm_control::kControlAccepted);
  const auto unsupported = v.face().counters().unsupported;
  jss::msg::SetLocalPose set{};
  set.x_m = 100;
  set.y_m = 100;
  v.send(kJssLocalPose, set);
  v.send(kJssGlobalPose, jss::msg::QueryGeomagneticProperty{});
  v.run_for(50ms);
  EXPECT_EQ(v.face().counters().unsupported, unsupported + 2);
  const auto pose = v.ask<jss::msg::ReportLocalPose>(kJssLocalPose, jss::msg::QueryLocalPose{{0x0003}});
  ASSERT_TRUE(pose);
  EXPECT_LT(std::abs(*pose->x_m), 1.0);
  const auto global = v.ask<jss::msg::ReportGlobalPose>(kJssGlobalPose, jss::msg::QueryGlobalPose{{0x0007}});
  ASSERT_TRUE(global);
  ASSERT_TRUE(global->latitude_deg && global->longitude_deg && global->elevation_m);
  EXPECT_NEAR(*global->latitude_deg, v.host().config().vehicle.start.latitude_deg, 1e-4);
  EXPECT_NEAR(*global->longitude_deg, v.host().config().vehicle.start.longitude_deg, 1e-4);
  bool logged = false;
  for (const auto& line : v.log()) logged |= line.find("Set Local Pose") != std::string::npos;
  EXPECT_TRUE(logged);
}

TEST(JssMobilityDrive, MalformedCommandsAreCountedAndNeverActedOn) {
  JssVehicle v;
  ASSERT_TRUE(v.wait_ready());
  ASSERT_EQ(v.request_control(kJssPrimitiveDriver), jss::msg::confirm_control::kControlAccepted);
  ASSERT_EQ(v.request_control(kJssWaypointDriver), jss::msg::confirm_control::kControlAccepted);
  const auto malformed = v.face().counters().malformed;
  // Set Wrench Effort whose presence vector promises a field that is not there.
  auto effort = jss::encode_contents(forward(80));
  effort.pop_back();
  // Set Element whose element data count runs past the end.
  const std::vector<std::uint8_t> element{0x1a, 0x04, 0x01, 0x01, 0x01, 0x00, 0x00, 0x00,
                                          0x00, 0x00, 0x00, 0x40, 0x00, 0x0d, 0x04};
  for (int i = 0; i < 10; ++i) {
    v.send_contents(kJssPrimitiveDriver, effort);
    v.send_contents(kJssWaypointDriver, element);
    v.run_for(100ms);
  }
  EXPECT_EQ(v.face().counters().malformed, malformed + 20);
  EXPECT_LT(v.speed_mps(), 0.01);
  EXPECT_EQ(v.count(jss::msg::ConfirmElementRequest::code) + v.count(jss::msg::RejectElementRequest::code), 0u);
  const auto count = v.ask<jss::msg::ReportElementCount>(kJssWaypointDriver, jss::msg::QueryElementCount{});
  ASSERT_TRUE(count);
  EXPECT_EQ(count->element_count, 0);
}

}  // namespace drive_test
}  // namespace jaus::test
