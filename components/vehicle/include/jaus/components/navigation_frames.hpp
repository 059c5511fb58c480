// Angles and axes between the conventions a vehicle meets and JAUS's own.
// The one place these conversions live: the simulated vehicle and the
// Clearpath bridge (bridge/frame_conventions.hpp, for Clearpath's body axes)
// both use them.
//
//   JAUS: body x forward, y right, z down (FRD); a global yaw is the heading
//         from true north, clockwise (RA 3.x Part 3, Report Global Pose: Yaw);
//         a local frame's axes are x north, y east, z down (NED).
//   ENU:  east, north, up, the local Cartesian frame of GeographicLib; a yaw
//         is counter-clockwise from east.
#pragma once

namespace jaus::components {

struct Vector3 {
  double x = 0, y = 0, z = 0;
  bool operator==(const Vector3&) const = default;
};

// Roll about x, pitch about y, yaw about z, radians.
struct EulerAngles {
  double roll = 0, pitch = 0, yaw = 0;
  bool operator==(const EulerAngles&) const = default;
};

// An angle in (-pi, pi], the range JAUS's angle fields encode.
double wrap_angle(double radians);

// A world yaw counter-clockwise from east (ENU) <-> a heading clockwise from
// north (NED), both wrapped to (-pi, pi].
double enu_yaw_to_ned_heading(double yaw_from_east_ccw);
double ned_heading_to_enu_yaw(double heading_from_north_cw);

// A position or vector, east-north-up <-> north-east-down.
Vector3 enu_to_ned(const Vector3& enu);
Vector3 ned_to_enu(const Vector3& ned);

}  // namespace jaus::components
