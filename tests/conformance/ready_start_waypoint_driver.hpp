// A local waypoint driver with the RA implementations' start rule (issue 43;
// OpenJAUS's waypoint driver): in Ready, a loaded list drives as soon as its
// controller's travel speed is above zero, whichever comes last, and the
// travel speed drops to zero whenever it leaves Ready. It drives no vehicle:
// it records whether it would have started a route (and in which state), so
// a test can show the waypoint cases accept this rule too and never make
// such a driver move (they load in Standby and never Resume). On a node of
// hand-made components (subsystem 5, node 1, component 46).
#pragma once

#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/runtime/component.hpp"
#include "memory_node.hpp"

namespace jaus::conform::test {

inline const Address kReadyStartWaypointDriver{5, 1, 46, 1};

class ReadyStartWaypointDriver final : public rt::Component {
 public:
  ReadyStartWaypointDriver(rt::ComponentConfig config, rt::Environment env)
      : Component(std::move(config), std::move(env)) {
    handle<msg::SetLocalWaypoint>(Access::controller, false, [this](const Header&, const msg::SetLocalWaypoint& m) {
      store(m);
      start_if_ready();
    });
    handle<msg::SetTravelSpeed>(Access::controller, false, [this](const Header&, const msg::SetTravelSpeed& m) {
      travel_speed_ = m.speed_mps;
      start_if_ready();
    });
    handle<msg::QueryWaypointCount>(Access::anyone, false, [this](const Header& h, const msg::QueryWaypointCount&) {
      msg::ReportWaypointCount r;
      r.waypoint_count = static_cast<std::uint16_t>(list_.size());
      send(h.source, r);
    });
    handle<msg::QueryLocalWaypoint>(Access::anyone, false, [this](const Header& h, const msg::QueryLocalWaypoint& q) {
      if (q.waypoint_number >= list_.size()) return;
      msg::ReportLocalWaypoint r;
      static_cast<msg::LocalWaypointBody&>(r) = list_[q.waypoint_number];
      send(h.source, r);
    });
    handle<msg::QueryTravelSpeed>(Access::anyone, false, [this](const Header& h, const msg::QueryTravelSpeed&) {
      msg::ReportTravelSpeed r;
      r.speed_mps = travel_speed_;
      send(h.source, r);
    });
  }

  // Routes it would have driven (a list loaded in Ready with a travel speed above zero).
  int routes_started() const { return routes_started_; }
  bool driving() const { return driving_; }

 protected:
  void command_stop(std::string_view) override { driving_ = false; }
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override {
    if (before == rt::PrimaryStatus::ready) travel_speed_ = 0;  // as the RA implementations do
    if (after == rt::PrimaryStatus::initialize) list_.clear();  // Reset clears the list
  }

 private:
  void store(const msg::LocalWaypointBody& w) {
    const std::size_t n = w.waypoint_number;
    if (n == 0) list_.clear();
    if (n < list_.size())
      list_[n] = w;
    else if (n == list_.size())
      list_.push_back(w);
  }
  void start_if_ready() {
    if (state() != rt::PrimaryStatus::ready || list_.empty() || !(travel_speed_ > 0) || driving_) return;
    driving_ = true;
    ++routes_started_;
  }

  std::vector<msg::LocalWaypointBody> list_;
  double travel_speed_ = 0;
  bool driving_ = false;
  int routes_started_ = 0;
};

class ReadyStartNode {
 public:
  ReadyStartNode(rt::VirtualTime& time, testing::MemoryNetwork& network) : node_(time, network, node_config()) {
    node_.emplace<ReadyStartWaypointDriver>("ready start waypoint driver", kReadyStartWaypointDriver.component);
  }
  node::Node& node() { return node_.node(); }
  ReadyStartWaypointDriver& driver() {
    return dynamic_cast<ReadyStartWaypointDriver&>(*node_.node().find(kReadyStartWaypointDriver));
  }

 private:
  static node::NodeConfig node_config() {
    node::NodeConfig config;
    config.subsystem = 5;
    config.node = 1;
    return config;
  }

  test_support::MemoryNode node_;
};

}  // namespace jaus::conform::test
