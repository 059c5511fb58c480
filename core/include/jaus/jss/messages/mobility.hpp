// JSS mobility v1.0 (docs/jss.md, "Mobility services"): Primitive Driver, Velocity State
// Sensor, Local and Global Pose Sensor. Same presence vectors and field order
// as RA, but every scaled field is unsigned (RA's signed ones rescale) and
// some ranges differ; member names are the RA bodies'.
#pragma once

#include "jaus/jss/messages/common.hpp"

namespace jaus::jss::msg {

struct WrenchEffortBody {
  std::optional<double> propulsive_linear_effort_x_percent;  // -100..100
  std::optional<double> propulsive_linear_effort_y_percent;
  std::optional<double> propulsive_linear_effort_z_percent;
  std::optional<double> propulsive_rotational_effort_x_percent;
  std::optional<double> propulsive_rotational_effort_y_percent;
  std::optional<double> propulsive_rotational_effort_z_percent;
  std::optional<double> resistive_linear_effort_x_percent;  // 0..100
  std::optional<double> resistive_linear_effort_y_percent;
  std::optional<double> resistive_linear_effort_z_percent;
  std::optional<double> resistive_rotational_effort_x_percent;
  std::optional<double> resistive_rotational_effort_y_percent;
  std::optional<double> resistive_rotational_effort_z_percent;
  bool operator==(const WrenchEffortBody&) const = default;
  static constexpr auto describe() {
    using B = WrenchEffortBody;
    constexpr wire::Scaled<std::uint16_t> propulsive{-100, 100};
    constexpr wire::Scaled<std::uint8_t> resistive{0, 100};
    return std::make_tuple(
        wire::presence_vector<std::uint16_t>(),
        wire::optional(0, "propulsive_linear_effort_x_percent", &B::propulsive_linear_effort_x_percent, propulsive),
        wire::optional(1, "propulsive_linear_effort_y_percent", &B::propulsive_linear_effort_y_percent, propulsive),
        wire::optional(2, "propulsive_linear_effort_z_percent", &B::propulsive_linear_effort_z_percent, propulsive),
        wire::optional(3, "propulsive_rotational_effort_x_percent", &B::propulsive_rotational_effort_x_percent,
                       propulsive),
        wire::optional(4, "propulsive_rotational_effort_y_percent", &B::propulsive_rotational_effort_y_percent,
                       propulsive),
        wire::optional(5, "propulsive_rotational_effort_z_percent", &B::propulsive_rotational_effort_z_percent,
                       propulsive),
        wire::optional(6, "resistive_linear_effort_x_percent", &B::resistive_linear_effort_x_percent, resistive),
        wire::optional(7, "resistive_linear_effort_y_percent", &B::resistive_linear_effort_y_percent, resistive),
        wire::optional(8, "resistive_linear_effort_z_percent", &B::resistive_linear_effort_z_percent, resistive),
        wire::optional(9, "resistive_rotational_effort_x_percent", &B::resistive_rotational_effort_x_percent,
                       resistive),
        wire::optional(10, "resistive_rotational_effort_y_percent", &B::resistive_rotational_effort_y_percent,
                       resistive),
        wire::optional(11, "resistive_rotational_effort_z_percent", &B::resistive_rotational_effort_z_percent,
                       resistive));
  }
};

struct VelocityStateBody {
  std::optional<double> velocity_x_mps;  // -327.68..327.67
  std::optional<double> velocity_y_mps;
  std::optional<double> velocity_z_mps;
  std::optional<double> velocity_rms_mps;  // 0..100
  std::optional<double> roll_rate_rps;     // -32.768..32.767
  std::optional<double> pitch_rate_rps;
  std::optional<double> yaw_rate_rps;
  std::optional<double> rate_rms_rps;  // 0..pi
  std::optional<TimeStamp> time_stamp;
  bool operator==(const VelocityStateBody&) const = default;
  static constexpr auto describe() {
    using B = VelocityStateBody;
    constexpr wire::Scaled<std::uint32_t> velocity{-327.68, 327.67};
    constexpr wire::Scaled<std::uint16_t> rate{-32.768, 32.767};
    return std::make_tuple(wire::presence_vector<std::uint16_t>(),
                           wire::optional(0, "velocity_x_mps", &B::velocity_x_mps, velocity),
                           wire::optional(1, "velocity_y_mps", &B::velocity_y_mps, velocity),
                           wire::optional(2, "velocity_z_mps", &B::velocity_z_mps, velocity),
                           wire::optional(3, "velocity_rms_mps", &B::velocity_rms_mps, kPositionRms),
                           wire::optional(4, "roll_rate_rps", &B::roll_rate_rps, rate),
                           wire::optional(5, "pitch_rate_rps", &B::pitch_rate_rps, rate),
                           wire::optional(6, "yaw_rate_rps", &B::yaw_rate_rps, rate),
                           wire::optional(7, "rate_rms_rps", &B::rate_rms_rps, kAttitudeRms),
                           wire::optional(8, "time_stamp", &B::time_stamp, wire::Time{}));
  }
};

struct LocalPoseBody {
  std::optional<double> x_m;  // -100000..100000
  std::optional<double> y_m;
  std::optional<double> z_m;             // -100000..100000 (RA: -10000..35000)
  std::optional<double> position_rms_m;  // 0..100
  std::optional<double> roll_rad;        // -pi..pi
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  std::optional<double> attitude_rms_rad;  // 0..pi
  std::optional<TimeStamp> time_stamp;
  bool operator==(const LocalPoseBody&) const = default;
  static constexpr auto describe() {
    using B = LocalPoseBody;
    return std::make_tuple(wire::presence_vector<std::uint16_t>(), wire::optional(0, "x_m", &B::x_m, kLocalXYZ),
                           wire::optional(1, "y_m", &B::y_m, kLocalXYZ), wire::optional(2, "z_m", &B::z_m, kLocalXYZ),
                           wire::optional(3, "position_rms_m", &B::position_rms_m, kPositionRms),
                           wire::optional(4, "roll_rad", &B::roll_rad, kAngle),
                           wire::optional(5, "pitch_rad", &B::pitch_rad, kAngle),
                           wire::optional(6, "yaw_rad", &B::yaw_rad, kAngle),
                           wire::optional(7, "attitude_rms_rad", &B::attitude_rms_rad, kAttitudeRms),
                           wire::optional(8, "time_stamp", &B::time_stamp, wire::Time{}));
  }
};

struct GlobalPoseBody {
  std::optional<double> latitude_deg;  // WGS 84, -90..90
  std::optional<double> longitude_deg;  // -180..180
  std::optional<double> elevation_m;    // JSS "altitude", -10000..35000
  std::optional<double> position_rms_m;
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  std::optional<double> attitude_rms_rad;
  std::optional<TimeStamp> time_stamp;
  bool operator==(const GlobalPoseBody&) const = default;
  static constexpr auto describe() {
    using B = GlobalPoseBody;
    return std::make_tuple(
        wire::presence_vector<std::uint16_t>(),
        wire::optional(0, "latitude_deg", &B::latitude_deg, wire::Scaled<std::uint32_t>{-90, 90}),
        wire::optional(1, "longitude_deg", &B::longitude_deg, wire::Scaled<std::uint32_t>{-180, 180}),
        wire::optional(2, "elevation_m", &B::elevation_m, wire::Scaled<std::uint32_t>{-10'000, 35'000}),
        wire::optional(3, "position_rms_m", &B::position_rms_m, kPositionRms),
        wire::optional(4, "roll_rad", &B::roll_rad, kAngle), wire::optional(5, "pitch_rad", &B::pitch_rad, kAngle),
        wire::optional(6, "yaw_rad", &B::yaw_rad, kAngle),
        wire::optional(7, "attitude_rms_rad", &B::attitude_rms_rad, kAttitudeRms),
        wire::optional(8, "time_stamp", &B::time_stamp, wire::Time{}));
  }
};

struct GeomagneticPropertyBody {
  double magnetic_variation_rad = 0;  // -pi..pi
  bool operator==(const GeomagneticPropertyBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("magnetic_variation_rad", &GeomagneticPropertyBody::magnetic_variation_rad, kAngle));
  }
};

// Primitive Driver.
using SetWrenchEffort = Message<0x0405, "Set Wrench Effort", WrenchEffortBody>;
using QueryWrenchEffort = Message<0x2405, "Query Wrench Effort", QueryPresence16Body>;
using ReportWrenchEffort = Message<0x4405, "Report Wrench Effort", WrenchEffortBody>;
// Velocity State Sensor.
using QueryVelocityState = Message<0x2404, "Query Velocity State", QueryPresence16Body>;
using ReportVelocityState = Message<0x4404, "Report Velocity State", VelocityStateBody>;
// Local Pose Sensor.
using SetLocalPose = Message<0x0403, "Set Local Pose", LocalPoseBody>;
using QueryLocalPose = Message<0x2403, "Query Local Pose", QueryPresence16Body>;
using ReportLocalPose = Message<0x4403, "Report Local Pose", LocalPoseBody>;
// Global Pose Sensor.
using SetGlobalPose = Message<0x0402, "Set Global Pose", GlobalPoseBody>;
using QueryGlobalPose = Message<0x2402, "Query Global Pose", QueryPresence16Body>;
using ReportGlobalPose = Message<0x4402, "Report Global Pose", GlobalPoseBody>;
using SetGeomagneticProperty = Message<0x0412, "Set Geomagnetic Property", GeomagneticPropertyBody>;
using QueryGeomagneticProperty = Message<0x2412, "Query Geomagnetic Property", Empty>;
using ReportGeomagneticProperty = Message<0x4412, "Report Geomagnetic Property", GeomagneticPropertyBody>;

using SensorDriverMessages =
    TypeList<SetWrenchEffort, QueryWrenchEffort, ReportWrenchEffort, QueryVelocityState, ReportVelocityState,
             SetLocalPose, QueryLocalPose, ReportLocalPose, SetGlobalPose, QueryGlobalPose, ReportGlobalPose,
             SetGeomagneticProperty, QueryGeomagneticProperty, ReportGeomagneticProperty>;

}  // namespace jaus::jss::msg
