// Where Clearpath's body axes and turn sense become JAUS's and back. The
// general conversions (Vector3, EulerAngles, wrap_angle, ENU yaw <-> NED
// heading, ENU <-> NED) live in components/vehicle's navigation_frames.hpp,
// shared with the simulated vehicle; they are re-exported here so the
// bridge's code says bridge::wrap_angle as before.
//
//   Clearpath: body x forward, y left, z up (FLU); yaw positive turning left
//              (counter-clockwise seen from above); a world yaw is measured
//              from the platform's x reference, counter-clockwise (ENU-like).
//   JAUS:      body x forward, y right, z down (FRD); yaw positive turning
//              right; a global yaw is the heading from true north, clockwise
//              (RA 3.x Part 3, Report Global Pose: Yaw).
//
// Turning FLU into FRD is a half turn about x: y and z change sign, so a
// vector (x, y, z) becomes (x, -y, -z), a rate (p, q, r) becomes (p, -q, -r)
// and Euler angles (roll, pitch, yaw) become (roll, -pitch, -yaw). The world
// heading also moves its origin from east to north: heading = pi/2 - yaw.
// docs/bridge.md states where each Clearpath message's values go.
#pragma once

#include "jaus/components/navigation_frames.hpp"

namespace jaus::bridge {

using components::enu_yaw_to_ned_heading;
using components::EulerAngles;
using components::ned_heading_to_enu_yaw;
using components::Vector3;
using components::wrap_angle;

// Body-frame vectors (positions, velocities, accelerations, angular rates).
Vector3 flu_to_frd(const Vector3& clearpath);
Vector3 frd_to_flu(const Vector3& jaus);

// Body attitude: roll kept, pitch and yaw negated (yaw wrapped).
EulerAngles flu_to_frd(const EulerAngles& clearpath);
EulerAngles frd_to_flu(const EulerAngles& jaus);

// A turn command: JAUS's rotational effort or rate is positive to the right,
// Clearpath's to the left.
inline double jaus_turn_to_clearpath(double turn_right_positive) { return -turn_right_positive; }
inline double clearpath_turn_to_jaus(double turn_left_positive) { return -turn_left_positive; }

}  // namespace jaus::bridge
