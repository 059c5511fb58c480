// Platform subgroup: 0x0400-0x05FF, 0x2400-0x25FF, 0x4400-0x45FF.
#pragma once

#include "jaus/messages/common.hpp"
#include "jaus/messages/core_messages.hpp"

namespace jaus::msg {

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
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = WrenchEffortBody;
    constexpr wire::Scaled<std::int16_t> propulsive{-100, 100};
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

inline constexpr auto kMainPropulsion =
    wire::bits_of<std::uint8_t>({"power_plant_on", "main_fuel_on", "auxiliary_fuel_on", "auxiliary_devices_power_on",
                                 "starting_device_on", "cold_start", "automatic_start", "automatic_shutdown"});
inline constexpr auto kParkingBrakeAndHorn = wire::bits_of<std::uint8_t>({"parking_brake_set", "horn_on"});
// Gear 1-127 (forward) and 129-255 (reverse), transfer case 0-127 (low) and
// 129-255 (high) are ranges: those show as numbers.
inline constexpr auto kGear = wire::enum_of<std::uint8_t>({{0, "park"}, {128, "neutral"}});
inline constexpr auto kTransferCase = wire::enum_of<std::uint8_t>({{128, "neutral"}});

struct DiscreteDevicesBody {
  // Bit fields as in Part 3: main propulsion bit 0 on, 1 main fuel, 2 auxiliary
  // fuel, 3 power to auxiliary devices, 4 starting device, 5 cold start,
  // 6 automatic start, 7 automatic shutdown; brake/horn bit 0 parking brake set,
  // bit 1 horn on. Gear: 0 park, 1-127 forward, 128 neutral, 129-255 reverse.
  // Transfer case: 0-127 low, 128 neutral, 129-255 high.
  std::optional<std::uint8_t> main_propulsion;
  std::optional<std::uint8_t> parking_brake_and_horn;
  std::optional<std::uint8_t> gear;
  std::optional<std::uint8_t> transfer_case;
  bool operator==(const DiscreteDevicesBody&) const = default;
  static constexpr auto describe() {
    using B = DiscreteDevicesBody;
    return std::make_tuple(
        wire::presence_vector<std::uint8_t>(),
        wire::optional(0, "main_propulsion", &B::main_propulsion, kMainPropulsion),
        wire::optional(1, "parking_brake_and_horn", &B::parking_brake_and_horn, kParkingBrakeAndHorn),
        wire::optional(2, "gear", &B::gear, kGear),
        wire::optional(3, "transfer_case", &B::transfer_case, kTransferCase));
  }
};

struct GlobalVectorBody {
  std::optional<double> speed_mps;
  std::optional<double> altitude_m;  // above sea level
  std::optional<double> heading_rad;
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  bool operator==(const GlobalVectorBody&) const = default;
  static constexpr auto describe() {
    using B = GlobalVectorBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::optional(0, "speed_mps", &B::speed_mps, wire::Scaled<std::uint16_t>{0, 10'000}),
                           wire::optional(1, "altitude_m", &B::altitude_m, kElevation),
                           wire::optional(2, "heading_rad", &B::heading_rad, kAngleShort),
                           wire::optional(3, "roll_rad", &B::roll_rad, kAngleShort),
                           wire::optional(4, "pitch_rad", &B::pitch_rad, kAngleShort));
  }
};

struct LocalVectorBody {
  double speed_mps = 0;
  double heading_rad = 0;
  bool operator==(const LocalVectorBody&) const = default;
  static constexpr auto describe() {
    using B = LocalVectorBody;
    return std::make_tuple(wire::field("speed_mps", &B::speed_mps, wire::Scaled<std::int32_t>{0, 10'000}),
                           wire::field("heading_rad", &B::heading_rad, kAngleShort));
  }
};

struct TravelSpeedBody {
  double speed_mps = 0;
  bool operator==(const TravelSpeedBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    // JSS (Local Waypoint Driver): 0..327.67 m/s.
    return std::make_tuple(wire::field("speed_mps", &TravelSpeedBody::speed_mps,
                                       wire::Scaled<std::uint16_t>{0, 10'000}.jss(0, 327.67)));
  }
};

struct GlobalWaypointBody {
  std::uint16_t waypoint_number = 0;
  double latitude_deg = 0;
  double longitude_deg = 0;
  std::optional<double> elevation_m;
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  bool operator==(const GlobalWaypointBody&) const = default;
  static constexpr auto describe() {
    using B = GlobalWaypointBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("waypoint_number", &B::waypoint_number, UShort{}),
                           wire::field("latitude_deg", &B::latitude_deg, kLatitude),
                           wire::field("longitude_deg", &B::longitude_deg, kLongitude),
                           wire::optional(0, "elevation_m", &B::elevation_m, kElevation),
                           wire::optional(1, "roll_rad", &B::roll_rad, kAngleShort),
                           wire::optional(2, "pitch_rad", &B::pitch_rad, kAngleShort),
                           wire::optional(3, "yaw_rad", &B::yaw_rad, kAngleShort));
  }
};

// RA numbers its waypoints in the message; JSS keeps them in a list manager
// (the element's UID, not a field) and adds two tolerances, bits 4 and 5.
struct LocalWaypointBody {
  std::uint16_t waypoint_number = 0;  // RA only
  double x_m = 0;
  double y_m = 0;
  std::optional<double> z_m;  // RA -10000..35000 (an elevation), JSS -100000..100000
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  std::optional<double> waypoint_tolerance_m;  // JSS only: 0..100
  std::optional<double> path_tolerance_m;      // JSS only: 0..100000, 0 = infinite
  bool operator==(const LocalWaypointBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = LocalWaypointBody;
    using wire::Dialect;
    return std::make_tuple(
        wire::presence_vector<std::uint8_t>(),
        wire::field("waypoint_number", &B::waypoint_number, UShort{}).not_in(Dialect::jss),
        wire::field("x_m", &B::x_m, kLocalXY), wire::field("y_m", &B::y_m, kLocalXY),
        wire::optional(0, "z_m", &B::z_m, kElevation.jss(-100'000, 100'000)),
        wire::optional(1, "roll_rad", &B::roll_rad, kAngleShort),
        wire::optional(2, "pitch_rad", &B::pitch_rad, kAngleShort),
        wire::optional(3, "yaw_rad", &B::yaw_rad, kAngleShort),
        wire::optional(4, "waypoint_tolerance_m", &B::waypoint_tolerance_m, wire::Scaled<std::uint16_t>{0, 100})
            .only_in(Dialect::jss),
        wire::optional(5, "path_tolerance_m", &B::path_tolerance_m, wire::Scaled<std::uint32_t>{0, 100'000})
            .only_in(Dialect::jss));
  }
};

inline constexpr wire::Scaled<std::uint16_t> kWeightingFactor{0, 500};

struct GlobalPathSegmentBody {
  std::uint16_t path_segment_number = 0;
  double p1_latitude_deg = 0;
  double p1_longitude_deg = 0;
  std::optional<double> p1_elevation_m;
  double p2_latitude_deg = 0;
  double p2_longitude_deg = 0;
  std::optional<double> p2_elevation_m;
  double weighting_factor = 0;  // 0 = straight line, up to 500
  bool operator==(const GlobalPathSegmentBody&) const = default;
  static constexpr auto describe() {
    using B = GlobalPathSegmentBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("path_segment_number", &B::path_segment_number, UShort{}),
                           wire::field("p1_latitude_deg", &B::p1_latitude_deg, kLatitude),
                           wire::field("p1_longitude_deg", &B::p1_longitude_deg, kLongitude),
                           wire::optional(0, "p1_elevation_m", &B::p1_elevation_m, kElevation),
                           wire::field("p2_latitude_deg", &B::p2_latitude_deg, kLatitude),
                           wire::field("p2_longitude_deg", &B::p2_longitude_deg, kLongitude),
                           wire::optional(1, "p2_elevation_m", &B::p2_elevation_m, kElevation),
                           wire::field("weighting_factor", &B::weighting_factor, kWeightingFactor));
  }
};

struct LocalPathSegmentBody {
  std::uint16_t path_segment_number = 0;
  double p1_x_m = 0;
  double p1_y_m = 0;
  std::optional<double> p1_z_m;
  double p2_x_m = 0;
  double p2_y_m = 0;
  std::optional<double> p2_z_m;
  double weighting_factor = 0;
  bool operator==(const LocalPathSegmentBody&) const = default;
  static constexpr auto describe() {
    using B = LocalPathSegmentBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("path_segment_number", &B::path_segment_number, UShort{}),
                           wire::field("p1_x_m", &B::p1_x_m, kLocalXY), wire::field("p1_y_m", &B::p1_y_m, kLocalXY),
                           wire::optional(0, "p1_z_m", &B::p1_z_m, kElevation),
                           wire::field("p2_x_m", &B::p2_x_m, kLocalXY), wire::field("p2_y_m", &B::p2_y_m, kLocalXY),
                           wire::optional(1, "p2_z_m", &B::p2_z_m, kElevation),
                           wire::field("weighting_factor", &B::weighting_factor, kWeightingFactor));
  }
};

struct WaypointNumberBody {
  std::uint16_t waypoint_number = 0;
  bool operator==(const WaypointNumberBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("waypoint_number", &WaypointNumberBody::waypoint_number, UShort{}));
  }
};

// Query Global/Local Path Segment. Part 3 lists Query Local Path Segment with
// the presence vector first, the reverse of its global twin; the RA 3.3 peers
// send the number first for both, and so do we (docs/messages.md).
struct PathSegmentQueryBody {
  std::uint16_t path_segment_number = 0;
  std::uint8_t presence_vector = 0;
  bool operator==(const PathSegmentQueryBody&) const = default;
  static constexpr auto describe() {
    using B = PathSegmentQueryBody;
    return std::make_tuple(wire::field("path_segment_number", &B::path_segment_number, UShort{}),
                           wire::field("presence_vector", &B::presence_vector, Byte{}));
  }
};

struct WaypointCountBody {
  std::uint16_t waypoint_count = 0;
  bool operator==(const WaypointCountBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("waypoint_count", &WaypointCountBody::waypoint_count, UShort{}));
  }
};

struct PathSegmentCountBody {
  std::uint16_t path_segment_count = 0;
  bool operator==(const PathSegmentCountBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("path_segment_count", &PathSegmentCountBody::path_segment_count, UShort{}));
  }
};

struct PlatformSpecificationsBody {
  std::optional<std::string> mobility_platform_name;  // up to 15 characters
  std::optional<double> front_m, back_m, right_m, left_m, bottom_m, top_m;
  std::optional<double> x_cg_m, y_cg_m, z_cg_m;
  std::optional<double> turning_radius_m, wheel_base_m, track_width_m;
  std::optional<double> static_pitch_over_rad, static_roll_over_rad;
  std::optional<double> max_velocity_x_mps, max_velocity_y_mps, max_velocity_z_mps;
  std::optional<double> max_roll_rate_rps, max_pitch_rate_rps, max_yaw_rate_rps;
  bool operator==(const PlatformSpecificationsBody&) const = default;
  static constexpr auto describe() {
    using B = PlatformSpecificationsBody;
    constexpr wire::Scaled<std::uint16_t> extent{0, 32.767};
    constexpr wire::Scaled<std::uint16_t> length{0, 65.535};
    constexpr wire::Scaled<std::uint16_t> over{0, 2.56};
    constexpr wire::Scaled<std::uint16_t> velocity{0, 65.534};
    constexpr wire::Scaled<std::uint16_t> rate{0, 32.767};
    return std::make_tuple(
        wire::presence_vector<std::uint32_t>(),
        wire::optional(0, "mobility_platform_name", &B::mobility_platform_name, wire::Text<15>{}),
        wire::optional(1, "front_m", &B::front_m, extent), wire::optional(2, "back_m", &B::back_m, extent),
        wire::optional(3, "right_m", &B::right_m, extent), wire::optional(4, "left_m", &B::left_m, extent),
        wire::optional(5, "bottom_m", &B::bottom_m, extent), wire::optional(6, "top_m", &B::top_m, extent),
        wire::optional(7, "x_cg_m", &B::x_cg_m, extent), wire::optional(8, "y_cg_m", &B::y_cg_m, extent),
        wire::optional(9, "z_cg_m", &B::z_cg_m, extent),
        wire::optional(10, "turning_radius_m", &B::turning_radius_m, length),
        wire::optional(11, "wheel_base_m", &B::wheel_base_m, length),
        wire::optional(12, "track_width_m", &B::track_width_m, length),
        wire::optional(13, "static_pitch_over_rad", &B::static_pitch_over_rad, over),
        wire::optional(14, "static_roll_over_rad", &B::static_roll_over_rad, over),
        wire::optional(15, "max_velocity_x_mps", &B::max_velocity_x_mps, velocity),
        wire::optional(16, "max_velocity_y_mps", &B::max_velocity_y_mps, velocity),
        wire::optional(17, "max_velocity_z_mps", &B::max_velocity_z_mps, velocity),
        wire::optional(18, "max_roll_rate_rps", &B::max_roll_rate_rps, rate),
        wire::optional(19, "max_pitch_rate_rps", &B::max_pitch_rate_rps, rate),
        wire::optional(20, "max_yaw_rate_rps", &B::max_yaw_rate_rps, rate));
  }
};

struct PlatformOperationalDataBody {
  std::optional<double> engine_temperature_c;
  std::optional<std::uint32_t> odometer_m;  // cumulative distance, whole metres
  std::optional<double> battery_voltage_percent;
  std::optional<double> fuel_level_percent;
  std::optional<double> oil_pressure_percent;
  bool operator==(const PlatformOperationalDataBody&) const = default;
  static constexpr auto describe() {
    using B = PlatformOperationalDataBody;
    return std::make_tuple(
        wire::presence_vector<std::uint8_t>(),
        wire::optional(0, "engine_temperature_c", &B::engine_temperature_c, wire::Scaled<std::int16_t>{-75, 180}),
        wire::optional(1, "odometer_m", &B::odometer_m, UInt{}),
        wire::optional(2, "battery_voltage_percent", &B::battery_voltage_percent, wire::Scaled<std::uint8_t>{0, 127}),
        wire::optional(3, "fuel_level_percent", &B::fuel_level_percent, wire::Scaled<std::uint8_t>{0, 100}),
        wire::optional(4, "oil_pressure_percent", &B::oil_pressure_percent, wire::Scaled<std::uint8_t>{0, 127}));
  }
};

inline constexpr wire::Scaled<std::uint32_t> kPositionRms{0, 100};
inline constexpr wire::Scaled<std::uint16_t> kAttitudeRms{0, kPi};

struct GlobalPoseBody {
  std::optional<double> latitude_deg;  // WGS 84
  std::optional<double> longitude_deg;
  std::optional<double> elevation_m;
  std::optional<double> position_rms_m;
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  std::optional<double> attitude_rms_rad;
  std::optional<TimeStamp> time_stamp;
  bool operator==(const GlobalPoseBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = GlobalPoseBody;
    return std::make_tuple(wire::presence_vector<std::uint16_t>(),
                           wire::optional(0, "latitude_deg", &B::latitude_deg, kLatitude),
                           wire::optional(1, "longitude_deg", &B::longitude_deg, kLongitude),
                           wire::optional(2, "elevation_m", &B::elevation_m, kElevation),
                           wire::optional(3, "position_rms_m", &B::position_rms_m, kPositionRms),
                           wire::optional(4, "roll_rad", &B::roll_rad, kAngleShort),
                           wire::optional(5, "pitch_rad", &B::pitch_rad, kAngleShort),
                           wire::optional(6, "yaw_rad", &B::yaw_rad, kAngleShort),
                           wire::optional(7, "attitude_rms_rad", &B::attitude_rms_rad, kAttitudeRms),
                           wire::optional(8, "time_stamp", &B::time_stamp, wire::Time{}));
  }
};

struct LocalPoseBody {
  std::optional<double> x_m;
  std::optional<double> y_m;
  std::optional<double> z_m;
  std::optional<double> position_rms_m;
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;
  std::optional<double> attitude_rms_rad;
  std::optional<TimeStamp> time_stamp;
  bool operator==(const LocalPoseBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = LocalPoseBody;
    // JSS: z over x and y's range, not an elevation's.
    constexpr auto z = kElevation.jss(-100'000, 100'000);
    return std::make_tuple(wire::presence_vector<std::uint16_t>(), wire::optional(0, "x_m", &B::x_m, kLocalXY),
                           wire::optional(1, "y_m", &B::y_m, kLocalXY), wire::optional(2, "z_m", &B::z_m, z),
                           wire::optional(3, "position_rms_m", &B::position_rms_m, kPositionRms),
                           wire::optional(4, "roll_rad", &B::roll_rad, kAngleShort),
                           wire::optional(5, "pitch_rad", &B::pitch_rad, kAngleShort),
                           wire::optional(6, "yaw_rad", &B::yaw_rad, kAngleShort),
                           wire::optional(7, "attitude_rms_rad", &B::attitude_rms_rad, kAttitudeRms),
                           wire::optional(8, "time_stamp", &B::time_stamp, wire::Time{}));
  }
};

struct VelocityStateBody {
  std::optional<double> velocity_x_mps;
  std::optional<double> velocity_y_mps;
  std::optional<double> velocity_z_mps;
  std::optional<double> velocity_rms_mps;
  std::optional<double> roll_rate_rps;
  std::optional<double> pitch_rate_rps;
  std::optional<double> yaw_rate_rps;
  std::optional<double> rate_rms_rps;
  std::optional<TimeStamp> time_stamp;
  bool operator==(const VelocityStateBody&) const = default;
  static constexpr bool kSharedWithJss = true;  // also a JSS body (jaus/jss/messages), read in Dialect::jss
  static constexpr auto describe() {
    using B = VelocityStateBody;
    // JSS has its own ranges: +-327.68 m/s and +-32.768 rad/s, unsigned.
    constexpr auto velocity = wire::Scaled<std::int32_t>{-65.534, 65.534}.jss(-327.68, 327.67);
    constexpr auto rate = wire::Scaled<std::int16_t>{-32.767, 32.767}.jss(-32.768, 32.767);
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

using SetWrenchEffort = Message<0x0405, "Set Wrench Effort", WrenchEffortBody>;
using SetDiscreteDevices = Message<0x0406, "Set Discrete Devices", DiscreteDevicesBody>;
using SetGlobalVector = Message<0x0407, "Set Global Vector", GlobalVectorBody>;
using SetLocalVector = Message<0x0408, "Set Local Vector", LocalVectorBody>;
using SetTravelSpeed = Message<0x040A, "Set Travel Speed", TravelSpeedBody>;
using SetGlobalWaypoint = Message<0x040C, "Set Global Waypoint", GlobalWaypointBody>;
using SetLocalWaypoint = Message<0x040D, "Set Local Waypoint", LocalWaypointBody>;
using SetGlobalPathSegment = Message<0x040F, "Set Global Path Segment", GlobalPathSegmentBody>;
using SetLocalPathSegment = Message<0x0410, "Set Local Path Segment", LocalPathSegmentBody>;

using QueryPlatformSpecifications =
    Message<0x2400, "Query Platform Specifications", PresenceQueryBody<std::uint32_t>>;
using QueryPlatformOperationalData =
    Message<0x2401, "Query Platform Operational Data", PresenceQueryBody<std::uint8_t>>;
using QueryGlobalPose = Message<0x2402, "Query Global Pose", PresenceQueryBody<std::uint16_t>>;
using QueryLocalPose = Message<0x2403, "Query Local Pose", PresenceQueryBody<std::uint16_t>>;
using QueryVelocityState = Message<0x2404, "Query Velocity State", PresenceQueryBody<std::uint16_t>>;
using QueryWrenchEffort = Message<0x2405, "Query Wrench Effort", PresenceQueryBody<std::uint16_t>>;
using QueryDiscreteDevices = Message<0x2406, "Query Discrete Devices", PresenceQueryBody<std::uint8_t>>;
using QueryGlobalVector = Message<0x2407, "Query Global Vector", PresenceQueryBody<std::uint8_t>>;
using QueryLocalVector = Message<0x2408, "Query Local Vector", Empty>;
using QueryTravelSpeed = Message<0x240A, "Query Travel Speed", Empty>;
using QueryWaypointCount = Message<0x240B, "Query Waypoint Count", Empty>;
using QueryGlobalWaypoint = Message<0x240C, "Query Global Waypoint", WaypointNumberBody>;
using QueryLocalWaypoint = Message<0x240D, "Query Local Waypoint", WaypointNumberBody>;
using QueryPathSegmentCount = Message<0x240E, "Query Path Segment Count", Empty>;
using QueryGlobalPathSegment = Message<0x240F, "Query Global Path Segment", PathSegmentQueryBody>;
using QueryLocalPathSegment = Message<0x2410, "Query Local Path Segment", PathSegmentQueryBody>;

using ReportPlatformSpecifications = Message<0x4400, "Report Platform Specifications", PlatformSpecificationsBody>;
using ReportPlatformOperationalData =
    Message<0x4401, "Report Platform Operational Data", PlatformOperationalDataBody>;
using ReportGlobalPose = Message<0x4402, "Report Global Pose", GlobalPoseBody>;
using ReportLocalPose = Message<0x4403, "Report Local Pose", LocalPoseBody>;
using ReportVelocityState = Message<0x4404, "Report Velocity State", VelocityStateBody>;
using ReportWrenchEffort = Message<0x4405, "Report Wrench Effort", WrenchEffortBody>;
using ReportDiscreteDevices = Message<0x4406, "Report Discrete Devices", DiscreteDevicesBody>;
using ReportGlobalVector = Message<0x4407, "Report Global Vector", GlobalVectorBody>;
using ReportLocalVector = Message<0x4408, "Report Local Vector", LocalVectorBody>;
using ReportTravelSpeed = Message<0x440A, "Report Travel Speed", TravelSpeedBody>;
using ReportWaypointCount = Message<0x440B, "Report Waypoint Count", WaypointCountBody>;
using ReportGlobalWaypoint = Message<0x440C, "Report Global Waypoint", GlobalWaypointBody>;
using ReportLocalWaypoint = Message<0x440D, "Report Local Waypoint", LocalWaypointBody>;
using ReportPathSegmentCount = Message<0x440E, "Report Path Segment Count", PathSegmentCountBody>;
using ReportGlobalPathSegment = Message<0x440F, "Report Global Path Segment", GlobalPathSegmentBody>;
using ReportLocalPathSegment = Message<0x4410, "Report Local Path Segment", LocalPathSegmentBody>;

using PlatformMessages =
    TypeList<SetWrenchEffort, SetDiscreteDevices, SetGlobalVector, SetLocalVector, SetTravelSpeed, SetGlobalWaypoint,
             SetLocalWaypoint, SetGlobalPathSegment, SetLocalPathSegment, QueryPlatformSpecifications,
             QueryPlatformOperationalData, QueryGlobalPose, QueryLocalPose, QueryVelocityState, QueryWrenchEffort,
             QueryDiscreteDevices, QueryGlobalVector, QueryLocalVector, QueryTravelSpeed, QueryWaypointCount,
             QueryGlobalWaypoint, QueryLocalWaypoint, QueryPathSegmentCount, QueryGlobalPathSegment,
             QueryLocalPathSegment, ReportPlatformSpecifications, ReportPlatformOperationalData, ReportGlobalPose,
             ReportLocalPose, ReportVelocityState, ReportWrenchEffort, ReportDiscreteDevices, ReportGlobalVector,
             ReportLocalVector, ReportTravelSpeed, ReportWaypointCount, ReportGlobalWaypoint, ReportLocalWaypoint,
             ReportPathSegmentCount, ReportGlobalPathSegment, ReportLocalPathSegment>;

}  // namespace jaus::msg
