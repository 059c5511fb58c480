#include "jaus/components/guidance/path_segment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "argument_checks.hpp"

namespace jaus::components::guidance {

using detail::bad;

namespace {

constexpr double kMaxWeight = 500;         // Part 3: range 0 to 500
constexpr double kFlatness_m = 0.01;       // polyline within 1 cm of the curve
constexpr int kMinDepth = 3;               // at least 8 pieces a segment
constexpr int kMaxDepth = 14;              // at most 16384 pieces a segment
constexpr double kSearchBack_m = 1.0;      // how far behind its progress a vehicle may be found

bool finite(const Point2& p) { return std::isfinite(p.x_m) && std::isfinite(p.y_m); }
bool finite(const Pose2& p) { return finite(p.position()) && std::isfinite(p.yaw_rad); }

// Distance from p to the line through a and b (or to a, if they coincide).
double off_chord(const Point2& p, const Point2& a, const Point2& b) {
  const double len = distance(a, b);
  if (len < 1e-12) return distance(p, a);
  return std::abs((b.x_m - a.x_m) * (p.y_m - a.y_m) - (b.y_m - a.y_m) * (p.x_m - a.x_m)) / len;
}

}  // namespace

Point2 PathSegment::point_at(double t) const {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  const double b0 = (1 - t) * (1 - t), b1 = 2 * t * (1 - t) * weight, b2 = t * t;
  const double d = b0 + b1 + b2;  // >= 1/2 for weight >= 0
  return {(b0 * p0.x_m + b1 * p1.x_m + b2 * p2.x_m) / d, (b0 * p0.y_m + b1 * p1.y_m + b2 * p2.y_m) / d};
}

Point2 PathSegment::derivative_at(double t) const {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  const double b0 = (1 - t) * (1 - t), b1 = 2 * t * (1 - t) * weight, b2 = t * t;
  const double db0 = -2 * (1 - t), db1 = 2 * (1 - 2 * t) * weight, db2 = 2 * t;
  const double d = b0 + b1 + b2, dd = db0 + db1 + db2;
  const double nx = b0 * p0.x_m + b1 * p1.x_m + b2 * p2.x_m, ny = b0 * p0.y_m + b1 * p1.y_m + b2 * p2.y_m;
  const double dnx = db0 * p0.x_m + db1 * p1.x_m + db2 * p2.x_m, dny = db0 * p0.y_m + db1 * p1.y_m + db2 * p2.y_m;
  return {(dnx * d - nx * dd) / (d * d), (dny * d - ny * dd) / (d * d)};
}

Point2 PathSegment::tangent_at(double t) const {
  auto unit = [](Point2 v) -> std::optional<Point2> {
    const double n = std::hypot(v.x_m, v.y_m);
    if (!(n > 1e-12)) return std::nullopt;
    return Point2{v.x_m / n, v.y_m / n};
  };
  if (weight == 0) {
    if (auto u = unit({p2.x_m - p0.x_m, p2.y_m - p0.y_m})) return *u;
    return {};
  }
  if (auto u = unit(derivative_at(t))) return *u;
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  const Point2 a = point_at(t - 1e-3), b = point_at(t + 1e-3);
  if (auto u = unit({b.x_m - a.x_m, b.y_m - a.y_m})) return *u;
  return {};
}

Expected<Path> Path::make(const Point2& start, const std::vector<SegmentSpec>& specs) {
  if (specs.empty()) return unexpected(bad("no path segments"));
  if (!finite(start)) return unexpected(bad("the start is not finite"));
  Path path;
  Point2 p0 = start;
  for (const auto& s : specs) {
    if (!finite(s.p1) || !finite(s.p2)) return unexpected(bad("a path segment point is not finite"));
    if (!std::isfinite(s.weight) || s.weight < 0 || s.weight > kMaxWeight) {
      return unexpected(bad("a weighting factor outside 0..500"));
    }
    path.segments_.push_back({p0, s.p1, s.p2, s.weight});
    p0 = s.p2;
  }

  // Flatten each segment: split [t0, t1] while its middle is off the chord by
  // more than the flatness (or it is not yet kMinDepth deep).
  path.samples_.push_back({start, 0, 0});
  for (std::size_t i = 0; i < path.segments_.size(); ++i) {
    const PathSegment& seg = path.segments_[i];
    struct Span { double t0, t1; int depth; };
    std::vector<Span> stack{{0, 1, 0}};
    while (!stack.empty()) {
      const Span span = stack.back();
      stack.pop_back();
      const double tm = (span.t0 + span.t1) / 2;
      const Point2 a = seg.point_at(span.t0), b = seg.point_at(span.t1);
      const bool flat = span.depth >= kMinDepth && off_chord(seg.point_at(tm), a, b) <= kFlatness_m &&
                        off_chord(seg.point_at((span.t0 + tm) / 2), a, b) <= kFlatness_m &&
                        off_chord(seg.point_at((tm + span.t1) / 2), a, b) <= kFlatness_m;
      if (flat || span.depth >= kMaxDepth) {
        path.samples_.push_back({b, i, span.t1});
      } else {
        stack.push_back({tm, span.t1, span.depth + 1});  // the second half after the first
        stack.push_back({span.t0, tm, span.depth + 1});
      }
    }
  }
  path.cumulative_.reserve(path.samples_.size());
  path.cumulative_.push_back(0);
  for (std::size_t k = 1; k < path.samples_.size(); ++k) {
    path.cumulative_.push_back(path.cumulative_.back() + distance(path.samples_[k - 1].point, path.samples_[k].point));
  }
  return path;
}

Point2 Path::point_at_arc(double s) const {
  if (!(s > 0)) return samples_.front().point;
  if (s >= cumulative_.back()) return samples_.back().point;
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const std::size_t k = static_cast<std::size_t>(it - cumulative_.begin());  // 1..size-1
  const double piece = cumulative_[k] - cumulative_[k - 1];
  const double f = piece > 0 ? (s - cumulative_[k - 1]) / piece : 0;
  const Point2 a = samples_[k - 1].point, b = samples_[k].point;
  return {a.x_m + f * (b.x_m - a.x_m), a.y_m + f * (b.y_m - a.y_m)};
}

PathProjection Path::project(const Point2& p, double from, double to) const {
  PathProjection best;
  if (!finite(p)) return best;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < samples_.size(); ++k) {
    if (cumulative_[k] < from || cumulative_[k - 1] > to) continue;
    const Point2 a = samples_[k - 1].point, b = samples_[k].point;
    const double piece = cumulative_[k] - cumulative_[k - 1];
    double f = 0;
    if (piece > 1e-12) {
      f = ((p.x_m - a.x_m) * (b.x_m - a.x_m) + (p.y_m - a.y_m) * (b.y_m - a.y_m)) / (piece * piece);
      f = std::clamp(f, 0.0, 1.0);
    }
    const Point2 q{a.x_m + f * (b.x_m - a.x_m), a.y_m + f * (b.y_m - a.y_m)};
    const double d = distance(p, q);
    if (d < best_d) {
      best_d = d;
      best.arc_length_m = cumulative_[k - 1] + f * piece;
      best.point = q;
      // The segment and its parameter: the piece's end's, or its start's within the same segment.
      const Sample& end = samples_[k];
      const Sample& start = samples_[k - 1];
      best.segment = end.segment;
      const double t0 = start.segment == end.segment ? start.t : 0.0;
      best.t = t0 + f * (end.t - t0);
    }
  }
  if (!std::isfinite(best_d)) return project(p);  // an empty window: the whole path
  // The side from the curve's own tangent (the polyline's piece where it degenerates).
  Point2 tangent = segments_[best.segment].tangent_at(best.t);
  if (std::hypot(tangent.x_m, tangent.y_m) < 1e-12) {
    const Point2 ahead = point_at_arc(best.arc_length_m + 0.01), behind = point_at_arc(best.arc_length_m - 0.01);
    tangent = {ahead.x_m - behind.x_m, ahead.y_m - behind.y_m};
  }
  const double norm = std::hypot(tangent.x_m, tangent.y_m);
  const double side = tangent.x_m * (p.y_m - best.point.y_m) - tangent.y_m * (p.x_m - best.point.x_m);
  best.cross_track_m = norm > 0 ? side / norm : 0;  // |side| / norm is the distance: p - q is normal to the path
  return best;
}

Expected<PathPursuit> PathPursuit::make(Path path, const PursuitConfig& config, const VehicleLimits& limits) {
  if (auto ok = validate(config); !ok) return unexpected(ok.error());
  if (auto ok = validate(limits); !ok) return unexpected(ok.error());
  return PathPursuit(std::move(path), config, limits);
}

PursuitOutput PathPursuit::update(const Pose2& pose) {
  PursuitOutput out;
  if (!finite(pose)) return out;  // no pose to steer by: stop, and keep the progress
  const Point2 here = pose.position();
  const PathProjection at = started_ ? path_.project(here, progress_ - kSearchBack_m,
                                                    progress_ + 2 * config_.lookahead_m + 5)
                                     : path_.project(here);
  started_ = true;
  progress_ = std::max(progress_, at.arc_length_m);
  out.target = at.segment;
  out.cross_track_m = at.cross_track_m;

  const double remaining = path_.length_m() - progress_;
  if (finished_ || (distance(here, path_.end()) <= config_.arrival_tolerance_m &&
                    remaining <= config_.arrival_tolerance_m + config_.lookahead_m)) {
    finished_ = true;
    out.finished = true;
    out.lookahead = path_.end();
    return out;
  }

  out.lookahead = path_.point_at_arc(progress_ + config_.lookahead_m);
  double speed = std::min(config_.travel_speed_mps, limits_.max_speed_mps);
  const double to_end = std::max(distance(here, path_.end()), remaining);
  speed = std::min(speed, std::sqrt(2 * config_.max_deceleration_mps2 * to_end));
  const double dx = out.lookahead.x_m - here.x_m, dy = out.lookahead.y_m - here.y_m;
  const double bearing_error = heading_error(std::atan2(dy, dx), pose.yaw_rad);
  out.command = shape_command(pursuit_curvature(pose, out.lookahead), bearing_error, speed, config_, limits_);
  out.effort = to_effort(out.command, limits_);
  return out;
}

}  // namespace jaus::components::guidance
