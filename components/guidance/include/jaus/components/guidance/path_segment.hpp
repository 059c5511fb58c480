// The RA's path segments (Part 3, Code 040Fh Set Global Path Segment and
// 0410h Set Local Path Segment) as curves, and their pursuit.
//
// Part 3 gives each segment three points and a weighting factor: P0 (the
// platform's position for segment 0, else the previous segment's P2), P1,
// P2, and a factor from 0 to 500, "zero = a straight line". It does not give
// the curve. Our decision: the rational quadratic Bezier curve with P1's
// weight w (the form JAUS's later mobility service set, AS6009, states):
//
//   B(t) = ((1-t)^2 P0 + 2 t (1-t) w P1 + t^2 P2) / ((1-t)^2 + 2 t (1-t) w + t^2),  t in [0, 1]
//
// It fits every word of Part 3: it starts at P0 and ends at P2; w = 0 is the
// straight line P0-P2 (P1 is ignored); w = 1 is the ordinary quadratic Bezier
// (a parabola), w < 1 an ellipse's arc, w > 1 a hyperbola's, pulled towards
// P1 as w grows (at 500 nearly the corner P0-P1-P2). For w > 0 it leaves P0
// towards P1 and arrives at P2 from P1, so a P1 on the line through the
// previous segment's P1 and P2 gives a smooth joint. The weight here is the
// factor's value (0..500), not the wire's scaled integer.
#pragma once

#include <cstddef>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/guidance/pursuit.hpp"

namespace jaus::components::guidance {

struct PathSegment {
  Point2 p0, p1, p2;
  double weight = 0;  // 0..500

  Point2 point_at(double t) const;  // t clamped to [0, 1]
  // dB/dt (not unit). Zero at the ends when w = 0 (the parametrisation
  // stalls there, the line does not), and where P1 = P0 or P2.
  Point2 derivative_at(double t) const;
  // The unit direction of travel at t: P2 - P0 for w = 0, else the
  // derivative's, else the chord through points either side; zero only for a
  // segment of no length.
  Point2 tangent_at(double t) const;
};

// P1, P2 and the factor of one Set ... Path Segment message.
struct SegmentSpec {
  Point2 p1, p2;
  double weight = 0;
};

// Where a point is nearest the path.
struct PathProjection {
  double arc_length_m = 0;    // from the path's start
  Point2 point;               // on the path
  double cross_track_m = 0;   // distance from the path, positive to the right of its direction of travel
  std::size_t segment = 0;
  double t = 0;               // the segment's parameter there
};

// A chain of segments, P0 of the first given (the platform's position when
// the driver starts), each next P0 the previous P2, measured by arc length.
// The curves are flattened once into a polyline within 1 cm of them (adaptive
// subdivision, so a heavy weight's sharp bend near P1 keeps its shape); arc
// lengths, projections and points ahead are on that polyline, tangents on the
// curves.
class Path {
 public:
  // Errors: no segments, a point not finite, a weight outside 0..500.
  static Expected<Path> make(const Point2& start, const std::vector<SegmentSpec>& segments);

  const std::vector<PathSegment>& segments() const { return segments_; }
  double length_m() const { return cumulative_.back(); }
  Point2 end() const { return segments_.back().p2; }

  // The point `s` metres along (clamped to the path).
  Point2 point_at_arc(double s) const;
  // The nearest point of the path between arc lengths `from` and `to`
  // (clamped to the path; the whole path by default). A driver searches near
  // its last progress, so a path that comes back near itself is followed in
  // order. A point that is not finite projects to the start.
  PathProjection project(const Point2& p, double from = 0, double to = 1e300) const;

 private:
  struct Sample {
    Point2 point;
    std::size_t segment;
    double t;
  };
  Path() = default;
  std::vector<PathSegment> segments_;
  std::vector<Sample> samples_;
  std::vector<double> cumulative_;  // arc length at each sample
};

// Pure pursuit along a Path: the lookahead point is lookahead_m of arc length
// ahead of the vehicle's projection, the speed slows to stop at the end, and
// arriving within arrival_tolerance_m of the end (with the whole path driven)
// finishes it. The projection is searched from the last progress, a little
// back to 2 lookaheads plus 5 m ahead, so the vehicle follows the path in
// order even where it crosses itself.
class PathPursuit {
 public:
  static Expected<PathPursuit> make(Path path, const PursuitConfig& config, const VehicleLimits& limits);

  // target: the segment being followed. A pose that is not finite gives the
  // zero command and changes nothing.
  PursuitOutput update(const Pose2& pose);
  bool finished() const { return finished_; }
  double progress_m() const { return progress_; }
  const Path& path() const { return path_; }
  void set_travel_speed(double mps) { config_.travel_speed_mps = mps; }

 private:
  PathPursuit(Path path, const PursuitConfig& config, const VehicleLimits& limits)
      : path_(std::move(path)), config_(config), limits_(limits) {}
  Path path_;
  PursuitConfig config_;
  VehicleLimits limits_;
  double progress_ = 0;
  bool started_ = false;
  bool finished_ = false;
};

}  // namespace jaus::components::guidance
