// What the global and the local path segment drivers (components 47 and 48,
// issue 30) share: the route's life, travel speed, the guidance step and the
// queries that do not depend on the frame. Each derived driver keeps its
// PathSegmentList, handles its own Set/Query Path Segment and says where its
// points lie in the route's frame (the local driver: the vehicle's local
// frame; the global one: a LocalFrame whose datum is the vehicle's position
// when the route starts).
//
// The route (docs/components.md, "Path segment drivers"):
//   - loading (Set ... Path Segment, Set Travel Speed) needs control of this
//     driver, in any state;
//   - it starts by either start rule of ready_start.hpp: (1) the driver
//     enters Ready by Resume (Standby -> Ready) with segments loaded and the
//     route not finished; (2) in Ready, once its controller has set a travel
//     speed above zero there, as soon as segments are loaded (the RA
//     implementations' rule). No other way into Ready starts it, and loading
//     in any other state never moves anything. P0 of segment 0 is the
//     vehicle's position when it first starts;
//   - Standby pauses it, Emergency and a loss of the primitive driver halt
//     it: the path (its P0) and the progress along it are kept, and Standby +
//     Resume continues; nothing but a new command of the controller restarts
//     it (ready_start.hpp);
//   - a new list (segment 0) drops the route (halting it if it drives; under
//     rule 2 the new list drives at once); appending or replacing a segment
//     of a started route rebuilds its path from the same P0, followed on
//     from the vehicle's nearest point (under rule 2 a segment appended to a
//     finished route drives on along it);
//   - reaching the end within arrival_tolerance_m finishes it: zero below,
//     control released, the list kept for queries; it does not drive again
//     until a new list is loaded. Reset clears the list and the travel speed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "jaus/components/guidance/path_segment.hpp"
#include "jaus/components/mobility_driver.hpp"
#include "jaus/components/path_segment_list.hpp"
#include "jaus/components/ready_start.hpp"

namespace jaus::components {

struct PathSegmentDriverOptions {
  MobilityDriverOptions mobility;
  double lookahead_m = 1.0;          // pure pursuit's distance along the path, 0.1..50
  double arrival_tolerance_m = 0.5;  // the path's end within this is reached, 0.05..100
  double travel_speed_mps = 0.5;     // until Set Travel Speed (and after Reset), 0..100
  std::size_t max_path_segments = 1000;  // the list's capacity, 1..65536
};

// kMobilityDriverOptionKeys and the path segment drivers' own.
const std::vector<std::string_view>& path_segment_driver_option_keys();
Expected<PathSegmentDriverOptions> path_segment_driver_options(const rt::KindOptions& options);

struct PathSegmentCounters {
  std::uint64_t segments_stored = 0;     // Set ... Path Segment stored (new list, appended, replaced)
  std::uint64_t segments_refused = 0;    // a gap in the numbering, or beyond max_path_segments
  std::uint64_t queries_unanswered = 0;  // Query ... Path Segment for a number not loaded
  std::uint64_t routes_started = 0;      // paths built from a list (P0 fixed)
  std::uint64_t routes_finished = 0;     // ends reached
  std::uint64_t ready_starts = 0;        // started in Ready by its controller's list and speed (start rule 2)
};

class PathSegmentDriver : public MobilityDriver {
 public:
  PathSegmentDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose,
                    const PathSegmentDriverOptions& options);

  virtual std::size_t segment_count() const = 0;
  double travel_speed_mps() const { return travel_speed_mps_; }
  // Start rule 2 (ready_start.hpp): segments loaded now in Ready would drive.
  bool armed_in_ready() const { return ready_start_.armed(); }
  // The route's path once started (kept while paused), none before.
  const guidance::PathPursuit* pursuit() const { return pursuit_ ? &*pursuit_ : nullptr; }
  bool route_finished() const { return finished_; }
  // Where `sample` lies in the frame of the route's path (its cross-track
  // error: pursuit()->path().project(...)); none before a route started.
  virtual Expected<guidance::Point2> position_in_route(const PoseSample& sample) const = 0;
  // The cross-track error of the last guidance step (m, positive right of the path).
  double last_cross_track_m() const { return last_cross_track_m_; }
  const PathSegmentCounters& path_counters() const { return path_counters_; }

 protected:
  // The route starts at `start` (the vehicle's pose on the first Resume):
  // the derived driver fixes its frame and returns P0 of segment 0 in it.
  virtual Expected<guidance::Point2> start_route(const PoseSample& start) = 0;
  // P1, P2 and the weight of every loaded segment in the route's frame.
  virtual Expected<std::vector<guidance::SegmentSpec>> route_segments() const = 0;
  // Reset: the list is emptied.
  virtual void clear_segments() = 0;

  // The derived driver's Set ... Path Segment handler reports here what its
  // list made of segment `number` (stored, or refused with why).
  void segment_set(const Header& header, std::uint16_t number, const Expected<ListChange>& result);
  // A query for segment `number` not loaded: no reply (no made-up data), counted and logged.
  void segment_query_unanswered(const Header& header, std::uint16_t number);

  Step step(const PoseSample& pose, double dt_s) override;
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override;
  void motion_halted(std::string_view why) override;
  void command_stop(std::string_view why) override;

 private:
  Expected<void> build_pursuit(const PoseSample& pose);
  void drop_route();
  void start_in_ready(std::string_view what);

  PathSegmentDriverOptions options_;
  double travel_speed_mps_;
  std::optional<guidance::PathPursuit> pursuit_;
  guidance::Point2 route_start_;
  bool path_stale_ = false;  // a segment changed under a started route: rebuild from route_start_
  bool finished_ = false;
  ReadyStart ready_start_;
  bool replacing_list_ = false;  // halting for the controller's new list (rule 2 stays armed)
  double last_cross_track_m_ = 0;
  PathSegmentCounters path_counters_;
};

}  // namespace jaus::components
