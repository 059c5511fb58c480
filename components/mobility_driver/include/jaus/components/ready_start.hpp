// When a route driver (the waypoint drivers 45 and 46, the path segment
// drivers 47 and 48) starts driving its loaded list: two rules, both kept
// (issue 43; docs/components.md, "When a route drives").
//
//   1. Resume: the driver enters Ready by Resume (Standby -> Ready) with a
//      list loaded and its route not finished. Our rule since issue 30; the
//      travel speed may have been set in any state.
//   2. Load and go in Ready (the RA implementations' rule, OpenJAUS's): a
//      driver in Ready drives its list once its controller has set a travel
//      speed above zero *while it is Ready* ("armed" here): whichever comes
//      last, the Set Travel Speed above zero or the list's first element,
//      starts it at once. Armed, a new list (element 0) replaces the route
//      and drives the new one, and an element appended to a finished route
//      drives on to it; a Set Travel Speed 0 disarms (a running route holds
//      the vehicle still, as under rule 1).
//
// Safety (where "nothing starts by itself" is kept for rule 2):
//   - only the controller arms it and only the controller's Set ... starts
//     it: Set Travel Speed and Set ... Waypoint/Path Segment are registered
//     Access::controller, so a non-controller's or an observer's list or
//     speed is refused before it reaches the driver, and never starts
//     anything;
//   - every stop disarms it: the driver's command_stop (it leaves Ready:
//     Standby, Emergency, Reset, Shutdown, Failure; its control released,
//     taken over or its controller silent: rt::Component::enforce_stop) and
//     every end of a motion but arriving and the controller's own new list
//     (the primitive driver lost, taken by an operator or out of Ready, a
//     stale pose, a list that makes no path). So after any stop nothing
//     restarts the route: not Clear Emergency, not a later element, not the
//     primitive driver's return; only a new command of the controller in
//     Ready (Set Travel Speed above zero: rule 2, or Standby and Resume:
//     rule 1);
//   - arming needs Ready: a Set Travel Speed received in Standby (rule 1's
//     loading) never arms, so Standby -> load -> Resume is exactly as it was.
#pragma once

#include <cmath>

#include "jaus/runtime/lifecycle.hpp"

namespace jaus::components {

class ReadyStart {
 public:
  // Its controller's Set Travel Speed (the handler is controller-only) in `state`.
  void travel_speed_set(rt::PrimaryStatus state, double speed_mps) {
    armed_ = state == rt::PrimaryStatus::ready && std::isfinite(speed_mps) && speed_mps > 0;
  }
  // Any stop (see above).
  void disarm() { armed_ = false; }
  bool armed() const { return armed_; }

 private:
  bool armed_ = false;
};

}  // namespace jaus::components
