#include "reference_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace jaus::model {

const char* name(Ctl c) {
  switch (c) {
    case Ctl::none: return "nobody";
    case Ctl::a: return "A";
    case Ctl::b: return "B";
    case Ctl::j: return "J";
    case Ctl::c: return "C";
    case Ctl::driver: return "the vector driver";
  }
  return "?";
}

Ctl ctl_of(Party p) {
  switch (p) {
    case Party::a: return Ctl::a;
    case Party::b: return Ctl::b;
    case Party::j: return Ctl::j;
    case Party::c: return Ctl::c;
  }
  return Ctl::none;
}

const char* name(PdState s) {
  switch (s) {
    case PdState::initialize: return "Initialize";
    case PdState::ready: return "Ready";
    case PdState::standby: return "Standby";
    case PdState::emergency: return "Emergency";
    case PdState::failure: return "Failure";
    case PdState::shutdown: return "Shutdown";
  }
  return "?";
}

void ReferenceModel::start(Ms now) {
  ctl_ = Ctl::none;
  ctl_authority_ = 0;
  own_authority_ = 0;  // as configured
  standby_ = shutdown_ = false;
  standby_since_ = shutdown_since_ = kNever;
  unsettled_until_ = now + t_.settle;
  heard_.fill(now);
  command_.reset();
  zero_due_ = now;
  lingering_.reset();
  lingering_any_ = false;
  lingering_until_ = 0;
  c_controls_vector_ = false;
  driver_motion_ = false;
  driver_settle_until_ = 0;
  // The new process hears the held stops at its start.
  if (!holders_.empty()) holders_since_ = now;
  if (estop_) estop_since_ = now;
  if (pause_) pause_since_ = now;
  estop_heard_ = pause_heard_ = false;
}

std::optional<Party> ReferenceModel::controlling_operator() const {
  switch (ctl_) {
    case Ctl::a: return Party::a;
    case Ctl::b: return Party::b;
    case Ctl::j: return Party::j;
    case Ctl::c: return Party::c;
    default: return std::nullopt;
  }
}

// Rule: a controller silent for longer than the controller timeout loses
// control (and the drive stops); a command older than the command timeout is
// no longer in effect (control is kept). Inside the margin either holds.
void ReferenceModel::advance_to(Ms now) {
  for (const bool estop : {true, false}) {
    const bool pressed = estop ? estop_ : pause_;
    bool& heard_of = estop ? estop_heard_ : pause_heard_;
    const Ms heard_by = (estop ? estop_since_ : pause_since_) + t_.platform_deadline;
    if (pressed && !heard_of && now >= heard_by) {
      heard_of = true;
      emergency_began(heard_by, 0);
    }
  }
  if (shutdown_) return;
  if (const auto op = controlling_operator()) {
    const Ms lost_by = heard_[static_cast<int>(*op)] + t_.controller_timeout + t_.margin;
    if (now > lost_by) {
      ctl_ = Ctl::none;
      disarm(lost_by);
    }
  }
  if (command_) {
    const Ms stale_by = command_->at + t_.command_timeout + t_.margin;
    if (now > stale_by) disarm(stale_by);
  }
  if (c_controls_vector_) {
    const Ms lost_by = c_heard_vector_ + t_.controller_timeout + t_.margin;
    if (now > lost_by) {
      c_controls_vector_ = false;
      end_driver_motion(lost_by);
    }
  }
}

void ReferenceModel::disarm(Ms due) {
  if (command_) {
    lingering_ = command_->percent;
    lingering_any_ = false;
    lingering_until_ = due;
    command_.reset();
    zero_due_ = due;
  } else {
    zero_due_ = std::min(zero_due_, due);
  }
}

// Rule: the vector driver's motion ends on every stop of its own or of the
// primitive driver, and it gives the primitive driver back; nothing but C's
// new Set Local Vector starts it again.
void ReferenceModel::end_driver_motion(Ms due) {
  if (!driver_motion_ && ctl_ != Ctl::driver) return;
  if (ctl_ == Ctl::driver) {
    if (driver_motion_) {
      lingering_any_ = true;
      lingering_until_ = due;
      zero_due_ = due;
    }
    ctl_ = Ctl::none;  // released, within driver_settle
  }
  driver_motion_ = false;
  driver_settle_until_ = std::max(driver_settle_until_, due + t_.driver_settle);
}

void ReferenceModel::emergency_began(Ms now, Ms deadline) {
  disarm(now + deadline);
  end_driver_motion(now + deadline);
}

void ReferenceModel::emergency_may_have_ended(Ms now) {
  if (!emergency()) unsettled_until_ = now + t_.settle;
}

bool ReferenceModel::certainly_ready(Ms now) const {
  const auto s = expected_states(now);
  return s.size() == 1 && s.front() == PdState::ready;
}

PdState ReferenceModel::effective_state(Ms now, PdState observed) const {
  const auto s = expected_states(now);
  return s.size() == 1 ? s.front() : observed;
}

// ---- events -------------------------------------------------------------------

void ReferenceModel::heard(Party p, Ms now) { heard_[static_cast<int>(p)] = now; }

// Rule (RA arbitration): uncontrolled, a request at or above the component's
// own authority is granted; the controller may change its authority; another
// requester takes control only with a higher authority, and the drive stops.
void ReferenceModel::request_control(Party p, std::uint8_t authority, Ms now) {
  heard(p, now);
  if (shutdown_) return;
  const Ctl me = ctl_of(p);
  if (ctl_ == Ctl::none) {
    if (authority >= own_authority_) {
      ctl_ = me;
      ctl_authority_ = authority;
    }
    return;
  }
  if (ctl_ == me) {
    ctl_authority_ = authority;
    return;
  }
  if (authority > ctl_authority_) {
    const Ctl previous = ctl_;
    ctl_ = me;
    ctl_authority_ = authority;
    disarm(now + t_.stop_deadline);
    if (previous == Ctl::driver) {
      // Rejected: its motion ends (it no longer holds the primitive driver).
      driver_motion_ = false;
      lingering_any_ = true;
      lingering_until_ = now + t_.stop_deadline;
    }
  }
}

void ReferenceModel::release_control(Party p, Ms now) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p)) return;
  ctl_ = Ctl::none;
  disarm(now + t_.stop_deadline);
}

// Rule: only the controller's Set Wrench Effort, in Ready, drives; it is in
// effect until the next stop (or the command timeout).
void ReferenceModel::effort(Party p, double percent, Ms now, PdState observed) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p)) return;
  if (effective_state(now, observed) != PdState::ready) return;
  if (command_ && command_->percent != percent) {
    lingering_ = command_->percent;
    lingering_any_ = false;
    lingering_until_ = now + t_.stop_deadline;
  }
  command_ = Command{percent, certainly_ready(now), now};
}

// Rule: each sender of Set Emergency holds it until it clears it (or the
// local clear); the vehicle's moving components share one latch.
void ReferenceModel::set_emergency(Party p, Target to, Ms now) {
  if (to == Target::primitive_driver) heard(p, now);
  else if (p == Party::c) c_heard_by_vector(now);  // any message from its controller keeps it
  if (to == Target::primitive_driver && shutdown_) return;  // a shut-down component answers nothing
  const bool was = emergency();
  if (holders_.empty()) holders_since_ = now;
  holders_.insert(p);
  if (!was) emergency_began(now, t_.stop_deadline);
}

void ReferenceModel::clear_emergency(Party p, Target to, Ms now) {
  if (to == Target::primitive_driver) heard(p, now);
  else if (p == Party::c) c_heard_by_vector(now);
  if (to == Target::primitive_driver && shutdown_) return;
  if (holders_.erase(p) == 0) return;
  if (holders_.empty()) {
    holders_since_ = kNever;
    emergency_may_have_ended(now);
  }
}

// Rule: Standby from anyone (it only stops), acted on in Ready; Resume from
// the controller only, and nothing moves until its new command.
void ReferenceModel::standby(Party p, Ms now, PdState observed) {
  heard(p, now);
  if (shutdown_ || effective_state(now, observed) != PdState::ready) return;
  standby_ = true;
  standby_since_ = now;
  disarm(now + t_.stop_deadline);
  end_driver_motion(now + t_.stop_deadline);
}

void ReferenceModel::resume(Party p, Ms now, PdState observed) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p) || effective_state(now, observed) != PdState::standby) return;
  standby_ = false;
  standby_since_ = kNever;
}

// RA Set Component Authority (the controller's): the component's own
// authority. JSS Set Authority (AS5710) is the controlling client's own
// authority, i.e. the controller's request at a new authority.
void ReferenceModel::set_authority(Party p, std::uint8_t authority, Ms now) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p)) return;
  if (p == Party::j) ctl_authority_ = authority;
  else own_authority_ = authority;
}

void ReferenceModel::shutdown(Party p, Ms now) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p)) return;
  shutdown_ = true;
  shutdown_since_ = now;
  standby_ = false;
  ctl_ = Ctl::none;
  disarm(now + t_.stop_deadline);
  end_driver_motion(now + t_.stop_deadline);
}

bool ReferenceModel::emergency_before_press(bool estop) const {
  return !holders_.empty() || (estop ? pause_ : estop_);
}

// Rule: Reset (the controller's) re-initialises: Standby forgotten, the
// drive stopped, control kept, Ready again (or Emergency, still held).
void ReferenceModel::reset(Party p, Ms now) {
  heard(p, now);
  if (shutdown_ || ctl_ != ctl_of(p)) return;
  standby_ = false;
  standby_since_ = kNever;
  disarm(now + t_.stop_deadline);
  end_driver_motion(now + t_.stop_deadline);
  unsettled_until_ = std::max(unsettled_until_, now + t_.settle);
}

// Rule: the platform's own stop holds every component on it until the
// platform releases it; jausd commands zero once it hears of it (its safety
// status, 50 Hz: surely within platform_deadline). With
// every_platform_stop_ends_the_command (the default) a stop of one status
// period or longer, released before jausd reports it, still ends the command
// in effect; without it the model lets what was commanded before it go on
// (what jausd did at 10 Hz: the platform dropped the setpoint, the bridge's
// periodic setpoint brought it back until command_timeout_s).
void ReferenceModel::platform_input(bool estop, bool on, Ms now) {
  bool& flag = estop ? estop_ : pause_;
  bool& heard_of = estop ? estop_heard_ : pause_heard_;
  Ms& since = estop ? estop_since_ : pause_since_;
  if (on == flag) return;
  if (on) {
    flag = true;
    heard_of = false;
    since = now;
    if (t_.every_platform_stop_ends_the_command && !emergency_before_press(estop)) emergency_began(now, t_.platform_deadline);
    // Heard at some point in the window: the vector driver (on the platform) stops and gives control back.
    if (driver_motion_) driver_settle_until_ = std::max(driver_settle_until_, now + t_.platform_deadline + t_.driver_settle);
    return;  // advance_to() makes it a stop once jausd surely heard of it
  }
  flag = false;
  since = kNever;
  if (!heard_of) {
    // Perhaps heard: the vector driver may have stopped and given the primitive driver back.
    driver_settle_until_ = std::max(driver_settle_until_, now + t_.driver_settle);
    unsettled_until_ = std::max(unsettled_until_, now + t_.settle);
  }
  heard_of = false;
  emergency_may_have_ended(now);
}

void ReferenceModel::local_clear(Ms now) {
  if (holders_.empty()) return;
  holders_.clear();
  holders_since_ = kNever;
  emergency_may_have_ended(now);
}

void ReferenceModel::c_takes_vector(Ms now) {
  c_controls_vector_ = true;  // its own authority (1) is below C's (5), and only C asks for it
  c_heard_vector_ = now;
}

void ReferenceModel::c_releases_vector(Ms now) {
  if (!c_controls_vector_) return;
  c_controls_vector_ = false;
  end_driver_motion(now + t_.stop_deadline);
}

void ReferenceModel::c_heard_by_vector(Ms now) {
  if (c_controls_vector_) c_heard_vector_ = now;
}

void ReferenceModel::c_drives_vector(Ms now, bool vector_ready) {
  c_heard_by_vector(now);
  if (!vector_ready || !c_controls_vector_) return;  // Set Local Vector: its controller's, in Ready
  driver_motion_ = true;
  if (shutdown_ || ctl_ == Ctl::driver) return;
  // The driver asks with its own authority, 1: the RA's arbitration as for
  // anyone (an operator below it is taken over; see driver_authority_cap()).
  constexpr std::uint8_t kDriverAuthority = 1;
  const bool granted = ctl_ == Ctl::none ? own_authority_ <= kDriverAuthority : kDriverAuthority > ctl_authority_;
  if (granted) {
    if (ctl_ != Ctl::none) disarm(now + t_.stop_deadline);  // taken over: the operator's command ends
    ctl_ = Ctl::driver;
    ctl_authority_ = kDriverAuthority;
    driver_settle_until_ = now + t_.driver_settle;
    return;
  }
  driver_motion_ = false;  // refused: held by an operator at or above it, or its own authority is above it
}

// ---- what the node must show ---------------------------------------------------

std::vector<Ctl> ReferenceModel::allowed_controllers(Ms now) const {
  std::vector<Ctl> v{ctl_};
  const auto add = [&v](Ctl c) {
    if (std::find(v.begin(), v.end(), c) == v.end()) v.push_back(c);
  };
  if (const auto op = controlling_operator(); op && !shutdown_)
    if (now - heard_[static_cast<int>(*op)] > t_.controller_timeout - t_.margin) add(Ctl::none);
  if (now < driver_settle_until_) {
    add(Ctl::driver);
    add(Ctl::none);
  }
  return v;
}

void ReferenceModel::sync_controller(Ctl observed, Ms now) {
  if (observed == ctl_) return;
  if (observed == Ctl::driver) {
    ctl_ = Ctl::driver;  // not yet given back
    ctl_authority_ = 1;
    return;
  }
  if (observed != Ctl::none) return;  // not allowed: the runner reports it
  if (ctl_ == Ctl::driver) {
    if (driver_motion_) end_driver_motion(now + t_.stop_deadline);
    ctl_ = Ctl::none;
    return;
  }
  ctl_ = Ctl::none;  // a silent controller, dropped inside the margin
  disarm(now + t_.stop_deadline);
}

std::vector<bool> ReferenceModel::allowed_vector_controlled(Ms now) const {
  if (!c_controls_vector_) return {false};
  if (now - c_heard_vector_ > t_.controller_timeout - t_.margin) return {true, false};
  return {true};
}

void ReferenceModel::sync_vector_controlled(bool observed, Ms now) {
  if (observed || !c_controls_vector_) return;
  c_controls_vector_ = false;
  end_driver_motion(now + t_.stop_deadline);
}

std::vector<PdState> ReferenceModel::expected_states(Ms now) const {
  if (shutdown_) return {PdState::shutdown};
  const PdState base = standby_ ? PdState::standby : PdState::ready;
  if (!holders_.empty()) return {PdState::emergency};
  if (estop_ || pause_) {
    const bool heard_of = (estop_ && now >= estop_since_ + t_.platform_deadline) ||
                          (pause_ && now >= pause_since_ + t_.platform_deadline);
    if (heard_of) return {PdState::emergency};
    return {PdState::emergency, base, PdState::initialize};
  }
  if (now < unsettled_until_) return {PdState::emergency, base, PdState::initialize};
  return {base};
}

std::string ReferenceModel::zero_required(Ms now) const {
  const Ms d = t_.stop_deadline;
  if (shutdown_ && now >= shutdown_since_ + d) return "the primitive driver is shut down";
  if (!holders_.empty() && now >= holders_since_ + d) {
    std::string who;
    for (const Party p : holders_) who += std::string(who.empty() ? "" : ", ") + name(p);
    return "Set Emergency held by " + who;
  }
  if (estop_ && now >= estop_since_ + t_.platform_deadline) return "the platform's e-stop is pressed";
  if (pause_ && now >= pause_since_ + t_.platform_deadline) return "the platform's pause is on";
  if (standby_ && now >= standby_since_ + d) return "Standby";
  const bool driver_active = driver_motion_ && ctl_ == Ctl::driver;
  if (!command_ && !driver_active && now >= zero_due_)
    return ctl_ == Ctl::none ? "nobody controls the primitive driver"
                             : std::string("no command from its controller (") + name(ctl_) + ") since the last stop";
  return {};
}

bool ReferenceModel::allows_drive(double percent, Ms now) const {
  if (!zero_required(now).empty()) return false;
  const auto near = [percent](double v) { return std::abs(v - percent) <= 1.5; };
  if (command_ && near(command_->percent)) return true;
  if (driver_motion_ && ctl_ == Ctl::driver) return true;  // the vector driver's own efforts
  if (now < lingering_until_ && (lingering_any_ || (lingering_ && near(*lingering_)))) return true;
  return false;
}

std::string ReferenceModel::describe(Ms now) const {
  std::ostringstream o;
  o << "controller " << name(ctl_);
  if (ctl_ != Ctl::none) o << " (authority " << int{ctl_authority_} << ")";
  o << ", own authority " << int{own_authority_} << ", holders {";
  bool first = true;
  for (const Party p : holders_) {
    o << (first ? "" : ",") << name(p);
    first = false;
  }
  o << "}" << (estop_ ? ", e-stop" : "") << (pause_ ? ", pause" : "") << (standby_ ? ", Standby" : "")
    << (shutdown_ ? ", Shutdown" : "");
  if (command_) o << ", command " << command_->percent << "% at " << command_->at;
  o << (driver_motion_ ? ", vector driver driving" : "") << (c_controls_vector_ ? ", C controls the vector driver" : "");
  const auto z = zero_required(now);
  if (!z.empty()) o << "; zero required: " << z;
  return o.str();
}

}  // namespace jaus::model
