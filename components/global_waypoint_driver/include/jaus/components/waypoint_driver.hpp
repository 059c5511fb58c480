// The waypoint drivers (global, component 45; local, component 46), written
// once over the frame their waypoints are in (`Waypoints`: the messages, and
// how a waypoint and the vehicle become points of one local frame).
//
// Control: Set ... Waypoint and Set Travel Speed need control of this driver
// and are taken in any state; queries are anyone's. The route drives
// (MobilityDriver::engage) by either of the two start rules of
// ready_start.hpp: (1) the driver enters Ready by Resume (Standby -> Ready)
// with waypoints loaded and the route not finished; (2) in Ready, once its
// controller has set a travel speed above zero there, as soon as a list is
// loaded (the RA implementations' rule). Loading in any other state never
// moves anything. Standby pauses it, Emergency or a loss of the primitive
// driver halts it, both keeping the list and the active waypoint (Standby +
// Resume continues from it), and neither is undone by anything but a new
// command of the controller (ready_start.hpp); Reset clears the list and the
// travel speed. Reaching the last waypoint within arrival_tolerance_m
// finishes the route: zero below, control released, the list kept for
// queries, and it does not drive again until a new list (waypoint 0) is
// loaded (or, under rule 2, a waypoint appended).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "jaus/components/guidance/pursuit.hpp"
#include "jaus/components/mobility_driver.hpp"
#include "jaus/components/ready_start.hpp"
#include "jaus/components/waypoint_driver_options.hpp"
#include "jaus/components/waypoint_list.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::components {

struct WaypointDriverCounters {
  std::uint64_t waypoints_loaded = 0;   // Set ... Waypoint taken
  std::uint64_t waypoints_refused = 0;  // a gap in the numbering, or beyond max_waypoints
  std::uint64_t queries_unanswered = 0; // Query ... Waypoint beyond the count
  std::uint64_t routes_started = 0;     // Resume with a route to drive (start rule 1)
  std::uint64_t ready_starts = 0;       // started in Ready by its controller's list and speed (rule 2)
  std::uint64_t routes_finished = 0;    // the last waypoint reached
};

// Waypoints names the frame:
//   using Body, Set, Query, Report;      the messages (Set/Report carry Body)
//   static constexpr std::string_view kWhat;  "global waypoint"
//   class Frame {                        made when a motion starts
//     static Expected<Frame> at(const PoseSample& start);
//     std::optional<guidance::Point2> vehicle(const PoseSample&) const;
//     guidance::Point2 point(const Body&) const;
//   };
template <class Waypoints>
class WaypointDriver : public MobilityDriver {
 public:
  using Body = typename Waypoints::Body;
  using Frame = typename Waypoints::Frame;

  WaypointDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose, WaypointDriverOptions options)
      : MobilityDriver(std::move(config), std::move(env), pose, options.mobility),
        options_(options),
        list_(options.max_waypoints),
        travel_speed_{options.pursuit.travel_speed_mps} {
    handle<typename Waypoints::Set>(Access::controller, false,
                                    [this](const Header& h, const Body& m) { on_set_waypoint(h, m); });
    handle<msg::SetTravelSpeed>(Access::controller, false,
                                [this](const Header&, const msg::SetTravelSpeed& m) { on_travel_speed(m); });
    handle<typename Waypoints::Query>(Access::anyone, false,
                                      [this](const Header& h, const msg::WaypointNumberBody& m) { on_query(h, m); });
    handle<msg::QueryWaypointCount>(Access::anyone, false, [this](const Header& h, const msg::QueryWaypointCount&) {
      send(h.source, count_report());
    });
    handle<msg::QueryTravelSpeed>(Access::anyone, false, [this](const Header& h, const msg::QueryTravelSpeed&) {
      send(h.source, msg::ReportTravelSpeed{travel_speed_});
    });
    // Every optional field is stored and echoed (elevation, roll, pitch and
    // yaw are not followed by a ground vehicle).
    declare_input_presence(Waypoints::Set::code, 0x0F);
    declare_input_presence(Waypoints::Query::code, 0x0F);
    provide<msg::ReportWaypointCount>(0, [this] { return count_report(); });
    provide<msg::ReportTravelSpeed>(0, [this] { return msg::ReportTravelSpeed{travel_speed_}; });
  }

  const WaypointList<Body>& waypoints() const { return list_; }
  // The waypoint being driven to (or where a paused route continues).
  std::size_t active_waypoint() const { return active_; }
  bool route_finished() const { return finished_; }
  double travel_speed_mps() const { return travel_speed_.speed_mps; }
  // Start rule 2 (ready_start.hpp): a list loaded now in Ready would drive.
  bool armed_in_ready() const { return ready_start_.armed(); }
  const WaypointDriverCounters& waypoint_counters() const { return counters_; }
  // The last guidance output (cross-track error, lookahead) while driving.
  const guidance::PursuitOutput& last_output() const { return last_output_; }

 protected:
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override {
    MobilityDriver::state_changed(before, after);
    if (after == rt::PrimaryStatus::initialize && before != rt::PrimaryStatus::initialize) {
      // Reset: nothing of the old route remains.
      list_.clear();
      active_ = 0;
      finished_ = false;
      travel_speed_ = {options_.pursuit.travel_speed_mps};
      return;
    }
    // Start rule 1: Resume starts a route (never the first Ready, a cleared
    // Emergency or Failure: nothing drives off by itself; rule 2 was
    // disarmed by the stop that left Ready, command_stop).
    if (before == rt::PrimaryStatus::standby && after == rt::PrimaryStatus::ready && !list_.empty() && !finished_) {
      ++counters_.routes_started;
      engage("Resume: " + std::string(Waypoints::kWhat) + " " + std::to_string(active_) + " of " +
             std::to_string(list_.size()));
    }
  }

  void motion_started() override {
    frame_.reset();
    pursuit_.reset();
  }

  void motion_halted(std::string_view) override {
    // The list and the active waypoint stay (Resume continues); the pursuit
    // is made again from the vehicle's position then.
    pursuit_.reset();
    // Safety: every end of a motion but arriving and the controller's own
    // new list disarms start rule 2 (the primitive driver lost, a stale
    // pose): nothing restarts the route but a new command of the controller.
    if (!finished_ && !replacing_list_) ready_start_.disarm();
  }

  // Safety: every stop path of the component (leaving Ready, its control
  // released, taken over or its controller silent) disarms start rule 2
  // before the motion ends below.
  void command_stop(std::string_view why) override {
    ready_start_.disarm();
    MobilityDriver::command_stop(why);
  }

  Step step(const PoseSample& pose, double) override {
    if (!frame_) {
      auto frame = Frame::at(pose);
      if (!frame) return Step::fault("no frame for the route: " + frame.error().message());
      frame_.emplace(std::move(*frame));
    }
    const auto position = frame_->vehicle(pose);
    if (!position || !pose.attitude) return Step::fault("the pose has no position or heading");
    if (!pursuit_) {
      if (auto made = make_pursuit(); !made) return Step::fault(made.error().message());
    }
    // Travel speed 0 holds the vehicle still, the route still running.
    if (!(travel_speed_.speed_mps > 0)) return Step::drive(WrenchEffort{});
    pursuit_->set_travel_speed(travel_speed_.speed_mps);
    last_output_ = pursuit_->update(guidance::Pose2{position->x_m, position->y_m, pose.attitude->yaw});
    active_ = first_ + last_output_.target;
    if (last_output_.finished) {
      finished_ = true;
      active_ = list_.size() - 1;
      ++counters_.routes_finished;
      return Step::arrived("route finished: " + std::string(Waypoints::kWhat) + " " + std::to_string(active_) +
                           " reached");
    }
    return Step::drive(last_output_.effort);
  }

 private:
  // The remaining waypoints, from the active one, in the route's frame.
  Expected<void> make_pursuit() {
    if (!limits()) return unexpected(make_error(ErrorCode::invalid_argument, "no vehicle limits"));
    if (list_.empty()) return unexpected(make_error(ErrorCode::invalid_argument, "no waypoints"));
    first_ = std::min(active_, list_.size() - 1);
    std::vector<guidance::Point2> points;
    for (std::size_t i = first_; i < list_.size(); ++i) points.push_back(frame_->point(list_.elements()[i]));
    auto pursuit = guidance::WaypointPursuit::make(std::move(points), options_.pursuit, *limits());
    if (!pursuit) return unexpected(pursuit.error());
    pursuit_.emplace(std::move(*pursuit));
    return {};
  }

  void on_set_waypoint(const Header& h, const Body& waypoint) {
    const auto loaded = list_.load(waypoint);
    if (!loaded) {
      ++counters_.waypoints_refused;
      log_repeated("waypoints refused", rt::LogLevel::warn, [&] {
        return std::string(Waypoints::kWhat) + " from " + h.source.to_string() + " refused: " +
               loaded.error().message();
      });
      return;
    }
    ++counters_.waypoints_loaded;
    if (*loaded == WaypointLoad::new_list) {
      // A new list replaces the route: a running one stops first (the
      // controller's own replacement: start rule 2 stays armed).
      replacing_list_ = true;
      halt("new list");
      replacing_list_ = false;
      active_ = 0;
      finished_ = false;
    } else if (*loaded == WaypointLoad::appended && finished_ && ready_start_.armed() &&
               state() == rt::PrimaryStatus::ready) {
      // Start rule 2: a waypoint appended to a finished route drives on to it.
      finished_ = false;
      active_ = list_.size() - 1;
    }
    // A changed or longer list is driven from the active waypoint on (a
    // running route picks it up at its next step).
    pursuit_.reset();
    start_in_ready("loaded");
  }

  void on_travel_speed(const msg::SetTravelSpeed& m) {
    travel_speed_ = m;
    // Above zero in Ready arms start rule 2; 0 (or any speed outside Ready) disarms it.
    ready_start_.travel_speed_set(state(), travel_speed_.speed_mps);
    start_in_ready("Set Travel Speed");
  }

  // Start rule 2 (ready_start.hpp): armed, Ready, a route to drive, not driving.
  // Only the controller's Set ... reaches this (controller-only handlers).
  void start_in_ready(std::string_view what) {
    if (!ready_start_.armed() || state() != rt::PrimaryStatus::ready || list_.empty() || finished_ || driving())
      return;
    ++counters_.ready_starts;
    engage(std::string(what) + " in Ready: " + std::string(Waypoints::kWhat) + " " + std::to_string(active_) +
           " of " + std::to_string(list_.size()) + " at " + rt::option_number_text(travel_speed_.speed_mps) +
           " m/s");
  }

  void on_query(const Header& h, const msg::WaypointNumberBody& query) {
    const Body* waypoint = list_.find(query.waypoint_number);
    if (!waypoint) {
      // Never made-up data: no reply.
      ++counters_.queries_unanswered;
      log_repeated("waypoint queries beyond the count", rt::LogLevel::info, [&] {
        return "Query " + std::string(Waypoints::kWhat) + " " + std::to_string(query.waypoint_number) + " from " +
               h.source.to_string() + " unanswered: " + std::to_string(list_.size()) + " loaded";
      });
      return;
    }
    typename Waypoints::Report report;
    static_cast<Body&>(report) = *waypoint;
    send(h.source, report);
  }

  msg::ReportWaypointCount count_report() const {
    return msg::ReportWaypointCount{{static_cast<std::uint16_t>(list_.size())}};
  }

  WaypointDriverOptions options_;
  WaypointList<Body> list_;
  msg::TravelSpeedBody travel_speed_;
  std::size_t active_ = 0;
  std::size_t first_ = 0;  // the list's index of the pursuit's first waypoint
  bool finished_ = false;
  ReadyStart ready_start_;
  bool replacing_list_ = false;  // halting for the controller's new list (rule 2 stays armed)
  std::optional<Frame> frame_;
  std::optional<guidance::WaypointPursuit> pursuit_;
  guidance::PursuitOutput last_output_;
  WaypointDriverCounters counters_;
};

}  // namespace jaus::components
