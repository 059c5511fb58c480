// LocalFrame::to_local, the inverse of to_geo: the global waypoint driver
// projects its waypoints and the vehicle with it.
#include <gtest/gtest.h>

#include "jaus/components/local_frame.hpp"

namespace jaus::components {
namespace {

TEST(LocalFrameToLocal, TheDatumIsTheOrigin) {
  const LocalFrame frame(GeoPosition{45.0, -73.0, 50.0});
  const LocalPosition p = frame.to_local(frame.datum());
  EXPECT_NEAR(p.x_m, 0, 1e-9);
  EXPECT_NEAR(p.y_m, 0, 1e-9);
  EXPECT_NEAR(p.z_m, 0, 1e-9);
}

TEST(LocalFrameToLocal, RoundTripsThroughGeoWithinAMillimetre) {
  const LocalFrame frame(GeoPosition{45.0, -73.0, 50.0});
  for (const LocalPosition ned : {LocalPosition{8, 0, 0}, LocalPosition{8, 8, 0}, LocalPosition{-250, 1200, -3},
                                  LocalPosition{0.01, -0.02, 0.5}}) {
    const LocalPosition back = frame.to_local(frame.to_geo(ned));
    EXPECT_NEAR(back.x_m, ned.x_m, 1e-3);
    EXPECT_NEAR(back.y_m, ned.y_m, 1e-3);
    EXPECT_NEAR(back.z_m, ned.z_m, 1e-3);
  }
}

TEST(LocalFrameToLocal, NorthIsXAndEastIsY) {
  const LocalFrame frame(GeoPosition{45.0, -73.0, 50.0});
  // About 111 km per degree of latitude, 78.8 km per degree of longitude at 45 N.
  const LocalPosition north = frame.to_local(GeoPosition{45.001, -73.0, 50.0});
  EXPECT_NEAR(north.x_m, 111.1, 0.2);
  EXPECT_NEAR(north.y_m, 0, 0.01);
  const LocalPosition east = frame.to_local(GeoPosition{45.0, -72.999, 50.0});
  EXPECT_NEAR(east.x_m, 0, 0.01);
  EXPECT_NEAR(east.y_m, 78.8, 0.2);
  EXPECT_GT(east.z_m, 0);  // the ellipsoid curves down away from the tangent plane: z (down) grows
}

}  // namespace
}  // namespace jaus::components
