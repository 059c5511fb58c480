// JSS mobility v1.0 (docs/jss.md, "Mobility services"): Primitive Driver, Velocity State
// Sensor, Local and Global Pose Sensor. Same presence vectors and field order
// as RA, but every scaled field is unsigned (RA's signed ones rescale) and
// some ranges differ: the RA bodies, read in wire::Dialect::jss.
#pragma once

#include "jaus/jss/messages/common.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::jss::msg {

// The bodies JSS shares with RA, described once (jaus/messages/
// platform_messages.hpp): the same fields and presence bits; read in the JSS
// dialect, every scaled field is unsigned and Velocity State and Local Pose's
// z have JSS's ranges (wire::Scaled::jss).
using jaus::msg::GlobalPoseBody;     // latitude -90..90, longitude -180..180, "altitude" -10000..35000
using jaus::msg::LocalPoseBody;      // x, y, z -100000..100000 (RA z: -10000..35000)
using jaus::msg::VelocityStateBody;  // velocity -327.68..327.67, rates -32.768..32.767
using jaus::msg::WrenchEffortBody;   // propulsive -100..100, resistive 0..100
static_assert(wire::shared_with_jss<GlobalPoseBody>() && wire::shared_with_jss<LocalPoseBody>() &&
                  wire::shared_with_jss<VelocityStateBody>() && wire::shared_with_jss<WrenchEffortBody>(),
              "a body JSS shares says so (kSharedWithJss): its JSS walk is compiled with the dialect as a constant");

struct GeomagneticPropertyBody {
  double magnetic_variation_rad = 0;  // -pi..pi
  bool operator==(const GeomagneticPropertyBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("magnetic_variation_rad", &GeomagneticPropertyBody::magnetic_variation_rad, kAngle));
  }
};

// Primitive Driver.
using jaus::msg::SetWrenchEffort;
using QueryWrenchEffort = Message<0x2405, "Query Wrench Effort", QueryPresence16Body>;
using jaus::msg::ReportWrenchEffort;
// Velocity State Sensor.
using QueryVelocityState = Message<0x2404, "Query Velocity State", QueryPresence16Body>;
using jaus::msg::ReportVelocityState;
// Local Pose Sensor.
using SetLocalPose = Message<0x0403, "Set Local Pose", LocalPoseBody>;
using QueryLocalPose = Message<0x2403, "Query Local Pose", QueryPresence16Body>;
using jaus::msg::ReportLocalPose;
// Global Pose Sensor.
using SetGlobalPose = Message<0x0402, "Set Global Pose", GlobalPoseBody>;
using QueryGlobalPose = Message<0x2402, "Query Global Pose", QueryPresence16Body>;
using jaus::msg::ReportGlobalPose;
using SetGeomagneticProperty = Message<0x0412, "Set Geomagnetic Property", GeomagneticPropertyBody>;
using QueryGeomagneticProperty = Message<0x2412, "Query Geomagnetic Property", Empty>;
using ReportGeomagneticProperty = Message<0x4412, "Report Geomagnetic Property", GeomagneticPropertyBody>;

using SensorDriverMessages =
    TypeList<SetWrenchEffort, QueryWrenchEffort, ReportWrenchEffort, QueryVelocityState, ReportVelocityState,
             SetLocalPose, QueryLocalPose, ReportLocalPose, SetGlobalPose, QueryGlobalPose, ReportGlobalPose,
             SetGeomagneticProperty, QueryGeomagneticProperty, ReportGeomagneticProperty>;

}  // namespace jaus::jss::msg
