#include "jaus/components/global_waypoint_driver.hpp"

namespace jaus::components {

Expected<GlobalWaypoints::Frame> GlobalWaypoints::Frame::at(const PoseSample& start) {
  if (!start.position)
    return unexpected(make_error(ErrorCode::invalid_argument, "the pose source gives no geodetic position"));
  return Frame(LocalFrame(*start.position));
}

std::optional<guidance::Point2> GlobalWaypoints::Frame::vehicle(const PoseSample& pose) const {
  if (!pose.position) return std::nullopt;
  const LocalPosition p = frame_.to_local(*pose.position);
  return guidance::Point2{p.x_m, p.y_m};
}

// On the datum's altitude: a ground vehicle follows latitude and longitude only.
guidance::Point2 GlobalWaypoints::Frame::point(const Body& waypoint) const {
  const LocalPosition p =
      frame_.to_local(GeoPosition{waypoint.latitude_deg, waypoint.longitude_deg, frame_.datum().altitude_m});
  return {p.x_m, p.y_m};
}

}  // namespace jaus::components
