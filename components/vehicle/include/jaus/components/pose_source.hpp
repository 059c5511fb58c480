// The hardware interface of the pose and velocity sensors: what a navigation
// source knows of the platform, already in JAUS's frames (body x forward,
// y right, z down; attitude roll, pitch, yaw with yaw the heading from true
// north, clockwise; position WGS 84), each value with its accuracy, all from
// one sample taken at one time. Backends: the simulated vehicle
// (simulated_vehicle.hpp) and the Clearpath platform (bridge/); conversions
// from other conventions happen once, in navigation_frames.hpp.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/components/drive.hpp"
#include "jaus/components/navigation_frames.hpp"

namespace jaus::components {

struct GeoPosition {
  double latitude_deg = 0, longitude_deg = 0;
  double altitude_m = 0;  // above the WGS 84 ellipsoid
  bool operator==(const GeoPosition&) const = default;
};

// A position in the configured local frame: origin at its datum, x north,
// y east, z down (metres).
struct LocalPosition {
  double x_m = 0, y_m = 0, z_m = 0;
  bool operator==(const LocalPosition&) const = default;
};

// One sample; a value the source does not have is absent, and so is its RMS.
struct PoseSample {
  rt::TimePoint taken_at{};  // on the runtime's clock: how old the sample is
  rt::UtcTime taken_utc{};   // the reports' time stamp

  std::optional<GeoPosition> position;
  std::optional<LocalPosition> local_position;
  std::optional<double> position_rms_m;  // of both positions
  std::optional<EulerAngles> attitude;   // rad; yaw = heading from north, clockwise
  std::optional<double> attitude_rms_rad;

  std::optional<Axes> velocity_mps;      // body frame
  std::optional<double> velocity_rms_mps;
  std::optional<Axes> rates_rps;         // roll, pitch, yaw rates, body frame
  std::optional<double> rate_rms_rps;
};

class PoseSource {
 public:
  // Its name among the hardware a host offers a component kind (rt::Backends).
  static constexpr std::string_view kInterface = "pose_source";
  static constexpr std::string_view kDescription = "a vehicle pose source";

  virtual ~PoseSource() = default;
  // The latest sample; none before the source has produced one.
  virtual std::optional<PoseSample> sample() = 0;
  // How often the source produces a new sample (Hz): reports on service
  // connections go no faster.
  virtual double update_rate_hz() const = 0;
};

// For a component whose figures are in the local frame (the local pose
// sensor, the local waypoint and path segment drivers): a source known to
// have no local frame (a sample without a local position) is refused, saying
// why; a source with no sample yet is taken as it comes.
inline Expected<void> require_local_frame(PoseSource& source, std::string_view kind) {
  if (const auto sample = source.sample(); sample && !sample->local_position)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 std::string(kind) + " needs a pose source with a local frame (vehicle.local_frame: true)"));
  return {};
}

}  // namespace jaus::components
