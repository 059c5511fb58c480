// What a pose sample says as a JAUS report, written once for every component
// that reports it (the global pose sensor, the local pose sensor): which
// fields a sample fills, angles wrapped to the range their fields encode, an
// RMS only with its value, and the time the sample was taken.
#pragma once

#include "jaus/components/pose_source.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

// Latitude, longitude, elevation (with their RMS) when the sample has a
// position; attitude (with its RMS) when it has one.
msg::ReportGlobalPose global_pose_report(const PoseSample& sample);
// x, y, z in the source's local frame (with the position RMS) when the sample
// has a local position; attitude as above. Without a local position the
// report carries no x, y, z: never a made-up position.
msg::ReportLocalPose local_pose_report(const PoseSample& sample);

}  // namespace jaus::components
