#include "jaus/components/path_segment_driver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

using namespace rt;

const std::vector<std::string_view>& path_segment_driver_option_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k = kMobilityDriverOptionKeys;
    for (std::string_view own : {"lookahead_m", "arrival_tolerance_m", "travel_speed_mps", "max_path_segments"})
      k.push_back(own);
    return k;
  }();
  return keys;
}

Expected<PathSegmentDriverOptions> path_segment_driver_options(const KindOptions& options) {
  PathSegmentDriverOptions o;
  auto mobility = mobility_driver_options(options);
  if (!mobility) return unexpected(mobility.error());
  o.mobility = *mobility;
  const auto lookahead = number_option(options, "lookahead_m", 0.1, 50, o.lookahead_m);
  if (!lookahead) return unexpected(lookahead.error());
  o.lookahead_m = *lookahead;
  const auto tolerance = number_option(options, "arrival_tolerance_m", 0.05, 100, o.arrival_tolerance_m);
  if (!tolerance) return unexpected(tolerance.error());
  o.arrival_tolerance_m = *tolerance;
  const auto speed = number_option(options, "travel_speed_mps", 0, 100, o.travel_speed_mps);
  if (!speed) return unexpected(speed.error());
  o.travel_speed_mps = *speed;
  const auto capacity = number_option(options, "max_path_segments", 1, 65536, static_cast<double>(o.max_path_segments));
  if (!capacity) return unexpected(capacity.error());
  if (*capacity != std::floor(*capacity))
    return unexpected(option_error(options, "max_path_segments", "a whole number 1..65536"));
  o.max_path_segments = static_cast<std::size_t>(*capacity);
  return o;
}

PathSegmentDriver::PathSegmentDriver(ComponentConfig config, Environment env, PoseSource& pose,
                                     const PathSegmentDriverOptions& options)
    : MobilityDriver(std::move(config), std::move(env), pose, options.mobility),
      options_(options),
      travel_speed_mps_(options.travel_speed_mps) {
  // Loading is allowed in any state, to the controller only; it moves
  // something only by start rule 2 (ready_start.hpp), in Ready.
  handle<msg::SetTravelSpeed>(Access::controller, false, [this](const Header&, const msg::SetTravelSpeed& m) {
    travel_speed_mps_ = m.speed_mps;
    if (pursuit_) pursuit_->set_travel_speed(travel_speed_mps_);
    // Above zero in Ready arms start rule 2; 0 (or any speed outside Ready) disarms it.
    ready_start_.travel_speed_set(state(), travel_speed_mps_);
    start_in_ready("Set Travel Speed");
  });
  handle<msg::QueryTravelSpeed>(Access::anyone, false, [this](const Header& h, const msg::QueryTravelSpeed&) {
    send(h.source, msg::ReportTravelSpeed{{travel_speed_mps_}});
  });
  handle<msg::QueryPathSegmentCount>(Access::anyone, false, [this](const Header& h, const msg::QueryPathSegmentCount&) {
    send(h.source, msg::ReportPathSegmentCount{{static_cast<std::uint16_t>(segment_count())}});
  });
  provide<msg::ReportTravelSpeed>(0, [this] { return msg::ReportTravelSpeed{{travel_speed_mps_}}; });
  provide<msg::ReportPathSegmentCount>(
      0, [this] { return msg::ReportPathSegmentCount{{static_cast<std::uint16_t>(segment_count())}}; });
}

void PathSegmentDriver::segment_set(const Header& header, std::uint16_t number, const Expected<ListChange>& result) {
  if (!result) {
    ++path_counters_.segments_refused;
    log_repeated("path segments refused", LogLevel::warn, [&] {
      return "path segment " + std::to_string(number) + " from " + header.source.to_string() +
             " refused: " + result.error().message();
    });
    return;
  }
  ++path_counters_.segments_stored;
  switch (*result) {
    case ListChange::new_list:
      // A route driving the old list stops (a no-op otherwise); the
      // controller's own replacement: start rule 2 stays armed.
      replacing_list_ = true;
      halt("new list");
      replacing_list_ = false;
      drop_route();
      break;
    case ListChange::appended:
      // Start rule 2: a segment appended to a finished route drives on along it.
      if (finished_ && ready_start_.armed() && state() == PrimaryStatus::ready) finished_ = false;
      [[fallthrough]];
    case ListChange::replaced:
      // A started route follows the changed list from the same P0.
      if (pursuit_) path_stale_ = true;
      break;
  }
  start_in_ready("loaded");
}

// Start rule 2 (ready_start.hpp): armed, Ready, a route to drive, not
// driving. Only the controller's Set ... reaches this (controller-only handlers).
void PathSegmentDriver::start_in_ready(std::string_view what) {
  if (!ready_start_.armed() || state() != PrimaryStatus::ready || segment_count() == 0 || finished_ || driving())
    return;
  ++path_counters_.ready_starts;
  engage(std::string(what) + " in Ready: " + (pursuit_ ? "continuing the path" : "starting the path") + " at " +
         option_number_text(travel_speed_mps_) + " m/s");
}

// Safety: every end of a motion but arriving and the controller's own new
// list disarms start rule 2 (the primitive driver lost, a stale pose, a
// list that makes no path): nothing restarts the route but a new command
// of the controller.
void PathSegmentDriver::motion_halted(std::string_view) {
  if (!finished_ && !replacing_list_) ready_start_.disarm();
}

// Safety: every stop path of the component (leaving Ready, its control
// released, taken over or its controller silent) disarms start rule 2
// before the motion ends below.
void PathSegmentDriver::command_stop(std::string_view why) {
  ready_start_.disarm();
  MobilityDriver::command_stop(why);
}

void PathSegmentDriver::segment_query_unanswered(const Header& header, std::uint16_t number) {
  ++path_counters_.queries_unanswered;
  log_repeated("path segment queries unanswered", LogLevel::warn, [&] {
    return "no path segment " + std::to_string(number) + " to report to " + header.source.to_string() + " (" +
           std::to_string(segment_count()) + " loaded): not answered";
  });
}

void PathSegmentDriver::drop_route() {
  pursuit_.reset();
  path_stale_ = false;
  finished_ = false;
  last_cross_track_m_ = 0;
}

// Start rule 1: Resume (Standby -> Ready) starts or continues a route (never
// the first Ready, a cleared Emergency or Failure: rule 2 was disarmed by
// the stop that left Ready, command_stop); Reset empties it.
void PathSegmentDriver::state_changed(PrimaryStatus before, PrimaryStatus after) {
  if (after == PrimaryStatus::initialize) {
    clear_segments();
    drop_route();
    travel_speed_mps_ = options_.travel_speed_mps;
    return;
  }
  if (before == PrimaryStatus::standby && after == PrimaryStatus::ready && segment_count() > 0 && !finished_)
    engage(pursuit_ ? "Resume: continuing the path" : "Resume: starting the path");
}

Expected<void> PathSegmentDriver::build_pursuit(const PoseSample& pose) {
  if (!pursuit_) {
    auto start = start_route(pose);
    if (!start) return unexpected(start.error());
    route_start_ = *start;
    ++path_counters_.routes_started;
  }
  auto segments = route_segments();
  if (!segments) return unexpected(segments.error());
  auto path = guidance::Path::make(route_start_, *segments);
  if (!path) return unexpected(path.error());
  guidance::PursuitConfig config;
  config.lookahead_m = options_.lookahead_m;
  config.arrival_tolerance_m = options_.arrival_tolerance_m;
  config.travel_speed_mps = std::max(travel_speed_mps_, 0.01);  // 0 is held below, in step()
  auto pursuit = guidance::PathPursuit::make(std::move(*path), config, *limits());
  if (!pursuit) return unexpected(pursuit.error());
  const bool rebuilt = pursuit_.has_value();
  pursuit_.emplace(std::move(*pursuit));
  path_stale_ = false;
  log(LogLevel::info, std::string(rebuilt ? "path rebuilt: " : "path: ") + std::to_string(segment_count()) +
                          " segments, " + option_number_text(pursuit_->path().length_m()) + " m");
  return {};
}

MobilityDriver::Step PathSegmentDriver::step(const PoseSample& pose, double /*dt_s*/) {
  if (!pursuit_ || path_stale_) {
    if (auto built = build_pursuit(pose); !built) {
      // A list that makes no path (a point not finite, no position): it
      // cannot drive; the list stays for queries and a new one.
      drop_route();
      return Step::fault("cannot follow the path: " + built.error().message());
    }
  }
  const auto here = position_in_route(pose);
  if (!here) return Step::fault("no position: " + here.error().message());
  if (!pose.attitude) return Step::fault("no heading in the pose");
  const guidance::PursuitOutput out = pursuit_->update(guidance::Pose2{here->x_m, here->y_m, pose.attitude->yaw});
  last_cross_track_m_ = out.cross_track_m;
  if (out.finished) {
    finished_ = true;
    ++path_counters_.routes_finished;
    return Step::arrived("the path's end reached (within " + option_number_text(options_.arrival_tolerance_m) + " m)");
  }
  // Travel speed 0 holds the vehicle still; the route stays running.
  if (!(travel_speed_mps_ > 0)) return Step::drive(WrenchEffort{});
  return Step::drive(out.effort);
}

}  // namespace jaus::components
