// A local Cartesian frame tangent to the WGS 84 ellipsoid at a datum
// (GeographicLib's LocalCartesian), in JAUS's axes: x north, y east, z down,
// metres from the datum. The one place a local position becomes latitude,
// longitude and altitude: the simulated vehicle and the Clearpath bridge's
// dead reckoning both use it, and the global drivers project their routes
// into one.
#pragma once

#include <memory>

#include "jaus/components/pose_source.hpp"

namespace jaus::components {

class LocalFrame {
 public:
  explicit LocalFrame(const GeoPosition& datum);
  ~LocalFrame();
  LocalFrame(LocalFrame&&) noexcept;
  LocalFrame& operator=(LocalFrame&&) noexcept;

  const GeoPosition& datum() const { return datum_; }
  GeoPosition to_geo(const LocalPosition& ned) const;
  // The inverse of to_geo: where `geo` lies in this frame (the global
  // waypoint and path segment drivers follow a global route in a frame whose
  // datum is the vehicle's position when the route starts).
  LocalPosition to_local(const GeoPosition& geo) const;

 private:
  struct Geodesy;
  GeoPosition datum_;
  std::unique_ptr<Geodesy> geodesy_;
};

}  // namespace jaus::components
