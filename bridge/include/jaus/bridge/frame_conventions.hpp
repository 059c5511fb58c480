// The one place where Clearpath's axes and angles become JAUS's and back.
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

namespace jaus::bridge {

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

// Body-frame vectors (positions, velocities, accelerations, angular rates).
Vector3 flu_to_frd(const Vector3& clearpath);
Vector3 frd_to_flu(const Vector3& jaus);

// Body attitude: roll kept, pitch and yaw negated (yaw wrapped).
EulerAngles flu_to_frd(const EulerAngles& clearpath);
EulerAngles frd_to_flu(const EulerAngles& jaus);

// A world yaw counter-clockwise from east (ENU) <-> a heading clockwise from
// north (NED), both wrapped to (-pi, pi].
double enu_yaw_to_ned_heading(double yaw_from_east_ccw);
double ned_heading_to_enu_yaw(double heading_from_north_cw);

// A turn command: JAUS's rotational effort or rate is positive to the right,
// Clearpath's to the left.
inline double jaus_turn_to_clearpath(double turn_right_positive) { return -turn_right_positive; }
inline double clearpath_turn_to_jaus(double turn_left_positive) { return -turn_left_positive; }

}  // namespace jaus::bridge
