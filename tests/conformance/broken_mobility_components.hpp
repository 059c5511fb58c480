// Drivers above the primitive driver, each broken in one way that one
// mobility case must catch, and otherwise as small as the cases allow: a
// local waypoint driver (lists, travel speed) and a local vector driver, on
// a node of hand-made components (subsystem 4, node 1):
//   4.1.46.1 waypoints and travel speed taken from anyone
//   4.1.47.1 waypoints reported without their optional yaw
//   4.1.48.1 a waypoint number past the end appended
//   4.1.49.1 waypoint 0 replaces the first waypoint only: the old list stays
//   4.1.50.1 Set Local Vector taken from anyone
//   4.1.51.1 Set Local Vector reported with speed 0
// They move nothing (no vehicle): the cases' verdicts are all that matters.
#pragma once

#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/runtime/component.hpp"
#include "memory_node.hpp"

namespace jaus::conform::test {

inline const Address kWaypointsObeyAnyone{4, 1, 46, 1};
inline const Address kWaypointsDropYaw{4, 1, 47, 1};
inline const Address kWaypointsAppendPastEnd{4, 1, 48, 1};
inline const Address kWaypointsKeepOldList{4, 1, 49, 1};
inline const Address kVectorObeysAnyone{4, 1, 50, 1};
inline const Address kVectorForgetsSpeed{4, 1, 51, 1};

enum class WaypointFlaw { obeys_anyone, drops_yaw, appends_past_end, keeps_old_list };

class BrokenWaypointDriver final : public rt::Component {
 public:
  BrokenWaypointDriver(rt::ComponentConfig config, rt::Environment env, WaypointFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    const Access setter = flaw == WaypointFlaw::obeys_anyone ? Access::anyone : Access::controller;
    handle<msg::SetLocalWaypoint>(setter, false, [this](const Header&, const msg::SetLocalWaypoint& m) { store(m); });
    handle<msg::SetTravelSpeed>(setter, false,
                                [this](const Header&, const msg::SetTravelSpeed& m) { travel_speed_ = m.speed_mps; });
    handle<msg::QueryWaypointCount>(Access::anyone, false, [this](const Header& h, const msg::QueryWaypointCount&) {
      msg::ReportWaypointCount r;
      r.waypoint_count = static_cast<std::uint16_t>(list_.size());
      send(h.source, r);
    });
    handle<msg::QueryLocalWaypoint>(Access::anyone, false, [this](const Header& h, const msg::QueryLocalWaypoint& q) {
      if (q.waypoint_number >= list_.size()) return;
      msg::ReportLocalWaypoint r;
      static_cast<msg::LocalWaypointBody&>(r) = list_[q.waypoint_number];
      if (flaw_ == WaypointFlaw::drops_yaw) r.yaw_rad.reset();
      send(h.source, r);
    });
    handle<msg::QueryTravelSpeed>(Access::anyone, false, [this](const Header& h, const msg::QueryTravelSpeed&) {
      msg::ReportTravelSpeed r;
      r.speed_mps = travel_speed_;
      send(h.source, r);
    });
  }

 protected:
  void state_changed(rt::PrimaryStatus, rt::PrimaryStatus after) override {
    if (after == rt::PrimaryStatus::initialize) list_.clear();  // Reset clears the list
  }

 private:
  void store(const msg::LocalWaypointBody& w) {
    const std::size_t n = w.waypoint_number;
    if (n == 0 && flaw_ != WaypointFlaw::keeps_old_list) list_.clear();
    if (n < list_.size())
      list_[n] = w;
    else if (n == list_.size() || flaw_ == WaypointFlaw::appends_past_end)
      list_.push_back(w);
  }

  WaypointFlaw flaw_;
  std::vector<msg::LocalWaypointBody> list_;
  double travel_speed_ = 0.5;
};

enum class VectorFlaw { obeys_anyone, forgets_speed };

class BrokenVectorDriver final : public rt::Component {
 public:
  BrokenVectorDriver(rt::ComponentConfig config, rt::Environment env, VectorFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    const Access setter = flaw == VectorFlaw::obeys_anyone ? Access::anyone : Access::controller;
    handle<msg::SetLocalVector>(setter, true, [this](const Header&, const msg::SetLocalVector& m) {
      vector_ = m;
      if (flaw_ == VectorFlaw::forgets_speed) vector_.speed_mps = 0;
    });
    handle<msg::QueryLocalVector>(Access::anyone, false, [this](const Header& h, const msg::QueryLocalVector&) {
      msg::ReportLocalVector r;
      static_cast<msg::LocalVectorBody&>(r) = vector_;
      send(h.source, r);
    });
  }

 private:
  VectorFlaw flaw_;
  msg::LocalVectorBody vector_;
};

class BrokenMobilityNode {
 public:
  BrokenMobilityNode(rt::VirtualTime& time, testing::MemoryNetwork& network) : node_(time, network, node_config()) {
    node_.emplace<BrokenWaypointDriver>("waypoints obey anyone", kWaypointsObeyAnyone.component,
                                        WaypointFlaw::obeys_anyone);
    node_.emplace<BrokenWaypointDriver>("waypoints drop yaw", kWaypointsDropYaw.component, WaypointFlaw::drops_yaw);
    node_.emplace<BrokenWaypointDriver>("waypoints append past end", kWaypointsAppendPastEnd.component,
                                        WaypointFlaw::appends_past_end);
    node_.emplace<BrokenWaypointDriver>("waypoints keep old list", kWaypointsKeepOldList.component,
                                        WaypointFlaw::keeps_old_list);
    node_.emplace<BrokenVectorDriver>("vector obeys anyone", kVectorObeysAnyone.component, VectorFlaw::obeys_anyone);
    node_.emplace<BrokenVectorDriver>("vector forgets speed", kVectorForgetsSpeed.component,
                                      VectorFlaw::forgets_speed);
  }
  node::Node& node() { return node_.node(); }

 private:
  static node::NodeConfig node_config() {
    node::NodeConfig config;
    config.subsystem = 4;
    config.node = 1;
    return config;
  }

  test_support::MemoryNode node_;
};

}  // namespace jaus::conform::test
