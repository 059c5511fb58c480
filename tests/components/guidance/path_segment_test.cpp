// Path segments as Part 3 gives them, with the rational quadratic Bezier as
// the curve: end points, tangents, the straight line at weight 0, the exact
// circle, arc length, projection and cross-track sign.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jaus/components/guidance/path_segment.hpp"

namespace jaus::components::guidance {
namespace {

using std::numbers::pi;

void expect_near(const Point2& a, const Point2& b, double tolerance = 1e-12) {
  EXPECT_NEAR(a.x_m, b.x_m, tolerance);
  EXPECT_NEAR(a.y_m, b.y_m, tolerance);
}

// The unit direction of v.
Point2 unit(const Point2& v) {
  const double n = std::hypot(v.x_m, v.y_m);
  return {v.x_m / n, v.y_m / n};
}

TEST(PathSegment, StartsAtP0AndEndsAtP2WhateverTheWeight) {
  for (double w : {0.0, 0.3, 1.0, 7.0, 500.0}) {
    const PathSegment s{{1, 2}, {5, 2}, {5, 6}, w};
    expect_near(s.point_at(0), {1, 2});
    expect_near(s.point_at(1), {5, 6});
    expect_near(s.point_at(-3), {1, 2});  // clamped
  }
}

TEST(PathSegment, WeightZeroIsTheStraightLineFromP0ToP2) {
  const PathSegment s{{0, 0}, {100, -40}, {4, 4}, 0};  // P1 far away: ignored
  expect_near(s.point_at(0.5), {2, 2});
  for (double t = 0; t <= 1; t += 0.1) {
    const Point2 p = s.point_at(t);
    EXPECT_NEAR(p.x_m, p.y_m, 1e-12);
    expect_near(s.tangent_at(t), unit({1, 1}), 1e-9);
  }
  expect_near(s.derivative_at(0), {0, 0});  // the parametrisation stalls at the ends: tangent_at() does not
}

TEST(PathSegment, TangentsLeaveTowardsP1AndArriveFromIt) {
  for (double w : {0.2, 1.0, 30.0}) {
    const PathSegment s{{0, 0}, {4, 0}, {4, 3}, w};
    expect_near(unit(s.derivative_at(0)), {1, 0}, 1e-12);  // along P1 - P0
    expect_near(unit(s.derivative_at(1)), {0, 1}, 1e-12);  // along P2 - P1
    expect_near(s.tangent_at(0), {1, 0}, 1e-12);
    expect_near(s.tangent_at(1), {0, 1}, 1e-12);
  }
}

TEST(PathSegment, WeightOneIsTheQuadraticBezierAndHeavyWeightsPullTowardsP1) {
  const PathSegment parabola{{0, 0}, {4, 0}, {4, 4}, 1};
  expect_near(parabola.point_at(0.5), {3, 1});  // (P0 + 2 P1 + P2) / 4
  const PathSegment heavy{{0, 0}, {4, 0}, {4, 4}, 500};
  EXPECT_LT(distance(heavy.point_at(0.5), {4, 0}), 0.01);
}

TEST(PathSegment, WeightCosHalfAngleIsAnExactCircularArc) {
  // A quarter circle of radius 3 about (0, 3): from (0, 0) heading north to (3, 3) heading east.
  const PathSegment s{{0, 0}, {3, 0}, {3, 3}, std::cos(pi / 4)};
  for (double t = 0; t <= 1; t += 0.05) EXPECT_NEAR(distance(s.point_at(t), {0, 3}), 3, 1e-12);
  auto path = Path::make({0, 0}, {{{3, 0}, {3, 3}, std::cos(pi / 4)}});
  ASSERT_TRUE(path);
  EXPECT_NEAR(path->length_m(), 3 * pi / 2, 0.01);
}

TEST(Path, ChainsEachSegmentFromThePreviousEndAndMeasuresArcLength) {
  auto path = Path::make({1, 1}, {{{3, 1}, {5, 1}, 0}, {{5, 3}, {5, 5}, 0}, {{0, 0}, {2, 5}, 0}});
  ASSERT_TRUE(path);
  ASSERT_EQ(path->segments().size(), 3u);
  EXPECT_EQ(path->segments()[0].p0, (Point2{1, 1}));
  EXPECT_EQ(path->segments()[1].p0, (Point2{5, 1}));
  EXPECT_EQ(path->segments()[2].p0, (Point2{5, 5}));
  EXPECT_NEAR(path->length_m(), 4 + 4 + 3, 1e-9);
  expect_near(path->point_at_arc(2), {3, 1}, 1e-9);
  expect_near(path->point_at_arc(6), {5, 3}, 1e-9);
  expect_near(path->point_at_arc(100), {2, 5}, 1e-9);
  expect_near(path->point_at_arc(-1), {1, 1}, 1e-9);
  EXPECT_EQ(path->end(), (Point2{2, 5}));
}

TEST(Path, RejectsNoSegmentsWeightsOutsideTheRangeAndNonFinitePoints) {
  EXPECT_FALSE(Path::make({0, 0}, {}));
  EXPECT_FALSE(Path::make({0, 0}, {{{1, 0}, {2, 0}, -0.1}}));
  EXPECT_FALSE(Path::make({0, 0}, {{{1, 0}, {2, 0}, 500.5}}));
  EXPECT_FALSE(Path::make({0, 0}, {{{1, 0}, {2, std::nan("")}, 1}}));
  EXPECT_TRUE(Path::make({0, 0}, {{{1, 0}, {2, 0}, 500}}));
}

TEST(Path, TheCrossTrackErrorIsPositiveToTheRightOfTheDirectionOfTravel) {
  auto north = Path::make({0, 0}, {{{5, 0}, {10, 0}, 0}});
  ASSERT_TRUE(north);
  auto at = north->project({4, 1.5});  // east of a northbound path: right
  EXPECT_NEAR(at.cross_track_m, 1.5, 1e-9);
  EXPECT_NEAR(at.arc_length_m, 4, 1e-9);
  expect_near(at.point, {4, 0}, 1e-9);
  EXPECT_NEAR(north->project({4, -2}).cross_track_m, -2, 1e-9);

  auto south = Path::make({10, 0}, {{{5, 0}, {0, 0}, 0}});
  ASSERT_TRUE(south);
  EXPECT_NEAR(south->project({4, 1.5}).cross_track_m, -1.5, 1e-9);  // east of southbound: left

  // On a right-hand curve (the quarter circle), inside the bend is right of it.
  auto arc = Path::make({0, 0}, {{{3, 0}, {3, 3}, std::cos(pi / 4)}});
  ASSERT_TRUE(arc);
  const Point2 inside{3 * std::sin(pi / 4) * 0.9, 3 - 3 * std::cos(pi / 4) * 0.9};
  const auto p = arc->project(inside);
  EXPECT_NEAR(p.cross_track_m, 0.3, 0.01);
  EXPECT_EQ(p.segment, 0u);
  EXPECT_NEAR(p.t, 0.5, 0.02);
}

TEST(Path, ProjectionWithinAWindowFollowsAPathThatComesBackNearItself) {
  // Out north 10 m, then back south 0.5 m to the east.
  auto path = Path::make({0, 0}, {{{5, 0}, {10, 0}, 0}, {{10, 0.25}, {10, 0.5}, 0}, {{5, 0.5}, {0, 0.5}, 0}});
  ASSERT_TRUE(path);
  EXPECT_NEAR(path->project({2, 0.1}).arc_length_m, 2, 1e-9);  // the whole path: the nearest leg
  EXPECT_NEAR(path->project({2, 0.1}, 15, 30).arc_length_m, 18.5, 1e-9);  // the return leg
}

TEST(PathPursuit, FollowsFromItsProgressAndStopsOnAPoseThatIsNotFinite) {
  auto path = Path::make({0, 0}, {{{5, 0}, {10, 0}, 0}});
  ASSERT_TRUE(path);
  PursuitConfig config;
  config.lookahead_m = 2;
  auto pursuit = PathPursuit::make(*path, config, {});
  ASSERT_TRUE(pursuit);
  auto out = pursuit->update({3, 0.4, 0});
  EXPECT_NEAR(out.cross_track_m, 0.4, 1e-9);
  EXPECT_NEAR(out.lookahead.x_m, 5, 1e-9);
  EXPECT_LT(out.command.curvature_per_m, 0);  // right of the path: back left
  EXPECT_NEAR(pursuit->progress_m(), 3, 1e-9);
  out = pursuit->update({std::nan(""), 0, 0});
  EXPECT_EQ(out.effort, WrenchEffort{});
  EXPECT_NEAR(pursuit->progress_m(), 3, 1e-9);
  EXPECT_FALSE(pursuit->finished());
  out = pursuit->update({9.8, 0, 0});
  EXPECT_TRUE(out.finished);
  EXPECT_EQ(out.effort, WrenchEffort{});
  EXPECT_EQ(path->project({std::nan(""), 1}).arc_length_m, 0);
}

}  // namespace
}  // namespace jaus::components::guidance
