#include "jaus/components/local_frame.hpp"

#include <GeographicLib/LocalCartesian.hpp>

namespace jaus::components {

struct LocalFrame::Geodesy {
  GeographicLib::LocalCartesian local;
};

LocalFrame::LocalFrame(const GeoPosition& datum)
    : datum_(datum),
      geodesy_(std::make_unique<Geodesy>(
          Geodesy{GeographicLib::LocalCartesian(datum.latitude_deg, datum.longitude_deg, datum.altitude_m)})) {}

LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;

GeoPosition LocalFrame::to_geo(const LocalPosition& ned) const {
  // GeographicLib's local frame is east, north, up.
  const Vector3 enu = ned_to_enu(Vector3{ned.x_m, ned.y_m, ned.z_m});
  GeoPosition geo;
  geodesy_->local.Reverse(enu.x, enu.y, enu.z, geo.latitude_deg, geo.longitude_deg, geo.altitude_m);
  return geo;
}

LocalPosition LocalFrame::to_local(const GeoPosition& geo) const {
  Vector3 enu;
  geodesy_->local.Forward(geo.latitude_deg, geo.longitude_deg, geo.altitude_m, enu.x, enu.y, enu.z);
  const Vector3 ned = enu_to_ned(enu);
  return LocalPosition{ned.x, ned.y, ned.z};
}

}  // namespace jaus::components
